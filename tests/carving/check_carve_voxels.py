#!/usr/bin/python3
"""`seedcarve carve --out` against the Kansas State program's rule, computed here independently
with numpy from the file alone (data/kstate_wheat_36view/README.md and carving/io/carve_input.hpp):
voxel (ix, iy, iz) is tested at ((i + 3/2) size/n - size/2) mm per axis, projected with P, rounded
to the nearest pixel (floor(q + 1/2)), and kept where its initial byte is 1 and every view's mask
is non-zero there (outside a mask: carved). Output byte iy + ny (ix + nx iz), as the original writes.
Checked on the file as given (25,234 voxels) and with its first half of initial bytes cleared
(iz < nz/2; the original program keeps 11,509): voxels.raw must equal the expected bytes exactly,
and voxels.h5's /occupancy the same bytes.
    check_carve_voxels.py SEEDCARVE CARVE_INPUT.dat WORK_DIR"""
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

seedcarve, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
work.mkdir(parents=True, exist_ok=True)
data = bytearray(source.read_bytes())


def parse(buf):
    at = 0

    def take(dtype, count):
        nonlocal at
        a = np.frombuffer(buf, dtype=dtype, count=count, offset=at)
        at += a.nbytes
        return a

    n = take("<i4", 3)
    initial = take("u1", int(n.prod())).copy()
    views = []
    for _ in range(int(take("<i4", 1)[0])):
        P = take("<f8", 12).reshape(4, 3).T  # column-major 3 x 4
        w, h = take("<i4", 2)
        mask = take("u1", int(w * h)).reshape(w, h)  # x-major: mask[x, y]
        views.append((P, mask))
    box = take("<f8", 3)
    return n, initial, views, box


def expected(buf):
    n, initial, views, box = parse(buf)
    d = box / n
    axes = [(np.arange(n[a]) + 1.5) * d[a] - box[a] / 2 for a in range(3)]
    z, x, y = np.meshgrid(axes[2], axes[0], axes[1], indexing="ij")  # y fastest, then x, then z
    points = np.stack([x.ravel(), y.ravel(), z.ravel(), np.ones(x.size)])
    keep = initial.astype(bool)
    for P, mask in views:
        q = P @ points
        u = np.floor(q[0] / q[2] + 0.5).astype(np.int64)
        v = np.floor(q[1] / q[2] + 0.5).astype(np.int64)
        inside = (u >= 0) & (u < mask.shape[0]) & (v >= 0) & (v < mask.shape[1])
        hit = np.zeros(keep.shape, bool)
        hit[inside] = mask[u[inside], v[inside]] != 0
        keep &= hit
    return keep.astype(np.uint8)


failed = False
half = bytearray(data)
nz_cells = int(np.frombuffer(data, "<i4", 3).prod())
half[12:12 + nz_cells // 2] = bytes(nz_cells // 2)
for name, buf in (("as given", data), ("first half cleared", half)):
    path = work / f"{name.replace(' ', '_')}.dat"
    path.write_bytes(buf)
    out = work / f"{name.replace(' ', '_')}_out"
    printed = subprocess.run([seedcarve, "carve", str(path), "--out", str(out), "--log-level", "warn"], check=True,
                             capture_output=True, text=True).stdout.split()
    want = expected(bytes(buf))
    got = np.frombuffer((out / "voxels.raw").read_bytes(), np.uint8)
    with h5py.File(out / "voxels.h5") as f:
        h5 = f["occupancy"][...].ravel()
    same = got.shape == want.shape and bool((got == want).all())
    print(f"{'ok  ' if same else 'FAIL'}  {name}: {int(got.sum())} voxels kept, expected {int(want.sum())} "
          f"({int((got != want).sum()) if got.shape == want.shape else 'shape'} bytes differ); printed {printed[0]}")
    failed |= not same or int(printed[0]) != int(want.sum())
    h5_same = h5.shape == got.shape and bool((h5 == got).all())
    print(f"{'ok  ' if h5_same else 'FAIL'}  {name}: voxels.h5 holds the same bytes")
    failed |= not h5_same
sys.exit(1 if failed else 0)
