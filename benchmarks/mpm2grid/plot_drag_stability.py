#!/usr/bin/python3
"""Table and chart of run_drag_stability.sh: per drag scheme and conductivity, the largest dt that
ran to its end and the smallest that blew up, against the theory 2 tau_d = 2 rho_red / c_E with
c_E = n^2 rho_w g / k and rho_red = rho_s rho_w / (rho_s + rho_w) (the scene's soil and water:
n = 0.4, rho_s = 2000, rho_w = 1000 kg/m^3, g = 9.81 m/s^2). Prints Markdown.
    plot_drag_stability.py drag_stability.csv drag_stability.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

N, RHO_S, RHO_W, G = 0.4, 2000.0, 1000.0, 9.81
RHO_RED = RHO_S * RHO_W / (RHO_S + RHO_W)
c_e = lambda k: N * N * RHO_W * G / k
rows = [r for r in csv.DictReader(open(sys.argv[1]))]
schemes = sorted({r["drag"] for r in rows})
ks = sorted({float(r["conductivity_m_s"]) for r in rows}, reverse=True)
# The wave-speed cap: the largest step any completed run took. A run that blew up is placed at
# min(dt_max, cap): the dt its blow-up line names is already shortened by the runaway velocities.
cap = max(float(r["dt_largest"]) for r in rows if r["exit"] == "0" and r["dt_largest"])
for r in rows:
    r["dt_s"] = r["dt_largest"] if r["exit"] == "0" and r["dt_largest"] else f"{min(float(r['dt_max_s']), cap):.6g}"


def stats(drag, k):
    rs = [r for r in rows if r["drag"] == drag and float(r["conductivity_m_s"]) == k]
    ok = [float(r["dt_s"]) for r in rs if r["exit"] == "0"]
    bad = [float(r["dt_s"]) for r in rs if r["exit"] != "0"]
    return (max(ok) if ok else None), (min(bad) if bad else None), rs


steps = round(float(rows[0]["end_s"]) / float(rows[0]["dt_max_s"]))
print(f"A run is stable when it reaches its end (time.end = {steps} x dt_max); dt is the largest step "
      f"actually taken (the wave-speed limits cap it at {cap:.3g} s here); a run that blew up "
      "counts at min(dt_max, cap).")
print()
print("| k (m/s) | c_E (kg/m^3/s) | theory 2 tau_d (s) | " +
      " | ".join(f"{d}: largest stable dt | {d}: smallest unstable dt | {d}: stable / theory" for d in schemes) + " |")
print("| --- | --- | --- | " + " | ".join("--- | --- | ---" for _ in schemes) + " |")
for k in ks:
    theory = 2 * RHO_RED / c_e(k)
    cells = []
    for d in schemes:
        ok, bad, _ = stats(d, k)
        cells += [f"{ok:.3g}" if ok else "none", f"{bad:.3g}" if bad else f"none up to {cap:.3g}",
                  f"{ok / theory:.2g}" if ok else "-"]
    print(f"| {k:g} | {c_e(k):.3g} | {theory:.3g} | " + " | ".join(cells) + " |")

fig, ax = plt.subplots(figsize=(7, 4.8))
colors = {"explicit": "tab:red", "lumped": "tab:blue", "consistent": "tab:green"}
offset = {d: 1 + 0.06 * i for i, d in enumerate(schemes)}
for d in schemes:
    col = colors.get(d, "k")
    ok = [(c_e(float(r["conductivity_m_s"])) * offset[d], float(r["dt_s"])) for r in rows
          if r["drag"] == d and r["exit"] == "0"]
    bad = [(c_e(float(r["conductivity_m_s"])) * offset[d], float(r["dt_s"])) for r in rows
           if r["drag"] == d and r["exit"] != "0"]
    if ok:
        ax.scatter(*zip(*ok), marker="o", s=14, color=col, alpha=0.5, label=f"{d}: ran to the end")
    if bad:
        ax.scatter(*zip(*bad), marker="x", s=22, color=col, label=f"{d}: blew up")
    best = [(c_e(k), stats(d, k)[0]) for k in ks if stats(d, k)[0]]
    if best:
        ax.plot(*zip(*best), "-", color=col, lw=1.5, label=f"{d}: largest stable dt")
xs = [c_e(k) for k in ks]
ax.plot(xs, [2 * RHO_RED / x for x in xs], "k--", lw=1, label="theory 2 tau_d = 2 rho_red / c_E")
ax.axhline(cap, color="0.5", ls=":", lw=1, label="wave-speed (CFL) cap of dt")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("drag coefficient c_E = n^2 rho_w g / k (kg m^-3 s^-1)")
ax.set_ylabel("time step dt (s)")
ax.set_title("mpm2grid: water column against a soil block, stability of the drag coupling", fontsize=9)
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
