#!/usr/bin/python3
"""A seed measured by `seedcarve measure`: one ok row, the volume within TOLERANCE (relative) of
the reference, and the seed's files. The reference is the true volume of the shape `seedcarve
render` drew into RENDER_DIR (its truth.json), or a number in mm^3.
    check_seed_outputs.py RENDER_DIR|VOLUME_MM3 MEASURE_DIR SEED_ID TOLERANCE
"""
import csv
import json
import sys
from pathlib import Path

reference, measure, seed, tolerance = sys.argv[1], Path(sys.argv[2]), sys.argv[3], float(sys.argv[4])
try:
    truth = float(reference)
except ValueError:
    truth = json.loads((Path(reference) / "truth.json").read_text())["volume_mm3"]
lines = [l for l in (measure / "results.csv").read_text().splitlines() if not l.startswith("#")]
rows = list(csv.DictReader(lines))
assert len(rows) == 1, rows
row = rows[0]
assert row["status"] == "ok", row
volume = float(row["volume_mm3"])
error = volume / truth - 1
print(f"{seed}: {volume:.4f} mm^3 against {truth:.4f} mm^3 ({100 * error:+.3f}%)")
assert abs(error) <= tolerance, f"error {error:+.4%} beyond {tolerance:.2%}"
folder = measure / seed
record = json.loads((folder / "seed.json").read_text())
assert abs(record["volume_mm3"] - volume) <= 1e-5 * volume
assert (folder / "overlays.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
if row["method"] == "carving":
    ply = (folder / "surface.ply").read_bytes()
    assert ply.startswith(b"ply\nformat binary_little_endian 1.0\n"), ply[:60]
    assert float(row["surface_mm2"]) > 0
voxels = folder / "voxels.h5"
if voxels.exists():  # carving.voxels_h5: the occupancy fractions hold the same volume (coarser grid: 0.5%)
    import h5py
    with h5py.File(voxels, "r") as f:
        occupancy = f["occupancy"]
        nz, ny, nx = (int(x) for x in occupancy.attrs["shape_zyx"].split())
        assert occupancy.shape == (nz * ny, nx), occupancy.shape
        voxel_volume = float(occupancy.attrs["voxel_mm"]) ** 3 * occupancy[:].sum()
    print(f"voxels.h5: {voxel_volume:.4f} mm^3")
    assert abs(voxel_volume / volume - 1) <= 0.005, voxel_volume
