#!/usr/bin/python3
"""The rice demo's held-out batch: each ok grain's class (CLASSIFY_DIR/classes.csv) against the grade
its photograph was rendered with (RENDER_DIR/truth.csv), as a confusion-matrix chart
(CLASSIFY_DIR/confusion_held_out.png) and the accuracy per class on stdout.
    confusion_held_out.py RENDER_DIR CLASSIFY_DIR
"""
import csv
import json
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def table(path):
    return list(csv.DictReader(l for l in Path(path).read_text().splitlines() if not l.startswith("#")))


rendered, classified = Path(sys.argv[1]), Path(sys.argv[2])
record = json.loads((classified / "classify.json").read_text())
names = record["classes"]
if names != ["low", "medium", "high"]:
    sys.exit(f"confusion_held_out.py: classes {names}; the demo trains low / medium / high")
grade_of = {r["image"]: int(r["grade"]) for r in table(rendered / "truth.csv")}
rows = table(classified / "classes.csv")
ok = [r for r in rows if r["status"] == "ok"]
matrix = np.zeros((3, 3), dtype=int)
for r in ok:
    matrix[(grade_of[Path(r["image"]).name] - 2) // 2, names.index(r["class"])] += 1

fig, ax = plt.subplots(figsize=(4.6, 4))
ax.imshow(matrix, cmap="Blues")
for i in range(3):
    for j in range(3):
        ax.text(j, i, matrix[i, j], ha="center", va="center", color="white" if matrix[i, j] > matrix.max() / 2 else "k")
ax.set_xticks(range(3), names)
ax.set_yticks(range(3), [f"{n}\n(grades {2 + 2 * k}-{3 + 2 * k})" for k, n in enumerate(names)])
ax.set_xlabel("predicted class")
ax.set_ylabel("rendered grade")
accuracy = np.trace(matrix) / max(matrix.sum(), 1)
ax.set_title(f"held-out batch, {record['model_type']}: {accuracy:.0%} of {matrix.sum()} ok grains\n"
             f"({sum(r['status'] == 'flagged' for r in rows)} flagged grains not counted)", fontsize=9)
fig.tight_layout()
fig.savefig(classified / "confusion_held_out.png", dpi=120)
for k, n in enumerate(names):
    print(f"[rice demo] held-out {n:6s}: {matrix[k, k]}/{matrix[k].sum()}")
print(f"[rice demo] held-out accuracy ({record['model_type']}) {accuracy:.1%} of {matrix.sum()} ok grains; chart "
      f"{classified / 'confusion_held_out.png'}")
