#!/usr/bin/python3
"""The table of run_rebalance.sh: per rank count, the diffusive and the fresh (METIS) rebalances of
the same run side by side, from each run's run.json.
    rebalance.py WORK_DIR SWEEP_RANKS "IMBALANCES" RANKS...
        (WORK_DIR holds diffuse-rRANKS/, fresh-rRANKS/ and imbalanceI-rSWEEP_RANKS/)
Columns: rebalances (of them by diffusion: a diffusive one that cannot reach its target falls back
to METIS), the particles the rebalances sent to other ranks (all of them: the particles in the
scene at the end for scale), rank 0's seconds finding the new owner tables, halo bytes and
messages per step over the run (the parts' shapes), the largest over the mean particles per rank
at the end, and over the run (run.json per_rank: each species' particle-steps, the most loaded
rank's over the mean; the time of a phase of that species on the slowest rank follows it).
The second table: the same at SWEEP_RANKS ranks, diffusing, for each decomposition.imbalance. No step times: oversubscribed, the run done first was the slower one whichever
it was (16 ranks on 2 cores: 50.2 / 43.3 s diffuse first, 49.3 / 43.7 s fresh first).
"""
import json
import sys
from pathlib import Path


def row(run):
    r = json.loads((run / "run.json").read_text())
    if r.get("status") != "completed":
        sys.exit(f"{run}: the run did not complete ({r.get('status')})")
    d = r["decomposition"]
    per_rank = d["particles_per_rank"]
    return {
        "rebalances": f"{d['rebalances']} ({d.get('rebalances_diffused', 0)})",
        "moved": f"{d.get('rebalance_migrated_particles', 0):,} of {sum(per_rank):,}",
        "partition": f"{d.get('rebalance_partition_s', 0):.3f}",
        "halo": f"{d['halo_bytes_per_step'] / 1e6:.3f} / {d['halo_messages_per_step']:.0f}",
        "balance": f"{max(per_rank) * len(per_rank) / sum(per_rank):.3f}",
        "run": " / ".join(f"{spread(r['per_rank'][k]):.4f}" for k in ("soil_particle_steps", "water_particle_steps")),
    }


def spread(values):
    return max(values) * len(values) / sum(values)


HEAD = ("| rebalances (by diffusion) | particles the rebalances moved | rank 0's partition (s) "
        "| halo MB / messages per step | particles max / mean at the end | particle-steps max / mean: soil / water |")


def cells(x):
    return f"{x['rebalances']} | {x['moved']} | {x['partition']} | {x['halo']} | {x['balance']} | {x['run']} |"


def main():
    work, sweep_ranks, imbalances = Path(sys.argv[1]), sys.argv[2], sys.argv[3].split()
    print("| ranks | repartition " + HEAD)
    print("| --- " * 8 + "|")
    for ranks in sys.argv[4:]:
        for mode in ("diffuse", "fresh"):
            print(f"| {ranks} | {mode} | " + cells(row(work / f"{mode}-r{ranks}")))
    print()
    print(f"Diffusing at {sweep_ranks} ranks:")
    print()
    print("| decomposition.imbalance " + HEAD)
    print("| --- " * 7 + "|")
    for imbalance in imbalances:
        print(f"| {imbalance} | " + cells(row(work / f"imbalance{imbalance}-r{sweep_ranks}")))


if __name__ == "__main__":
    main()
