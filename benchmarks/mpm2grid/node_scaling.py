#!/usr/bin/python3
"""Table and chart of run_node_scaling.sh (strong scaling on one many-core node). Prints Markdown.
    node_scaling.py CSV PNG LABEL=RUNS_DIR...   the runs' rows into CSV (mpm_metrics.py columns),
                                                then the report
    node_scaling.py CSV PNG                     the report from a CSV written before

LABEL names one session on a node (a lease: `lease1`), RUNS_DIR is run_node_scaling.sh's OUT_DIR
(runs CASE-rRANKS-REPEAT, CASE-rRANKS-MODE-REPEAT, CASE-rRANKStTHREADS-REPEAT, ceiling copies
CASE-copyI, machine.txt). The rows of other labels already in CSV are kept (a lease's runs are
gone with its node; the CSV is their record).

Runs with threads inside the ranks (HYBRID in run_node_scaling.sh) get a table of their own per
case: ranks x threads, the speedup over the same fastest one-rank run, the efficiency per core
(speedup / (ranks x threads)), and the step's mean rank split into compute, waiting in MPI and the
rest of the communication, beside the same lease's one thread per rank on as many cores.

Per case and rank count: the step phase on the slowest rank (run.json phases.step.max_s, median
over repeats), the speedup T1 / TP with T1 the fastest one-rank run (a slow one-rank run cannot
inflate a speedup: the first run on a fresh node ran 1.6x slower than the next, lease 1),
efficiency = speedup / P, halo bytes and messages per step,
rebalances and their seconds. The node's ceiling (the copies, all at once, one per core): the
lone one-rank run's step time over the mean copy's (what shared memory bandwidth and caches
allow) and over the slowest copy's (what P ranks of equal shares, who wait for each other every
step, can reach when one core is that slow). The breakdown at the largest rank count, seconds
over the run averaged over the ranks: compute (the phases with no MPI: grid, stresses, both
P2G and G2P, grid solve, boundary, inlet), its slowest rank over the mean (per phase, summed),
waiting in MPI (every phase's wait), the balancing, and the rest of the communication phases
(packing, unpacking, the migration's lookups), set beside one rank's compute over P.
"""
import csv
import math
import re
import statistics
import sys
from pathlib import Path

import matplotlib

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mpm_metrics import (COLUMNS, COMM_PHASES as COMM, COMPUTE_PHASES as COMPUTE, STEP_PHASES,  # noqa: E402
                         metrics, phase_sum)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CASES = {"ex2": "Table 3.4 example 2, h = 0.025 m", "ex2fine": "example 2, h = 0.0125 m",
         "ex2consistent": "example 2, h = 0.025 m, consistent drag",
         "ex2balanced": "example 2, h = 0.025 m, consistent drag, the solve's rows in equal shares",
         "ex2owners": "example 2, h = 0.025 m, consistent drag, the owners' rows in the solve",
         "ex2dry": "example 2, h = 0.025 m, consistent drag, the particle counts alone and the owners' rows",
         "ex2jacobi": "example 2, h = 0.025 m, consistent drag, point Jacobi (the preconditioner before SOR)",
         "3d": "two_species_3d, h = 5 mm"}
# A case run at the largest rank count only: its one-rank run is another case's (the same run).
BASELINE = {"ex2balanced": "ex2consistent", "ex2owners": "ex2consistent", "ex2dry": "ex2consistent"}
RUN = re.compile(r"^(?P<case>[a-z0-9]+)-r(?P<ranks>\d+)(t(?P<threads>\d+))?(-(?P<mode>equal|measured))?-(?P<repeat>\d+)$")
COPY = re.compile(r"^(?P<case>[a-z0-9]+)-copy(?P<copy>\d+)$")
HEAD = ["lease", "case", "kind", "mode", "repeat", "copy", "threads"] + COLUMNS


