#!/usr/bin/python3
"""Chart and table of run_granular_collapse.sh: the runout (L_inf - L0)/L0 of the deposit (98% of
the soil behind its front), of the front where the deposit is 3% of H0 thick and of the farthest
particle over the aspect ratio a, per resolution, against the experiments' fit (Lube et al. 2005:
1.2 a below a = 2.3, 1.9 a^(2/3) above) and the band the test allows (2/3 to 4/3 of the fit);
and how much each measure moves each time h halves.
    plot_granular_collapse.py CSV PNG
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

rows = list(csv.DictReader(open(sys.argv[1])))
by_h = defaultdict(dict)
for r in rows:
    by_h[float(r["spacing_mm"])][float(r["a"])] = r
spacings = sorted(by_h, reverse=True)
ratios = sorted({float(r["a"]) for r in rows})

print("| a | h (mm) | cells per H0 | deposit runout (98%) | 3% of H0 thick | farthest particle | fit (band) | H_inf/H0 "
      "| at rest | wall s |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for a in ratios:
    for h in spacings:
        r = by_h[h].get(a)
        if not r:
            continue
        inside = float(r["band_lo"]) <= float(r["runout_deposit"]) <= float(r["band_hi"])
        print(f"| {a:g} | {h:g} | {float(r['H0_m']) / (h / 1000):.0f} | {float(r['runout_deposit']):.2f}"
              f"{'' if inside else ' (outside)'} | {float(r['runout_thin']):.2f} | {float(r['runout_farthest']):.2f} | "
              f"{float(r['fit']):.2f} "
              f"({float(r['band_lo']):.2f}-{float(r['band_hi']):.2f}) | {float(r['H_inf_over_H0']):.2f} | "
              f"{'yes' if r['at_rest'] == '1' else 'no'} | {float(r['wall_s']):.1f} |")
for coarse, fine in zip(spacings, spacings[1:]):
    print()
    print(f"Change from h = {coarse:g} mm to {fine:g} mm (fine / coarse - 1):")
    print()
    for a in ratios:
        c, f = by_h[coarse].get(a), by_h[fine].get(a)
        if c and f:
            moved = {k: float(f[k]) / float(c[k]) - 1 for k in ("runout_deposit", "runout_thin", "runout_farthest")}
            print(f"- a = {a:g}: deposit (98%) {moved['runout_deposit']:+.1%}, 3% of H0 thick "
                  f"{moved['runout_thin']:+.1%}, farthest particle {moved['runout_farthest']:+.1%}")

fig, ax = plt.subplots(figsize=(7, 4.5))
a_line = np.linspace(0.3, 7, 200)
fit = np.where(a_line < 2.3, 1.2 * a_line, 1.9 * a_line ** (2 / 3))
ax.plot(a_line, fit, "k-", label="Lube et al. 2005 fit")
ax.fill_between(a_line, 2 / 3 * fit, 4 / 3 * fit, color="0.85", label="test band (2/3 to 4/3 of the fit)")
markers = dict(zip(spacings, "o^s"))
for h in spacings:
    a = [x for x in ratios if x in by_h[h]]
    ax.plot(a, [float(by_h[h][x]["runout_deposit"]) for x in a], markers.get(h, "^") + "-",
            label=f"deposit (98% behind), h = {h:g} mm")
    ax.plot(a, [float(by_h[h][x]["runout_farthest"]) for x in a], markers.get(h, "^") + ":", mfc="none",
            label=f"farthest particle, h = {h:g} mm")
ax.set_xlabel("aspect ratio a = H0 / L0")
ax.set_ylabel("runout (L_inf - L0) / L0")
ax.set_title("Granular column collapse, friction 30 deg, rough floor, soil.flip 0.99")
ax.legend(fontsize=7)
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
