#!/usr/bin/python3
"""The tables of run_wet_soil.sh, from each run's run.json.
    wet_soil.py WORK_DIR H STEPS LONG_H LONG_END "RANKS..." CONFIG...
        (WORK_DIR holds counts-WET-ROWS-rRANKS/, short-WET-ROWS-REPEAT/ and long-WET-ROWS-REPEAT/;
        a CONFIG is WET:ROWS, decomposition.balance_wet_soil and decomposition.drag_rows)
First table: per rank count and configuration, the coupled nodes the busiest rank owned a step
(mean over the steps; it assembles their rows) and those whose rows it solved, against the mean
rank, CG iterations, halo traffic a step, and the imbalances at the last load check. Second
table: 2 ranks, medians over the repeats (all of them in brackets) of the grid solve phase and
the step (s, the slowest rank's), and the busiest rank's drag seconds (rows, the assembly's
exchange, Krylov), for the short and the long run.
"""
import json
import statistics
import sys
from pathlib import Path


def load(run):
    r = json.loads((run / "run.json").read_text())
    if r.get("status") != "completed" and not str(r.get("status", "")).startswith("stopped"):
        sys.exit(f"{run}: the run did not finish ({r.get('status')})")
    return r


def spread(values, digits):
    return f"{statistics.median(values):.{digits}f} ({', '.join(f'{v:.{digits}f}' for v in values)})"


def main():
    work, h, steps, long_h, long_end, ranks = Path(sys.argv[1]), *sys.argv[2:7]
    configs = [c.split(":") for c in sys.argv[7:]]
    print(f"Counts, h = {h}, first {steps} steps (the coupled nodes: the mean over the steps of the busiest "
          "rank's and of the mean rank's):")
    print()
    print("| ranks | wet soil balanced | rows | coupled nodes owned, busiest rank / mean | solved, busiest "
          "| CG iterations | halo MB a step | halo messages a step | particles' imbalance | wet soil's imbalance |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for n in ranks.split():
        for wet, rows in configs:
            r = load(work / f"counts-{wet}-{rows}-r{n}")
            c, s, d = r["drag_coupled_nodes_per_rank"], r["drag_solved_nodes_per_rank"], r.get("decomposition", {})
            wet_imbalance = d.get("wet_soil_imbalance_at_last_check")
            print(f"| {n} | {wet} | {rows} | {c['max']:.0f} / {c['mean']:.1f} ({c['max'] / c['mean']:.2f}) "
                  f"| {s['max']:.0f} | {r['drag_ksp_max_iterations']} | {d.get('halo_bytes_per_step', 0) / 1e6:.3f} "
                  f"| {d.get('halo_messages_per_step', 0):.0f} | {d.get('imbalance_at_last_check', 1):.4f} "
                  f"| {'-' if wet_imbalance is None else f'{wet_imbalance:.4f}'} |")
    print()
    print("2 ranks, medians of the interleaved repeats (each in brackets), seconds of the slowest rank:")
    print()
    print("| run | wet soil balanced | rows | grid solve phase | step | drag rows | drag exchange | drag Krylov "
          "| CG iterations | coupled nodes, busiest / mean |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for kind, label in (("short", f"h = {h}, {steps} steps"), ("long", f"h = {long_h}, 0 to {long_end} s")):
        for wet, rows in configs:
            runs = [load(p) for p in sorted(work.glob(f"{kind}-{wet}-{rows}-*")) if p.name.split("-")[-1].isdigit()]
            if not runs:
                continue
            phase = lambda name: spread([r["phases"][name]["max_s"] for r in runs], 3)
            drag = lambda part: spread([r["drag_seconds_per_rank"][part]["max"] for r in runs], 3)
            c = runs[0]["drag_coupled_nodes_per_rank"]
            print(f"| {label} | {wet} | {rows} | {phase('step/grid solve')} | {phase('step')} | {drag('rows')} "
                  f"| {drag('exchange')} | {drag('krylov')} | {runs[0]['drag_ksp_max_iterations']} "
                  f"| {c['max']:.0f} / {c['mean']:.1f} |")


if __name__ == "__main__":
    main()
