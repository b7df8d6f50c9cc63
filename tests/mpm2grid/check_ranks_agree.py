"""Two mpm2grid runs of one scene, on 1 and on 2 ranks, agree to round-off (docs/methods/mpm2grid.md,
"Decomposition and performance design"): every column of series.csv and every particle's
position in the last particle file. The decomposition changes only the order in which P2G adds
particles into a node (its own particles first, then the halo sum) and the order of the global
sums, so the two runs differ by round-off that the steps carry along: about 1e-12 m after 3,600
steps of the dam scene. The tolerance, 1e-9 relative (positions: 1e-9 of the domain's size), is
a thousand times that and a million times below any modelling error; a wrong halo sum, a particle
lost or duplicated in migration, or a ghost node left with partial sums gives errors of percent.
The 2-rank run must really be decomposed: particles on both ranks, halo traffic.
With the free water's own field a water particle whose sampled soil fill lies within round-off
of the sort's threshold (1/2) can be sorted differently on the two runs for a step: a spike of
1.5e-9 in the kinetic energy at one sample of the dam scene, gone at the next. Such a run sets
RANKS_AGREE_TOLERANCE (1e-7: still five orders of magnitude below a wrong halo's percent).
Threads inside a rank change the order of P2G's sums the same way (threads_agree.sh); a second
run on one rank with threads sets SECOND_RANKS=1 (default 2), and OVERSUBSCRIBED=1 where the
second run has more threads than the machine has cores: the kernel then preempts a rank between
its phases' clocks (2 ranks x 2 threads on 2 cores: phases 7% short of the step), so the phases'
sum is not checked there (the ranks_agree tests check it).
  check_ranks_agree.py ONE_RANK_DIR TWO_RANK_DIR"""
import csv
import glob
import json
import math
import os
import re
import sys

import h5py
import numpy as np

one, two = sys.argv[1], sys.argv[2]
tol = float(os.environ.get("RANKS_AGREE_TOLERANCE", "1e-9"))
second_ranks = int(os.environ.get("SECOND_RANKS", "2"))


def series(d):
    with open(os.path.join(d, "series.csv")) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:] if r])


head, a = series(one)
_, b = series(two)
assert a.shape == b.shape, f"series.csv: {a.shape} rows/columns on 1 rank, {b.shape} on 2"
worst = 0.0
for k, name in enumerate(head):
    for x, y in zip(a[:, k], b[:, k]):
        if math.isnan(x) and math.isnan(y):
            continue
        scale = max(np.abs(a[:, k][np.isfinite(a[:, k])]).max(), 1e-300)
        err = abs(x - y) / scale
        worst = max(worst, err)
        assert err <= tol, f"{name}: {x!r} on 1 rank, {y!r} on 2 ranks (relative {err:.2e} > {tol:g})"
print(f"series.csv: {a.shape[0]} rows x {a.shape[1]} columns agree, largest relative difference {worst:.2e}")

last = sorted(os.path.basename(p) for p in glob.glob(os.path.join(one, "particles", "*.h5")))[-1]
with h5py.File(os.path.join(one, "particles", last)) as f1, h5py.File(os.path.join(two, "particles", last)) as f2:
    extent = max(np.ptp(f1[s]["position"][:], axis=0).max() for s in ("water", "soil") if s in f1)
    for s in ("water", "soil"):
        if s not in f1:
            continue
        p, q = f1[s]["position"][:], f2[s]["position"][:]
        assert p.shape == q.shape, f"{last}: {len(p)} {s} particles on 1 rank, {len(q)} on 2"
        # Sorted by position rounded to 1e-6 of the domain: particles of one lattice column share x,
        # and round-off alone must not change which of them comes first.
        key = lambda r: np.lexsort(np.round(r / (1e-6 * extent)).T[::-1])
        p, q = p[key(p)], q[key(q)]
        err = np.abs(p - q).max() / extent
        assert err <= tol, f"{last}: {s} positions differ by {err:.2e} of the domain (> {tol:g})"
        print(f"{last}: {len(p)} {s} particles at the same places (largest difference {err:.2e} of the domain)")

if second_ranks > 1:
    with open(os.path.join(two, "run.json")) as f:
        dd = json.load(f)["decomposition"]
    assert dd["ranks"] == 2 and min(dd["particles_per_rank"]) > 0, f"not decomposed: {dd}"
    assert dd["halo_bytes_per_step"] > 0, f"no halo traffic: {dd}"
    print(f"2 ranks: particles per rank {dd['particles_per_rank']}, halo {dd['halo_bytes_per_step']:.0f} bytes/step, "
          f"{dd['migrated_particles_per_step']:.2f} particles migrated/step, {dd['rebalances']} rebalances")

