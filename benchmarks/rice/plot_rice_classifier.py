#!/usr/bin/python3
"""Chart of the rice ASV classifier benchmark: held-out accuracy against the training grains per
grade (median and range over the repeats) for three classes and six grades, random forest, SVM and
the convolutional network;
and the time to train (train_and_evaluate: validation choice, final fit, 5-fold cross-validation)
and to predict one grain. Prints the medians it plots.
With BLEND P (the sets rendered with `riceasv render --blend P`), the best accuracy a classifier can
expect is marked: 1 - P/3 for three classes, 1 - 5P/6 for the six grades (blend_ceiling in
rice/render/render_set.hpp).
usage: plot_rice_classifier.py CSV PNG [BLEND]"""
import csv
import statistics
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

with open(sys.argv[1]) as f:
    rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
runs = defaultdict(list)
for r in rows:
    runs[(r["scheme"], r["model"], int(r["dishes_per_grade"]))].append(r)

fig, (ax_acc, ax_time) = plt.subplots(1, 2, figsize=(15, 5.2))
styles = {("three", "rtrees"): ("C0", "-", "three classes, random forest"),
          ("three", "svm"): ("C0", "--", "three classes, SVM"),
          ("grades", "rtrees"): ("C3", "-", "six grades, random forest"),
          ("grades", "svm"): ("C3", "--", "six grades, SVM"),
          ("three", "cnn"): ("C2", "-.", "three classes, CNN"),
          ("grades", "cnn"): ("C1", "-.", "six grades, CNN")}
print("scheme  model   dishes/grade  grains/grade  held-out accuracy median [min, max]   train+evaluate s   "
      "predict us/grain")
for (scheme, model), (colour, ls, label) in styles.items():
    sizes = sorted(n for (s, m, n) in runs if s == scheme and m == model)
    x, med, lo, hi, t_train, t_fit, t_pred = [], [], [], [], [], [], []
    for n in sizes:
        rs = runs[(scheme, model, n)]
        acc = [float(r["held_out_accuracy"]) for r in rs]
        per_grade = statistics.median(int(r["train_grains"]) for r in rs) / 6
        x.append(per_grade)
        med.append(100 * statistics.median(acc)), lo.append(100 * min(acc)), hi.append(100 * max(acc))
        t_train.append(statistics.median(float(r["train_evaluate_s"]) for r in rs))
        t_fit.append(statistics.median(float(r["fit_s"]) for r in rs))
        t_pred.append(statistics.median(float(r["predict_s_per_grain"]) for r in rs))
        print(f"{scheme:7s} {model:7s} {n:12d}  {per_grade:12.1f}  {med[-1]:6.1f}% [{lo[-1]:.1f}, {hi[-1]:.1f}]"
              f"   {t_train[-1]:16.3f}   {1e6 * t_pred[-1]:8.2f}")
    ax_acc.plot(x, med, ls, marker="o", color=colour, label=label)
    ax_acc.fill_between(x, lo, hi, color=colour, alpha=0.12)
    ax_time.loglog(x, t_train, ls, marker="o", color=colour, label=f"{label}: train + evaluate")
    if model == "rtrees" and scheme == "three":
        ax_time.loglog(x, t_fit, ":", marker="s", color="k", label="three classes, random forest: one fit")
    ax_time.loglog(x, [1e3 * t for t in t_pred], ls, marker="^", color=colour, alpha=0.5,
                   label=f"{label}: predict, ms per 1000 grains")
blend = float(sys.argv[3]) if len(sys.argv) > 3 else 0.0
if blend > 0:
    for ceiling, colour, label in ((1 - blend / 3, "C0", "three classes"), (1 - 5 * blend / 6, "C3", "six grades")):
        ax_acc.axhline(100 * ceiling, color=colour, lw=1.2, ls=(0, (1, 3)))
        ax_acc.text(x[-1], 100 * ceiling - 1.8, f"best expected, {label}: {100 * ceiling:.0f}%", fontsize=7,
                    ha="right", color=colour)
    print(f"blend {blend}: best expected accuracy {100 * (1 - blend / 3):.1f}% (three classes), "
          f"{100 * (1 - 5 * blend / 6):.1f}% (grades)")
ax_acc.axhline(85, color="k", lw=0.8, ls=":")
ax_acc.text(x[0], 85.5, "dissertation: 85% on real photographs", fontsize=8)
ax_acc.set_xlabel("training grains per grade (ok grains of the chosen dishes)")
ax_acc.set_ylabel("held-out accuracy, % of ok grains")
ax_acc.set_title("accuracy on a held-out rendered set (other seed, other pixel size)"
                 + (f"\n{100 * blend:.0f}% of grains drawn like a neighbouring grade" if blend > 0 else ""))
ax_acc.legend(fontsize=8, loc="lower right")
ax_time.set_xlabel("training grains per grade")
ax_time.set_ylabel("seconds (one core)")
ax_time.set_title("time to train and to predict")
ax_time.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
for ax in (ax_acc, ax_time):
    ax.grid(True, which="both", alpha=0.3)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