def rank_spreads(row):
    """Per rank (run.json's per_rank, mpm_metrics.py's rank_* columns): whether the slowest rank had
    more work or was slower over the same work, as a sentence; empty for runs from before."""
    if not row.get("rank_compute_spread"):
        return ""
    return (f" Per rank, compute over the run: the slowest {float(row['rank_compute_spread']):.2f}x the mean, "
            f"particle-steps {float(row['rank_work_spread']):.3f}x, compute per particle-step "
            f"{float(row['rank_cost_spread']):.2f}x; that rank is the slowest in "
            f"{100 * float(row['rank_slowest_same']):.0f}% of the compute phases.{off_core(row)}")


def copies_off_core(rows):
    """How long the ceiling's copies were off their cores (the CPU clock), as a sentence; empty for runs
    from before it."""
    if not rows or not all(r.get("rank_off_core") for r in rows):
        return ""
    off = [float(r["rank_off_core"]) for r in rows]
    slowest = max(rows, key=lambda r: num(r, "step_s"))
    return (f" The copies were off their cores {100 * min(off):.1f}-{100 * max(off):.1f}% of their compute's wall "
            f"time, the slowest copy {100 * float(slowest['rank_off_core']):.1f}%.")


def off_core(row):
    """The CPU clock's part of rank_spreads' sentence; empty for runs from before it."""
    if not row.get("rank_cpu_spread"):
        return ""
    return (f" On the CPU clock the slowest rank's compute is {float(row['rank_cpu_spread']):.2f}x the mean; the ranks "
            f"were off their cores {100 * float(row['rank_off_core']):.1f}% of their compute's wall time, the slowest "
            f"rank {100 * float(row['rank_off_core_slowest']):.1f}%.")


def coupled_share(row):
    """The consistent drag's coupled nodes on the rank with the most against the mean (the solve's
    work per rank), as a sentence; empty for runs without them (or from before they were counted)."""
    mean, most = row.get("drag_coupled_nodes_rank_mean"), row.get("drag_coupled_nodes_rank_max")
    if not mean or not most or float(mean) == 0:
        return ""
    solved = row.get("drag_solved_nodes_rank_max")
    rows = (f"; the solve's rows of {float(solved):.0f} on the busiest rank there"
            if solved and float(solved) != float(most) else "")
    seconds = ""
    if row.get("drag_rows_s_max"):
        pair = lambda k: f"{float(row[f'drag_{k}_s_max']):.3g} / {float(row[f'drag_{k}_s_mean']):.3g} s"
        seconds = (f" Its seconds, most / mean over the ranks: computing the rows {pair('rows')}, the assembly's "
                   f"exchange (waits included) {pair('exchange')}, the Krylov solves {pair('krylov')}.")
    return (f" The drag solve's coupled nodes: {float(most):.0f} on the busiest rank against {float(mean):.0f} "
            f"on average ({float(most) / float(mean):.1f}x){rows}.{seconds}")


def collect(label, runs_dir):
    rows = []
    for d in sorted(p for p in Path(runs_dir).iterdir() if p.is_dir()):
        m, c = RUN.match(d.name), COPY.match(d.name)
        if not (m or c):
            continue
        row = {k: "" if v is None else str(v) for k, v in metrics(str(d)).items()}
        row.update(lease=label, case=(m or c)["case"], kind="run" if m else "copy",
                   mode=(m["mode"] or "equal") if m else "", repeat=m["repeat"] if m else "",
                   copy=c["copy"] if c else "", threads=(m["threads"] or "1") if m else "1")
        rows.append(row)
    machine = Path(runs_dir) / "machine.txt"
    return rows, machine.read_text().strip() if machine.exists() else ""


def num(row, key):
    v = row.get(key, "")
    return float(v) if v not in ("", None) else math.nan