# With the consistent drag, run.json's coupled nodes per rank (the rows each owner assembles) and
# solved nodes per rank (the rows each holds in the Krylov solve) each add up over the ranks to
# the one-rank run's: every coupled node has exactly one owner and one place in the solve. The same
# nodes are coupled on both runs (both species' masses on a node, which round-off cannot bring to
# zero), so the sums per step, averaged over the same steps, agree to the averages' round-off.
# With the solve's rows in equal shares (decomposition.drag_rows: balanced) the shares of a step
# differ by at most one node, so their averages do too; with the owners' rows the solved nodes
# are the coupled ones; `auto` takes either, step by step (only the sums hold).
counts = []
for d in (one, two):
    with open(os.path.join(d, "run.json")) as f:
        r = json.load(f)
    with open(os.path.join(d, "effective_config.yaml")) as f:
        rows = re.search(r"^\s*drag_rows:\s*(\w+)\s*$", f.read(), re.M)
    counts.append((r.get("drag_coupled_nodes_per_rank"), r.get("drag_solved_nodes_per_rank"), rows and rows.group(1)))
    # The drag's rows, PETSc's assembly and the Krylov solves are disjoint intervals inside each
    # rank's grid solve phase, on the same clock: their sum is at most the phase, per rank and so
    # in the mean.
    if "drag_seconds_per_rank" in r:
        ds, solve = r["drag_seconds_per_rank"], r["phases"]["step/grid solve"]["mean_s"]
        parts = {k: ds[k]["mean"] for k in ("rows", "exchange", "krylov")}
        assert all(v >= 0 for v in parts.values()) and 0 < sum(parts.values()) <= solve * (1 + 1e-9), (
            f"{d}/run.json: drag seconds {parts}, grid solve {solve} s")
        print(f"{d}: drag rows {parts['rows']:.3f} s, exchange {parts['exchange']:.3f} s, Krylov "
              f"{parts['krylov']:.3f} s of the grid solve phase's {solve:.3f} s (rank mean)")
if counts[0][0] is not None:
    for key, (c1, c2) in (("coupled", (counts[0][0], counts[1][0])), ("solved", (counts[0][1], counts[1][1]))):
        assert c1["min"] == c1["mean"] == c1["max"], f"{one}/run.json: one rank, yet {key} nodes {c1}"
        assert c2["min"] <= c2["mean"] <= c2["max"], f"{two}/run.json: {key} nodes {c2}"
        total = c2["mean"] * second_ranks
        assert c1["mean"] > 0 and abs(total - c1["mean"]) <= 1e-9 * c1["mean"], (
            f"{key} nodes per step: {c1['mean']} on one rank, {total} summed over {second_ranks}")
        print(f"{key} nodes per step: {c1['mean']:.1f} on one rank; on {second_ranks}: {c2['min']:.1f} to "
              f"{c2['max']:.1f} a rank, {total:.1f} in all")
    (coupled, solved, rows) = counts[1]
    if rows == "balanced":
        assert solved["max"] - solved["min"] <= 1 + 1e-9, f"{two}/run.json: the solve's shares differ: {solved}"
    elif rows == "owners":
        assert solved == coupled, f"{two}/run.json: the owners' rows, yet solved nodes {solved}, coupled {coupled}"

# The step's breakdown in run.json (solvers/mpm2grid/model/step_timers.hpp) accounts for the step:
# its phases are disjoint and cover Simulation::step() but for a few assignments, so per rank
# their times add up to the "step" phase; the mean over the ranks is linear, so the phases' means
# add up to the step's mean. 5% covers the untimed assignments and the clock reads themselves
# (tens of nanoseconds against steps of at least 0.1 ms here). Every phase ran once a step; a
# phase's time blocked in MPI is part of its time; 2 ranks wait in the halo sums.
for d, ranks in ((one, 1), (two, second_ranks)):
    with open(os.path.join(d, "run.json")) as f:
        phases = json.load(f)["phases"]
    step = phases["step"]
    parts = {k[5:]: v for k, v in phases.items() if k.startswith("step/") and k.count("/") == 1}
    expected = {"grid", "stresses", "p2g water", "p2g soil", "grid solve", "boundary", "g2p water", "g2p soil"}
    if ranks > 1:
        expected |= {"halo plan", "halo sum", "halo copy", "migrate"}
    assert expected <= set(parts), f"{d}/run.json: step phases {sorted(parts)} miss {sorted(expected - set(parts))}"
    for name, v in parts.items():
        assert v["calls"] == step["calls"], f"{d}/run.json: step/{name} counted {v['calls']} calls, the step {step['calls']}"
        wait = phases.get(f"step/{name}/wait")
        if wait:
            assert wait["max_s"] <= v["max_s"] * (1 + 1e-9), f"{d}/run.json: step/{name} waited longer than it ran"
    total = sum(v["mean_s"] for v in parts.values())
    oversubscribed = d == two and os.environ.get("OVERSUBSCRIBED") == "1"
    assert oversubscribed or abs(total - step["mean_s"]) <= 0.05 * step["mean_s"], (
        f"{d}/run.json: the step's phases add up to {total:.4f} s, the step took {step['mean_s']:.4f} s (> 5% apart)")
    assert ranks == 1 or phases.get("step/halo sum/wait", {}).get("max_s", 0) > 0, f"{d}/run.json: no halo wait"
    print(f"{ranks} rank(s): {len(parts)} step phases add up to {total:.4f} s of the step's {step['mean_s']:.4f} s")

