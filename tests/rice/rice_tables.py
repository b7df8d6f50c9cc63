"""What the rice checks share: reading the suite's CSV tables (`#` lines are comments) and scoring
classified grains against the rendered truth."""
import csv
from collections import Counter
from pathlib import Path


def table(path):
    return list(csv.DictReader(l for l in Path(path).read_text().splitlines() if not l.startswith("#")))


def class_accuracy(ok, truth_csv, names, label, share_name="share"):
    """The share of the `ok` classified rows (image, grain, class, share) whose class is their
    photograph's grade in `truth_csv` (grades 2-3, 4-5, 6-7 -> names[0], [1], [2]); prints each
    wrong grain and the right ones per class, `label` before each class."""
    grade_of = {r["image"]: int(r["grade"]) for r in table(truth_csv)}
    right, per_class = Counter(), Counter()
    for r in ok:
        truth = names[(grade_of[Path(r["image"]).name] - 2) // 2]
        per_class[truth] += 1
        right[truth] += r["class"] == truth
        if r["class"] != truth:
            print(f"wrong: {r['image']} grain {r['grain']}: {r['class']} ({share_name} {r['share']}), truth {truth}")
    for k in names:
        print(f"{label} {k:6s}: {right[k]}/{per_class[k]}")
    return sum(right.values()) / len(ok) if ok else 0
