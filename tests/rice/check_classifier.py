#!/usr/bin/python3
"""`riceasv train` and `riceasv classify` end to end: the model's evaluation must add up (the test
and pooled k-fold confusion matrices sum to the test and the usable grains, JSON and CSV agree, k
folds give k accuracies, the flagged grains of the measurement are the ones excluded), and its
classes on a held-out set rendered with another seed must be right for more than MIN_ACCURACY of
the ok grains (each grain's true class is its photograph's grade in the held-out truth.csv).
Prints the held-out accuracy per class and overall.
    check_classifier.py MODEL_DIR CLASSIFY_DIR HELD_OUT_RENDER_DIR MIN_ACCURACY
"""
import csv
import json
import sys
from collections import Counter
from pathlib import Path

from rice_tables import class_accuracy, table



def matrix(path):
    rows = list(csv.reader(Path(path).read_text().splitlines()))
    return [[int(x) for x in r[1:]] for r in rows[1:]]


model, classified, held_out, minimum = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3]), float(sys.argv[4])
failures = []
check = lambda ok, what: ok or failures.append(what)

e = json.loads((model / "evaluation.json").read_text())
m = json.loads((model / "model.json").read_text())
names = m["classes"]["names"]
check(names == ["low", "medium", "high"], f"classes {names}")
g = e["grains"]
total = lambda mat: sum(map(sum, mat))
check(total(e["test"]["confusion"]) == g["test"], f"test matrix sums to {total(e['test']['confusion'])}, not {g['test']}")
check(total(matrix(model / "confusion_test.csv")) == g["test"], "confusion_test.csv disagrees with evaluation.json")
cv = e["cross_validation"]
check(len(cv["fold_accuracy"]) == cv["folds"], f"{len(cv['fold_accuracy'])} fold accuracies for {cv['folds']} folds")
check(total(cv["pooled"]["confusion"]) == g["used"], f"k-fold matrix sums to {total(cv['pooled']['confusion'])}, "
      f"not the {g['used']} usable grains")
check(matrix(model / "confusion_cv.csv") == cv["pooled"]["confusion"], "confusion_cv.csv disagrees with evaluation.json")
check(g["train"] + g["validation"] + g["test"] == g["used"], "split does not add up to the usable grains")
measured = Counter(r["status"] for r in table(model / "measured" / "results.csv"))
check(g["excluded_flagged"] == measured["flagged"] > 0, f"{g['excluded_flagged']} grains excluded, "
      f"{measured['flagged']} flagged in measured/results.csv (the training set has touching pairs)")
check(g["used"] == measured["ok"], f"{g['used']} grains used, {measured['ok']} ok")
samples = Counter(r["set"] for r in table(model / "samples.csv"))
check(samples["excluded"] == g["excluded_flagged"] and samples["test"] == g["test"], f"samples.csv sets {dict(samples)}")
check((model / "confusion.png").stat().st_size > 1000, "confusion.png missing")

rows = table(classified / "classes.csv")
ok = [r for r in rows if r["status"] == "ok"]
check(any(r["status"] == "flagged" for r in rows), "the held-out set's touching and cut grains are not flagged")
summary = json.loads((classified / "classify.json").read_text())
check(sum(summary["counts"].values()) == len(ok), "classify.json counts do not sum to the ok grains")
accuracy = class_accuracy(ok, held_out / "truth.csv", names, "held-out")
print(f"held-out accuracy {accuracy:.1%} of {len(ok)} ok grains (minimum {minimum:.0%}); training: test split "
      f"{e['test']['accuracy']:.1%} of {g['test']}, {cv['folds']}-fold {cv['pooled']['accuracy']:.1%} of {g['used']}")
check(accuracy > minimum, f"held-out accuracy {accuracy:.1%} not above {minimum:.0%}")
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
