#!/usr/bin/python3
"""The tables of run_drag_solver.sh, from each run's run.json.
    drag_solver.py WORK_DIR H STEPS LONG_H LONG_END "PCS" RANKS...
        (WORK_DIR holds iterations-PC-ROWS-rRANKS/, short-PC-REPEAT/ and long-PC-REPEAT/)
First table: per preconditioner, the most CG iterations a velocity component took in a step, per
rank count, with the solve's rows on the nodes' owners (owners) and in equal shares (balanced),
and the coupled nodes the busiest rank held in the solve against the mean. Second table: one
rank's grid solve phase and step (s), medians over the repeats (all of them in brackets), for the
short and the long run, with the long run's iterations.
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


def times(work, kind, pc):
    runs = [load(r) for r in sorted(work.glob(f"{kind}-{pc}-*")) if r.is_dir() and r.name.split("-")[-1].isdigit()]
    if not runs:
        return "-", "-", "-"
    solve = [r["phases"]["step/grid solve"]["max_s"] for r in runs]
    step = [r["phases"]["step"]["max_s"] for r in runs]
    fmt = lambda v: f"{statistics.median(v):.3f} ({', '.join(f'{x:.3f}' for x in v)})"
    return fmt(solve), fmt(step), str(runs[0]["drag_ksp_max_iterations"])


def main():
    work, h, steps, long_h, long_end, pcs = Path(sys.argv[1]), *sys.argv[2:7]
    ranks = sys.argv[7:]
    pcs = pcs.split()
    columns = [(n, rows) for n in ranks for rows in ("owners", "balanced") if not (n == "1" and rows == "balanced")]
    print(f"CG iterations (the most a component took in a step), h = {h}, first {steps} steps; "
          "in brackets the coupled nodes whose rows the busiest rank held, over the mean:")
    print()
    print("| preconditioner | " + " | ".join("1 rank" if n == "1" else f"{n} ranks, {rows}" for n, rows in columns) + " |")
    print("| --- | " + " | ".join("---" for _ in columns) + " |")
    for pc in pcs:
        cells = []
        for n, rows in columns:
            run = work / f"iterations-{pc}-{rows}-r{n}"
            if not run.is_dir():
                cells.append("-")
                continue
            r = load(run)
            solved = r.get("drag_solved_nodes_per_rank", {})
            share = f" ({solved['max']:.0f} / {solved['mean']:.0f})" if solved and n != "1" else ""
            cells.append(f"{r['drag_ksp_max_iterations']}{share}")
        print(f"| {pc} | " + " | ".join(cells) + " |")
    print()
    print(f"One rank: the grid solve phase and the step (s), medians (every repeat); short: h = {h}, "
          f"{steps} steps; long: h = {long_h}, 0 to {long_end} s:")
    print()
    print("| preconditioner | short: grid solve | short: step | long: grid solve | long: step | long: iterations |")
    print("| --- | --- | --- | --- | --- | --- |")
    for pc in pcs:
        short_solve, short_step, _ = times(work, "short", pc)
        long_solve, long_step, long_its = times(work, "long", pc)
        print(f"| {pc} | {short_solve} | {short_step} | {long_solve} | {long_step} | {long_its} |")


if __name__ == "__main__":
    main()
