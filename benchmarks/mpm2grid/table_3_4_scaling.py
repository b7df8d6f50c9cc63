#!/usr/bin/python3
"""Table, projection and chart of run_table_3_4_scaling.sh. Prints Markdown.
    table_3_4_scaling.py table_3_4_scaling.csv table_3_4_scaling.png

Per rank count (medians over repeats): seconds per step (the step phase on the slowest rank),
ns per particle-step per core (x ranks), particles at the start and the end and the inlet's
growth per step, halo and migration bytes per step, the peak RSS of the largest rank and the
bytes per particle (RSS summed over the ranks over the particles at the end). The strong-scaling
speedup is the median over repeats of T1 / TP of the same repeat (the runs alternate).

Against the dissertation: example 2's published row (Table 3.4): 50 hours on one PC for
475,429 particles (197,542 water + 277,887 soil) and 2185 "iterations". It publishes neither the
simulated duration nor the time step, and the iterations are most likely output frames, so a
step of ours cannot be set beside an iteration of its. The like-for-like figure is a whole run
against a whole run: the wall time of the scene's 20 s at the published particle count. This
script projects the steps that takes from the run's mean time step and the least wall time
from the starting particle count (the count grows with the inflow, so the real run takes longer).

Projection to P ranks (stated model, surface to volume of the partition):
  T(P) = T1 / P + c * H(P),
with H(P) the halo bytes one rank exchanges per step and c the seconds per halo byte measured on
2 ranks, c = (T2 - T1 / 2) / H(2), H(2) = halo_bytes_per_step(2 ranks) / 2. All of the 2-rank
overhead (halo packing and messages, ghost-node P2G, imbalance, migration) is charged to the halo,
so the projection is pessimistic where latency is low and ignores latency (neighbour count). H(P)
follows the cut length of a rank's part of the material: the material covers A = N s^2 (s the
particle spacing, N particles) over an x extent LX (21.75 m, the dam's downstream toe), a mean
height A / LX; the 2-rank partition cuts it once across (L(2) = A / LX), a rank inside a strip
of P slabs has 2 such cuts, and a rank inside a grid of squares of side sqrt(A / P) has 4 sides;
METIS takes the shorter: L(P) = min(2 A / LX, 4 sqrt(A / P)). H(P) = H(2) * L(P) / L(2).
"""
import csv
import math
import statistics
import sys

import matplotlib

from mpm_metrics import CHECKS, STEP_PHASES, slug

matplotlib.use("Agg")
import matplotlib.pyplot as plt

DISSERTATION_HOURS = 50
DISSERTATION_PARTICLES = 197542 + 277887
SCENE_SECONDS = 20  # the end time of our example 2 scene
LX = 21.75
INFLOW_Q = 14.5  # m^2/s per metre, the scene's inlet (7.25 m x 2 m/s)

rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["status"] == "completed"]
by_ranks = {}
for r in rows:
    by_ranks.setdefault(int(r["ranks"]), []).append(r)
med = lambda rs, f: statistics.median(float(r[f]) for r in rs if r[f] != "")
spacing = rows[0]["spacing"]
h = float(spacing.split()[0]) * {"m": 1, "mm": 1e-3, "cm": 1e-2}[spacing.split()[1] if " " in spacing else "m"]
s = h / 2  # particles_per_cell 2 in the scene

print(f"Example 2 at grid.spacing = {spacing} (particle spacing {s:g} m), {rows[0]['end_time_s']} s simulated "
      f"(about {rows[0]['steps']} steps), every step limited by the water's wave speed.")