def report(rows, machines, png):
    out = []
    leases = list(dict.fromkeys(r["lease"] for r in rows))
    curves = {}
    for lease in leases:
        out.append(f"### {lease}")
        out.append("")
        if machines.get(lease):
            out.append("Node: " + machines[lease].replace("\n", "; ") + ".")
            out.append("")
        mine = [r for r in rows if r["lease"] == lease]
        for case in [c for c in CASES if any(r["case"] == c for r in mine)]:
            runs = [r for r in mine if r["case"] == case and r["kind"] == "run" and r["mode"] == "equal"
                    and r["status"] == "completed" and r.get("threads", "1") in ("", "1")]
            hybrid = [r for r in mine if r["case"] == case and r["kind"] == "run" and r["mode"] == "equal"
                      and r["status"] == "completed" and r.get("threads", "1") not in ("", "1")]
            base = [r for r in mine if r["case"] == BASELINE.get(case, case) and r["kind"] == "run"
                    and r["mode"] == "equal" and r["status"] == "completed" and r.get("threads", "1") in ("", "1")]
            ones = {r["repeat"]: num(r, "step_s") for r in base if r["ranks"] == "1"}
            if not ones:
                continue
            runs = [r for r in base if r["ranks"] == "1"] + [r for r in runs if r["ranks"] != "1"]
            t1 = min(ones.values())
            steps = statistics.median(num(r, "steps") for r in runs)
            particles = statistics.median(num(r, "particles_mean") for r in runs)
            out.append(f"**{CASES[case]}** ({particles / 1e3:.0f}k particles, {steps:.0f} steps; one rank "
                       f"{t1 / steps * 1e3:.1f} ms per step, {t1 / steps / particles * 1e9:.0f} ns per particle-step)")
            out.append("")
            out.append("| ranks | runs | step phase (s) | speedup | efficiency | halo MB / step | messages / step "
                       "| rebalances (s) |")
            out.append("| --- | --- | --- | --- | --- | --- | --- | --- |")
            ranks = sorted({int(r["ranks"]) for r in runs})
            for p in ranks:
                mine_p = [r for r in runs if int(r["ranks"]) == p]
                tp = t1 if p == 1 else statistics.median(num(r, "step_s") for r in mine_p)
                s = t1 / tp
                halo = statistics.median(num(r, "halo_bytes_per_step") for r in mine_p) if p > 1 else 0
                msgs = statistics.median(num(r, "halo_messages_per_step") for r in mine_p) if p > 1 else 0
                reb = statistics.median(num(r, "rebalances") for r in mine_p) if p > 1 else 0
                bal = statistics.median(num(r, "ph_balance_max") for r in mine_p) if p > 1 else 0
                times = ", ".join(f"{num(r, 'step_s'):.3g}" for r in mine_p)
                out.append(f"| {p} | {len(mine_p)} | {tp:.3g} ({times}) | {s:.2f}x | {100 * s / p:.0f}% | "
                           f"{halo / 1e6:.2f} | {msgs:.0f} | {reb:.0f} ({bal:.2f}) |")
                if case == "ex2":
                    curves.setdefault(lease, []).append((p, s))
                    fast = min(mine_p, key=lambda r: num(r, "step_s"))
                    steps_p = num(fast, "steps")
                    parts = curves.setdefault(f"{lease} breakdown", {})
                    parts[p] = [phase_sum(fast, COMPUTE, "mean") / steps_p,
                                phase_sum(fast, STEP_PHASES, "wait") / steps_p,
                                (phase_sum(fast, COMM, "mean") - phase_sum(fast, COMM, "wait")) / steps_p,
                                phase_sum(fast, ["balance"], "mean") / steps_p]
            copy_rows = [r for r in mine if r["case"] == case and r["kind"] == "copy" and r["status"] == "completed"]
            copies = [num(r, "step_s") for r in copy_rows]
            if copies:
                mean_c, worst_c = statistics.mean(copies), max(copies)
                out.append("")
                out.append(f"Ceiling, {len(copies)} pinned one-rank copies at once: step phase {min(copies):.3g}-"
                           f"{worst_c:.3g} s (mean {mean_c:.3g}); lone one-rank run over the mean copy "
                           f"**{t1 / mean_c:.2f}**, over the slowest **{t1 / worst_c:.2f}**." + copies_off_core(copy_rows))
                if lease == leases[-1] or case == "ex2":
                    curves.setdefault(f"{lease} ceiling", {})[case] = (t1 / mean_c, t1 / worst_c)
            top = max(ranks)
            if top > 1:
                big = [r for r in runs if int(r["ranks"]) == top]
                row = min(big, key=lambda r: num(r, "step_s"))
                compute = phase_sum(row, COMPUTE, "mean")
                compute_max = phase_sum(row, COMPUTE, "max")
                wait = phase_sum(row, STEP_PHASES, "wait")
                balance = num(row, "ph_balance_mean")
                comm = phase_sum(row, COMM, "mean") - phase_sum(row, COMM, "wait")
                one = min((r for r in runs if r["ranks"] == "1"), key=lambda r: num(r, "step_s"))
                ideal = phase_sum(one, COMPUTE, "mean") / top
                out.append("")
                out.append(f"Where the time goes at {top} ranks (the faster run, {num(row, 'step_s'):.3g} s): compute "
                           f"{compute:.3g} s a rank on average (one rank's / {top}: {ideal:.3g} s, so "
                           f"{compute / ideal:.2f}x), its slowest rank per phase {compute_max / compute:.2f}x "
                           f"the mean; waiting in MPI {wait:.3g} s; balancing {balance:.3g} s; the rest of the "
                           f"communication {comm:.3g} s." + coupled_share(row) + rank_spreads(row))
            if hybrid:
                out.append("")
                out += hybrid_table(runs, hybrid, t1)
            out.append("")
        measured = [r for r in mine if r["kind"] == "run" and r["mode"] == "measured" and r["status"] == "completed"]
        if measured:
            out.append("Prototype `decomposition.speeds: measured` (branch wip/measured-speeds), step phase against "
                       "equal shares in the same repeat:")
            out.append("")
            for r in measured:
                twin = [q for q in mine if q["kind"] == "run" and q["mode"] == "equal" and q["case"] == r["case"]
                        and q["ranks"] == r["ranks"] and q["repeat"] == r["repeat"]]
                if twin:
                    out.append(f"- {r['case']}, {r['ranks']} ranks, repeat {r['repeat']}: {num(r, 'step_s'):.3g} s "
                               f"against {num(twin[0], 'step_s'):.3g} s ({num(r, 'rebalances'):.0f} rebalances, "
                               f"{num(r, 'ph_balance_max'):.2f} s)")
            out.append("")
    chart(curves, png)
    return "\n".join(out)


