#!/usr/bin/python3
"""run_threads.sh's report: medians per build and RANKSxTHREADS configuration of the step phase
and of each phase in it (run.json, the slowest rank's), the speedup over the same build's 1x1 and,
with a baseline build, the current build's time over the baseline's (the median of the repeats'
ratios: each repeat ran both builds back to back).
    threads.py CSV            (Markdown to standard output)
"""
import csv
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mpm_metrics import STEP_PHASES, CHECKS, slug  # noqa: E402


def main(path):
    rows = list(csv.DictReader(open(path)))
    builds = list(dict.fromkeys(r["build"] for r in rows))
    configs = list(dict.fromkeys(r["config"] for r in rows))
    runs = {}  # (build, config) -> {repeat: row}
    for r in rows:
        runs.setdefault((r["build"], r["config"]), {})[r["repeat"]] = r
    med = lambda build, config, col: statistics.median(float(r[col]) for r in runs[(build, config)].values())

    def paired(a, b, col="step_s"):
        """Median over the repeats of a's column over b's."""
        ra, rb = runs[a], runs[b]
        return statistics.median(float(ra[k][col]) / float(rb[k][col]) for k in ra if k in rb)

    steps = {c: int(next(iter(runs[(builds[0], c)].values()))["steps"]) for c in configs}
    particles = float(next(iter(runs[(builds[0], configs[0])].values()))["particles_mean"])
    print(f"{len(next(iter(runs.values())))} repeats; {particles:,.0f} particles (mean over the run).")
    print()
    print("| build | ranks x threads | step phase (s), median | ms per step | speedup over 1x1 | efficiency |")
    print("| --- | --- | --- | --- | --- | --- |")
    for b in builds:
        for c in configs:
            ranks, threads = map(int, c.split("x"))
            s = med(b, c, "step_s")
            speedup = 1 / paired((b, c), (b, "1x1")) if (b, "1x1") in runs else float("nan")
            print(f"| {b} | {c} | {s:.3f} | {1e3 * s / steps[c]:.2f} | {speedup:.2f}x | {speedup / (ranks * threads):.0%} |")
    if "baseline" in builds:
        print()
        print("Current over baseline (median of the repeats' ratios; below 1: the current build is faster):")
        print()
        print("| ranks x threads | step | " + " | ".join(STEP_PHASES_SHOWN) + " |")
        print("| --- " * (2 + len(STEP_PHASES_SHOWN)) + "|")
        for c in configs:
            cells = [f"{paired(('current', c), ('baseline', c)):.2f}"]
            for p in STEP_PHASES_SHOWN:
                col = f"ph_{slug(p)}_max"
                have = all(runs[(b, c)][k][col] for b in ("current", "baseline") for k in runs[(b, c)])
                cells.append(f"{paired(('current', c), ('baseline', c), col):.2f}" if have else "-")
            print(f"| {c} | " + " | ".join(cells) + " |")
    print()
    print("Seconds per phase over the run, medians (the slowest rank's; ranks wait inside the halo phases):")
    print()
    shown = [p for p in STEP_PHASES + CHECKS
             if any(r[f"ph_{slug(p)}_max"] and float(r[f"ph_{slug(p)}_max"]) > 0 for r in rows)]
    print("| phase | " + " | ".join(f"{b} {c}" for b in builds for c in configs) + " |")
    print("| --- " * (1 + len(builds) * len(configs)) + "|")
    for p in shown:
        col = f"ph_{slug(p)}_max"
        cells = []
        for b in builds:
            for c in configs:
                vals = [float(r[col]) for r in runs[(b, c)].values() if r[col]]
                cells.append(f"{statistics.median(vals):.3f}" if vals else "-")
        print(f"| {p} | " + " | ".join(cells) + " |")


STEP_PHASES_SHOWN = ["grid", "stresses", "p2g water", "p2g soil", "g2p water", "g2p soil", "outflow"]

if __name__ == "__main__":
    main(sys.argv[1])
