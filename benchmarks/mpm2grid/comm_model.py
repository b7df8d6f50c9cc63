#!/usr/bin/python3
"""Issue 28's model of mpm2grid's step time over several nodes, from what one 16-core node and the
oversubscribed message counts measured. Prints Markdown.
    comm_model.py node_scaling.csv message_counts.csv

Per step and rank, P ranks on N = P / 16 nodes (16 a node, one per core):

    T(P) = T_c(P) (1 + g(P)) + T_o(P) + T_net(P)

- T_c(P) = C1 / P * s(P): the compute phases (no MPI) of one rank over P, times the node's
  slowdown s(P) with min(P, 16) busy cores (shared memory and caches), measured at 2-16 ranks;
  beyond one node s(16).
- g(P): the waiting, as a share of the compute. Every step has about ten synchronisations (halo
  sums and copies, reductions), and at each the ranks wait for the slowest. With the ranks' step
  times scattered about their mean with a relative spread sigma, the slowest of P is E_P sigma
  above it, E_P the expected largest of P standard normals (0.56, 1.03, 1.42, 1.77, 2.07, 2.33
  for P = 2, 4, 8, 16, 32, 64). sigma is fitted to the 16-rank runs; the 2-8-rank runs are the
  check.
- T_o(P): the communication phases' own work (packing, the halo plan, the outflow scan, the
  migration's lookups; their time less their waiting), measured at 2-16 ranks; it falls as
  o / P (fitted), the per-rank bytes and messages hardly change.
- T_net(P): for N > 1, a share phi of each rank's halo messages crosses the network:
  phi (m(P) alpha + b(P) / beta), with m and b the messages and bytes a rank sends per step
  (run_message_counts.sh at P ranks, oversubscribed: the counts are the partition's, not the
  machine's), plus the reductions (about 6 a step) over the nodes, 6 log2(N) alpha. phi lies
  between 1/4 (a part's neighbours mostly on its own node) and 1 - 1/N (neighbours anywhere).
  Interconnects: InfiniBand EDR (alpha 1.5 us, beta 10 GB/s) and 25 Gb Ethernet (alpha 20 us,
  beta 2.5 GB/s), typical MPI point-to-point figures, assumptions of this model, not measured.

Efficiency(P) = T(1) / (P T(P)), with T(1) the one-rank step.
"""
import csv
import math
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mpm_metrics import COMM_PHASES as COMM, COMPUTE_PHASES as COMPUTE, STEP_PHASES, phase_sum  # noqa: E402

EXPECTED_MAX = {1: 0.0, 2: 0.5642, 4: 1.0294, 8: 1.4236, 16: 1.7660, 32: 2.0697, 64: 2.3318}
NETWORKS = {"InfiniBand EDR": (1.5e-6, 10e9), "25 Gb Ethernet": (20e-6, 2.5e9)}
REDUCTIONS = 6


def num(row, key):
    v = row.get(key, "")
    return float(v) if v not in ("", None) else 0.0


def per_step(row, phases, stat):
    return phase_sum(row, phases, stat) / num(row, "steps")