def hybrid_table(runs, hybrid, t1):
    """Threads inside the ranks beside one thread per rank on as many cores (the same lease)."""
    out = ["Threads inside the ranks (OMP_NUM_THREADS, each rank on its own cores), beside one thread per rank "
           "on as many cores; per step, ms on the mean rank:",
           "",
           "| ranks x threads | cores | runs | step phase (s) | speedup | efficiency | compute | waiting in MPI "
           "| rest of the communication |",
           "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    configs = sorted({(int(r["ranks"]), int(r.get("threads") or 1)) for r in runs + hybrid},
                     key=lambda rt: (-rt[0] * rt[1], -rt[0]))
    for p, t in configs:
        if p * t == 1:
            continue
        mine = [r for r in runs + hybrid if int(r["ranks"]) == p and int(r.get("threads") or 1) == t]
        tp = statistics.median(num(r, "step_s") for r in mine)
        fast = min(mine, key=lambda r: num(r, "step_s"))
        per = 1e3 / num(fast, "steps")
        compute = phase_sum(fast, COMPUTE, "mean") * per
        wait = phase_sum(fast, STEP_PHASES, "wait") * per
        comm = (phase_sum(fast, COMM, "mean") - phase_sum(fast, COMM, "wait")) * per
        times = ", ".join(f"{num(r, 'step_s'):.3g}" for r in mine)
        out.append(f"| {p} x {t} | {p * t} | {len(mine)} | {tp:.3g} ({times}) | {t1 / tp:.2f}x | "
                   f"{100 * t1 / tp / (p * t):.0f}% | {compute:.2f} | {wait:.2f} | {comm:.2f} |")
    return out


