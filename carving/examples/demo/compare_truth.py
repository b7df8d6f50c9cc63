#!/usr/bin/python3
"""The demo batch's measured volumes beside the true ones: OUT/batch/accuracy.csv and a table.
Synthetic seeds have their rendered shape's exact volume (images/<id>/truth.json); the real grain
has the original program's carving of its own masks (25.40 mm^3 at fine grids), not a physical
measurement.
    compare_truth.py OUT_DIR
"""
import csv
import json
import sys
from pathlib import Path

KSTATE_REFERENCE_MM3 = 25.40

out = Path(sys.argv[1])
lines = [l for l in (out / "batch" / "results.csv").read_text().splitlines() if not l.startswith("#")]
rows = list(csv.DictReader(lines))
table = []
for row in rows:
    truth_file = out / "images" / row["id"] / "truth.json"
    if truth_file.exists():
        reference, source = json.loads(truth_file.read_text())["volume_mm3"], "rendered shape"
    elif row["id"] == "kstate_wheat":
        reference, source = KSTATE_REFERENCE_MM3, "original program, own masks"
    else:
        reference, source = None, ""
    volume = float(row["volume_mm3"]) if row["status"] == "ok" else None
    error = f"{100 * (volume / reference - 1):+.2f}" if volume and reference else ""
    table.append({"id": row["id"], "method": row["method"], "status": row["status"],
                  "volume_mm3": f"{volume:.4f}" if volume else "", "reference_mm3": f"{reference:.4f}" if reference else "",
                  "error_percent": error, "reference": source,
                  "message": row["message"]})
with open(out / "batch" / "accuracy.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(table[0].keys()))
    w.writeheader()
    w.writerows(table)
print(f"{'seed':16} {'method':8} {'status':7} {'volume mm^3':>12} {'reference':>10} {'error %':>8}")
for t in table:
    print(f"{t['id']:16} {t['method']:8} {t['status']:7} {t['volume_mm3']:>12} {t['reference_mm3']:>10} "
          f"{t['error_percent']:>8}  {t['message'][:60]}")