print()
print("| ranks | repeats | steps | particles start -> end | s per step (median, min-max) | ns per particle-step per core | "
      "speedup | efficiency | halo bytes/step | migration bytes/step | rebalances | peak RSS largest rank (MB) | bytes per particle |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
T = {}
speedup = {}
for p, rs in sorted(by_ranks.items()):
    sp = [float(r["s_per_step"]) for r in rs]
    T[p] = statistics.median(sp)
    if p > 1 and 1 in by_ranks:
        one = {r["repeat"]: float(r["s_per_step"]) for r in by_ranks[1]}
        q = [one[r["repeat"]] / float(r["s_per_step"]) for r in rs if r["repeat"] in one]
        speedup[p] = statistics.median(q) if q else float("nan")
    rss = med(rs, "rss_max_kb") if all(r["rss_max_kb"] for r in rs) else float("nan")
    rss_sum = med(rs, "rss_sum_kb") if all(r["rss_sum_kb"] for r in rs) else float("nan")
    n_end = med(rs, "particles_last")
    halo = med(rs, "halo_bytes_per_step") if rs[0]["halo_bytes_per_step"] else None
    mig = med(rs, "migration_bytes_per_step") if rs[0]["migration_bytes_per_step"] else None
    reb = rs[0]["rebalances"] or "-"
    su = f"{speedup[p]:.2f}x" if p in speedup else "1"
    eff = f"{100 * speedup[p] / p:.0f}%" if p in speedup else "-"
    print(f"| {p} | {len(rs)} | {rs[0]['steps']} | {int(med(rs, 'particles_first'))} -> {int(n_end)} | "
          f"{T[p]:.3f} ({min(sp):.3f}-{max(sp):.3f}) | {p * med(rs, 'ns_per_particle_step'):.0f} | {su} | {eff} | "
          f"{'-' if halo is None else f'{halo / 1e6:.2f} MB'} | {'-' if mig is None else f'{mig / 1e3:.1f} kB'} | {reb} | "
          f"{rss / 1024:.0f} | {rss_sum * 1024 / n_end:.0f} |")
print()
one = by_ranks.get(1)
if one:
    n0, n1, steps, t_end = med(one, "particles_first"), med(one, "particles_last"), med(one, "steps"), med(one, "end_time")
    print(f"- Inlet: {n1 - n0:.0f} particles added in {steps:.0f} steps ({(n1 - n0) / steps:.1f} per step, "
          f"{(n1 - n0) / t_end:.0f} per simulated s; q / s^2 = {INFLOW_Q / s ** 2:.0f} per s expected). "
          f"Over the scene's 20 s the inflow alone adds {20 * INFLOW_Q / s ** 2 / 1e6:.2f} M particles (less what has left "
          "through the outlet: at 0.25 m the count grows 3.4x by 20 s), so the per-step cost grows with it: compare runs "
          "in ns per particle-step.")
    per_step = T[1]
    full_steps = SCENE_SECONDS / (t_end / steps)
    print(f"- Against the dissertation (example 2: {DISSERTATION_HOURS} h on one PC for {DISSERTATION_PARTICLES} "
          f"particles; simulated duration and time step not published): our scene's {SCENE_SECONDS} s take about "
          f"{full_steps:,.0f} steps at this run's mean dt ({t_end / steps:.3g} s), so at least "
          f"{full_steps * per_step / 3600:.1f} h on one core at {per_step:.3f} s per step; the particle count grows "
          "with the inflow, so the whole run takes longer and has not been timed. A step is not compared with one "
          "of the dissertation's iterations (most likely output frames).")
    if 2 in speedup:
        print(f"- Strong scaling 1 -> 2 ranks: {speedup[2]:.2f}x, {50 * speedup[2]:.0f}% efficiency (goal >= 85%).")

# Where the time goes: per phase of the step and the two per-step checks, ms per step (median over
# repeats) as the mean over the ranks, the largest rank's, and the mean part blocked in MPI calls.
breakdown = {}  # ranks -> [(phase, mean ms per step)]
if any(rows[0].get(f"ph_{slug(p)}_mean") for p in STEP_PHASES):
    print()
    print("Where a step's time goes (run.json's step phases, solvers/mpm2grid/model/step_timers.hpp): ms per step, "
          "mean over the ranks / largest rank / of the mean the part blocked in MPI calls (waiting for messages and "
          "for other ranks in reductions); medians over repeats.")
    print()
    counts = sorted(by_ranks)
    print("| phase | " + " | ".join(f"{p} rank{'s' if p > 1 else ''}: mean / max / wait" for p in counts) + " |")
    print("| --- |" + " --- |" * len(counts))
    for ph in STEP_PHASES + CHECKS:
        cells, seen = [], False
        for p in counts:
            rs = [r for r in by_ranks[p] if r.get(f"ph_{slug(ph)}_mean")]
            if not rs:
                cells.append("-")
                continue
            seen = True
            per = lambda f: 1e3 * statistics.median(float(r[f"ph_{slug(ph)}_{f}"]) / float(r["steps"]) for r in rs)
            breakdown.setdefault(p, []).append((ph, per("mean")))
            cells.append(f"{per('mean'):.2f} / {per('max'):.2f} / {per('wait'):.2f}")
        if seen:
            print(f"| {ph} | " + " | ".join(cells) + " |")

# The projection.
proj = []
if 1 in T and 2 in T and by_ranks[2][0]["halo_bytes_per_step"]:
    H2 = med(by_ranks[2], "halo_bytes_per_step") / 2
    c = max(0.0, T[2] - T[1] / 2) / H2
    N = med(by_ranks[1], "particles_mean")
    A = N * s * s
    Hm = A / LX

    def cut(P):
        if P == 2:
            return Hm
        return min(2 * Hm, 4 * math.sqrt(A / P))

    print()
    print(f"Projection (model in table_3_4_scaling.py): T(P) = T1/P + c H(P), c = {c * 1e9:.2f} ns per halo byte "
          f"from the 2-rank run, H(2) = {H2 / 1e6:.2f} MB per rank and step; material {A:.1f} m^2 over {LX} m "
          f"(mean height {Hm:.2f} m): slabs up to P = {int(4 * A / Hm ** 2)}, squares beyond.")
    print()
    print("| ranks | halo per rank and step | s per step | speedup | efficiency |")
    print("| --- | --- | --- | --- | --- |")
    for P in (2, 4, 8, 16, 32, 64, 128):
        HP = H2 * cut(P) / cut(2)
        TP = T[1] / P + c * HP
        proj.append((P, TP))
        print(f"| {P} | {HP / 1e6:.2f} MB | {TP:.4f} | {T[1] / TP:.1f}x | {100 * T[1] / TP / P:.0f}% |")

fig, axes = plt.subplots(1, 3 if breakdown else 2, figsize=(16 if breakdown else 11, 4.2))
ax = axes[0]
for p, rs in sorted(by_ranks.items()):
    ax.plot([p] * len(rs), [float(r["s_per_step"]) for r in rs], "o", color="tab:blue", alpha=0.5)
ax.plot(sorted(T), [T[p] for p in sorted(T)], "o-", color="tab:blue", label="measured (median)")
if proj:
    ax.plot([p for p, _ in proj], [t for _, t in proj], "s--", color="tab:orange", label="projection (surface/volume)")
ranks = sorted(set(list(T) + [p for p, _ in proj]))
ax.plot(ranks, [T[1] / p for p in ranks], ":", color="0.4", label="ideal")
ax.set_xscale("log", base=2)
ax.set_yscale("log")
ax.set_xlabel("ranks")
ax.set_ylabel("s per step")
ax.legend(fontsize=7)
ax.grid(True, which="both", alpha=0.3)
ax = axes[1]
if proj:
    ax.plot([p for p, _ in proj], [100 * T[1] / t / p for p, t in proj], "s--", color="tab:orange", label="projection")
for p in speedup:
    ax.plot(p, 100 * speedup[p] / p, "o", color="tab:blue", label=f"measured {p} ranks")
ax.axhline(85, color="r", ls="--", lw=0.8, label="goal 85%")
ax.set_xscale("log", base=2)
ax.set_ylim(0, 110)
ax.set_xlabel("ranks")
ax.set_ylabel("parallel efficiency (%)")
ax.legend(fontsize=7)
ax.grid(True, which="both", alpha=0.3)
if breakdown:
    ax = axes[2]
    counts = sorted(breakdown)
    names = [ph for ph in STEP_PHASES + CHECKS if any(ph == n for p in counts for n, _ in breakdown[p])]
    cmap = plt.get_cmap("tab20")
    bottom = [0.0] * len(counts)
    for k, ph in enumerate(names):
        # core-ms per step: mean per rank times the ranks, so perfect scaling keeps a bar's height
        vals = [p * dict(breakdown[p]).get(ph, 0.0) for p in counts]
        ax.bar([str(p) for p in counts], vals, bottom=bottom, color=cmap(k % 20), label=ph)
        bottom = [b + v for b, v in zip(bottom, vals)]
    ax.set_xlabel("ranks")
    ax.set_ylabel("core-ms per step (mean per rank x ranks)")
    ax.legend(fontsize=6, ncol=2)
    ax.grid(True, axis="y", alpha=0.3)
fig.suptitle(f"Table 3.4 example 2, grid.spacing {spacing}: strong scaling", fontsize=9)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