def main(node_csv, counts_csv):
    rows = [r for r in csv.DictReader(open(node_csv))
            if r["case"] == "ex2" and r["kind"] == "run" and r["mode"] == "equal" and r["status"] == "completed"]
    counts = {int(r["ranks"]): r for r in csv.DictReader(open(counts_csv)) if r["status"] == "completed"}
    out = []
    for lease in dict.fromkeys(r["lease"] for r in rows):
        mine = [r for r in rows if r["lease"] == lease]
        by_p = {}
        for r in mine:
            by_p.setdefault(int(r["ranks"]), []).append(r)
        one = min(by_p[1], key=lambda r: num(r, "step_s"))
        t1 = num(one, "step_s") / num(one, "steps")
        c1 = per_step(one, COMPUTE, "mean")
        measured = {}
        for p, rs in by_p.items():
            if p == 1:
                rs = [one]  # the fastest one-rank run, T(1)
            comp = statistics.median(per_step(r, COMPUTE, "mean") for r in rs)
            wait = statistics.median(per_step(r, STEP_PHASES, "wait") for r in rs)
            other = statistics.median(per_step(r, COMM, "mean") - per_step(r, COMM, "wait") for r in rs)
            step = statistics.median(num(r, "step_s") / num(r, "steps") for r in rs)
            measured[p] = dict(s=comp * p / c1, g=wait / comp if p > 1 else 0.0, other=other, step=step)
        top = max(measured)
        sigma = measured[top]["g"] / EXPECTED_MAX[top]
        # o / P fitted (least squares through the origin in 1 / P) over 2..top.
        ps = [p for p in measured if p > 1]
        o = sum(measured[p]["other"] / p for p in ps) / sum(1 / p**2 for p in ps)

        def model(p, network=None, phi=0.0):
            s = measured[min(p, top)]["s"] if p <= top else measured[top]["s"]
            t_c = c1 / p * s
            t = t_c * (1 + sigma * EXPECTED_MAX[p]) + o / p
            if network and p > top:
                alpha, beta = network
                r = counts[p]
                m, b = num(r, "halo_messages_per_step") / p, num(r, "halo_bytes_per_step") / p
                t += phi * (m * alpha + b / beta) + REDUCTIONS * math.log2(p / top) * alpha
            return t

        out.append(f"### {lease}: example 2, h = 0.025 m (one rank {t1 * 1e3:.1f} ms per step)")
        out.append("")
        balance = statistics.median(num(r, "ph_balance_mean") / num(r, "steps") for r in by_p[top])
        out.append(f"Fitted: sigma = {sigma:.3f} (the 16-rank runs' waiting, {measured[top]['g']:.2f} of their "
                   f"compute, over E_16 = 1.766); o = {o * 1e3:.2f} ms (the communication phases' own work, "
                   f"o / P). Rebalances are left out (the {top}-rank runs spent {balance * 1e3:.2f} ms a step in "
                   f"them); the measured step is the slowest rank's.")
        out.append("")
        out.append("| ranks | node slowdown s(P) | waiting / compute: measured, model | step (ms): measured, model "
                   "| efficiency: measured, model |")
        out.append("| --- | --- | --- | --- | --- |")
        for p in sorted(p for p in measured if p > 1):
            m = measured[p]
            t = model(p)
            out.append(f"| {p} | {m['s']:.2f} | {m['g']:.2f}, {sigma * EXPECTED_MAX[p]:.2f} | {m['step'] * 1e3:.2f}, "
                       f"{t * 1e3:.2f} | {100 * t1 / (p * m['step']):.0f}%, {100 * t1 / (p * t):.0f}% |")
        out.append("")
        out.append("Predicted on 2 and 4 nodes of 16 cores like this one (phi = 1/4 to 1 - 1/N):")
        out.append("")
        out.append("| nodes x ranks | network | halo messages / bytes per rank and step | step (ms) | efficiency |")
        out.append("| --- | --- | --- | --- | --- |")
        for p in (32, 64):
            if p not in counts:
                continue
            n = p // top
            r = counts[p]
            m, b = num(r, "halo_messages_per_step") / p, num(r, "halo_bytes_per_step") / p
            for name, net in NETWORKS.items():
                lo, hi = model(p, net, 0.25), model(p, net, 1 - 1 / n)
                out.append(f"| {n} x {top} | {name} | {m:.1f} / {b / 1e3:.0f} kB | {lo * 1e3:.2f}-{hi * 1e3:.2f} | "
                           f"{100 * t1 / (p * hi):.0f}-{100 * t1 / (p * lo):.0f}% |")
            out.append(f"| {n} x {top} | none (the network free) | | {model(p) * 1e3:.2f} | "
                       f"{100 * t1 / (p * model(p)):.0f}% |")
        out.append("")
    print("\n".join(out))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