def chart(curves, png):
    """Left: the speedup of example 2 at h = 0.025 m per lease, with the node's ceilings at the most ranks.
    Right: its step on the faster run of each rank count, in core-milliseconds (ranks x the mean
    rank's seconds), split into compute, waiting in MPI, the communication phases' own work and
    balancing: flat bars would be perfect scaling."""
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.8))
    top = 1
    for label, points in curves.items():
        if label.endswith("ceiling") or label.endswith("breakdown"):
            continue
        points.sort()
        by_p = {}
        for p, s in points:
            by_p.setdefault(p, []).append(s)
        ps = sorted(by_p)
        top = max(top, max(ps))
        ax.plot(ps, [statistics.median(by_p[p]) for p in ps], "o-", label=f"example 2, h = 0.025 m ({label})")
        ceiling = curves.get(f"{label} ceiling", {}).get("ex2")
        if ceiling:
            ax.plot([top], [ceiling[0] * top], "^", color=ax.lines[-1].get_color(),
                    label=f"ceiling, mean copy ({label})")
            ax.plot([top], [ceiling[1] * top], "v", color=ax.lines[-1].get_color(),
                    label=f"ceiling, slowest copy ({label})")
    ax.plot([1, top], [1, top], "k--", lw=0.8, label="ideal")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log", base=2)
    ax.set_xlabel("ranks (one per core)")
    ax.set_ylabel("speedup of the step phase over one rank")
    ax.set_title(f"mpm2grid strong scaling on one node, 1 to {top} ranks")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    breakdowns = [(k, v) for k, v in curves.items() if k.endswith("breakdown")]
    names = ["compute", "waiting in MPI", "communication work", "balancing"]
    colours = ["tab:blue", "tab:red", "tab:orange", "tab:gray"]
    width = 0.8 / max(1, len(breakdowns))
    for j, (label, parts) in enumerate(breakdowns):
        ps = sorted(parts)
        x = [i + j * width for i in range(len(ps))]
        bottom = [0.0] * len(ps)
        for k, name in enumerate(names):
            values = [parts[p][k] * p * 1e3 for p in ps]
            bx.bar(x, values, width, bottom=bottom, color=colours[k], alpha=1.0 - 0.35 * j,
                   label=f"{name} ({label.replace(' breakdown', '')})")
            bottom = [b + v for b, v in zip(bottom, values)]
        bx.set_xticks([i + 0.4 - width / 2 for i in range(len(ps))], [str(p) for p in ps])
    bx.set_xlabel("ranks")
    bx.set_ylabel("core-milliseconds per step (ranks x mean rank)")
    bx.set_title("example 2, h = 0.025 m: where the time goes")
    bx.legend(fontsize=7, ncol=2)
    bx.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    csv_path, png = argv[1], argv[2]
    machines = {}
    if len(argv) > 3:
        rows = []
        labels = [arg.partition("=")[0] for arg in argv[3:]]
        if Path(csv_path).exists():  # the other leases' rows, as recorded
            with open(csv_path) as f:
                rows = [r for r in csv.DictReader(f) if r["lease"] not in labels]
            read_machines(csv_path, machines)
            machines = {k: v for k, v in machines.items() if k not in labels}
        for arg in argv[3:]:
            label, _, runs_dir = arg.partition("=")
            found, machine = collect(label, runs_dir)
            rows += found
            machines[label] = machine
        with open(csv_path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=HEAD)
            w.writeheader()
            w.writerows(rows)
        with open(Path(csv_path).with_suffix(".machines.txt"), "w") as f:
            for label, text in machines.items():
                f.write(f"[{label}]\n{text}\n")
    else:
        with open(csv_path) as f:
            rows = list(csv.DictReader(f))
        read_machines(csv_path, machines)
    print(report(rows, machines, png))


def read_machines(csv_path, machines):
    info = Path(csv_path).with_suffix(".machines.txt")
    if info.exists():
        label = None
        for line in info.read_text().splitlines():
            if line.startswith("[") and line.endswith("]"):
                label = line[1:-1]
                machines[label] = ""
            elif label:
                machines[label] = (machines[label] + "\n" + line).strip()


if __name__ == "__main__":
    main(sys.argv)