# run.json's per_rank block gives every rank's figures behind those statistics: per phase the
# same seconds whose least, mean and largest "phases" reports (the same doubles: to their
# round-off in the mean), and per rank the particle-steps, which add up over the ranks to the
# one-rank run's: both runs take the same steps with the same particles (a particle that left
# through the outlet a step apart on round-off would change one particle-step of millions).
records = []
for d in (one, two):
    with open(os.path.join(d, "run.json")) as f:
        records.append(json.load(f))
for d, ranks, record in ((one, 1, records[0]), (two, second_ranks, records[1])):
    per_rank, phases = record["per_rank"], record["phases"]
    for name, seconds in per_rank["step_s"].items():
        v = phases[f"step/{name}"]
        close = lambda a, b: abs(a - b) <= 1e-12 + 1e-9 * abs(b)
        assert len(seconds) == ranks and close(min(seconds), v["min_s"]) and close(max(seconds), v["max_s"]) and \
            close(sum(seconds) / ranks, v["mean_s"]), f"{d}/run.json: per_rank step_s[{name}] = {seconds}, phases {v}"
# The CPU clock (step/<phase>/cpu, per_rank cpu_s: the main thread's CPU time in a phase outside
# its MPI waits). One thread's CPU time cannot run ahead of the wall clock, so per rank and phase
# it lies between 0 and the phase's wall time less its waits. Each clock read sits inside the
# span it is compared with; what is left is the CPU time between a wait's wall-clock and
# CPU-clock reads (about 1 us a wait, a few waits a step: under 0.1 ms a step) and the clock
# reads' own rounding, hence 1e-4 s a step and 1e-6 of the phase.
for d, ranks, record in ((one, 1, records[0]), (two, second_ranks, records[1])):
    per_rank, steps = record["per_rank"], record["phases"]["step"]["calls"]
    assert set(per_rank["cpu_s"]) == set(per_rank["step_s"]), f"{d}/run.json: cpu_s for {sorted(per_rank['cpu_s'])}"
    for name, cpu in per_rank["cpu_s"].items():
        wall, wait = per_rank["step_s"][name], per_rank["wait_s"][name]
        for r in range(ranks):
            slack = 1e-4 * steps + 1e-6 * wall[r]
            assert -slack <= cpu[r] <= wall[r] - wait[r] + slack, (
                f"{d}/run.json: rank {r}'s step/{name}: {cpu[r]:.6f} s on the CPU, {wall[r]:.6f} s of wall time "
                f"of which {wait[r]:.6f} s waiting")
    own = sum(sum(per_rank["step_s"][p]) - sum(per_rank["wait_s"][p]) for p in per_rank["step_s"])
    cpu = sum(sum(v) for v in per_rank["cpu_s"].values())
    assert cpu > 0, f"{d}/run.json: no CPU time in the step's phases"
    print(f"{ranks} rank(s): the phases' own work {own:.4f} rank-s of wall time, {cpu:.4f} on the CPU")
if records[0]["phases"]["step"]["calls"] == records[1]["phases"]["step"]["calls"]:
    for k in ("water_particle_steps", "soil_particle_steps", "grid_block_steps"):
        a, b = sum(records[0]["per_rank"][k]), sum(records[1]["per_rank"][k])
        if k == "grid_block_steps":  # ghost blocks: the ranks' grids overlap
            assert b >= a, f"{k}: {a} on one rank, {b} over {second_ranks}"
        else:
            assert abs(a - b) <= 1e-6 * a, f"{k}: {a} on one rank, {b} summed over {second_ranks}"
    print(f"per rank: particle-steps add up to one rank's; grid blocks {sum(records[1]['per_rank']['grid_block_steps']) / sum(records[0]['per_rank']['grid_block_steps']):.3f}x one rank's (the ghosts)")
