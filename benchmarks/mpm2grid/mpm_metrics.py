#!/usr/bin/python3
"""One mpm2grid output folder as one CSV row for the benchmark drivers in this folder.
    mpm_metrics.py --header               the column names
    mpm_metrics.py RUN_DIR [RSS_DIR]      the row (RSS_DIR: rss_rank<N>.txt files of /usr/bin/time -f %M)

Columns: status (completed / stopped / failed), ranks, steps (run.json phases.step.calls),
step_s (the step phase's total on the slowest rank, run.json phases.step.max_s), step_mean_s
(its mean over the ranks), wall_s (run.json wall_time_s: seeding, partition, output included),
particles_first / particles_last / particles_mean (water + soil over series.csv; the mean weights
each series interval by its steps, dt from the row), s_per_step, ns_per_particle_step
(step_s / (steps x particles_mean), wall time on the slowest rank; multiply by ranks for
core-ns), the decomposition block (halo and migration bytes per step summed over ranks,
migrated particles per step, rebalances, and at the end of the list halo and migration messages
per step summed over ranks; empty on 1 rank), drag_ksp_max_iterations (consistent drag only),
summary.json values (outflow water volume, eroded soil volume, water front, end time; empty
unless completed), peak RSS of each rank (kB, max and sum over ranks) when RSS_DIR is given, the
largest kinetic energy in series.csv, dt_first / dt_last / dt_largest: the dt column of series.csv
(the step before each sample; a step cut to land on a sample time is shorter, never longer),
outflow_discharge_max: the largest water discharge through the outlet in series.csv (m^2/s in 2D,
sampled at the output interval; empty without an outlet), drag_coupled_nodes_rank_mean and _max:
the consistent drag's coupled nodes per step owned by a rank, mean and most over the ranks (the
assembly's work per rank; empty without the consistent drag), drag_solved_nodes_rank_max: the
most whose rows a rank held in the Krylov solve (decomposition.drag_rows), drag_rows_s_mean and
_max, drag_exchange_s_mean and _max, drag_krylov_s_mean and _max: a rank's seconds computing its
rows of the drag matrix, in the assembly's exchange (the rows for other ranks, PETSc's assembly,
the waiting for the others) and in the Krylov
solves, mean and most over the ranks (all inside the grid solve phase). From run.json's
per_rank block (over several ranks; the compute phases' own seconds, waits taken off, summed per
rank):
rank_compute_spread, the most loaded rank's compute over the mean; rank_work_spread, the same of
the particle-steps (water and soil); rank_cost_spread, of the compute per particle-step (a rank
that is slower over the same work: its core); rank_slowest_same, the share of the compute phases
(each over 1% of the compute) whose slowest rank is the rank slowest over all of them (1: one
rank slow everywhere, as a slow core or more work would be; near 1 / ranks: chance).
On the CPU clock (per_rank cpu_s: the main thread's CPU outside the waits): rank_cpu_spread, the
most loaded rank's compute CPU over the mean (the work's imbalance without the time off the
cores); rank_off_core, the share of the compute's wall time that the ranks' main threads were off
their cores (wall less CPU, over the ranks together; another process, a host's steal);
rank_off_core_slowest, that share on the rank whose compute took longest. Empty for runs from
before the CPU clock.
Then per phase of the step (run.json "step/<phase>", solvers/mpm2grid/model/step_timers.hpp) and
the two per-step checks outside it ("dt limit", "blow-up check"): ph_<phase>_mean and ph_<phase>_max,
its seconds over the run, mean and largest over the ranks, and ph_<phase>_wait, the mean over the
ranks of the part blocked in MPI calls (phase names with '_' for spaces and '-'; empty where the
run did not report the phase, e.g. the halo's on one rank or runs before the breakdown existed).
A folder without run.json (a run that failed, e.g. the energy blow-up) gives status failed.
"""
import csv
import json
import sys
from pathlib import Path

COLUMNS = ["status", "ranks", "steps", "step_s", "step_mean_s", "wall_s", "particles_first", "particles_last",
           "particles_mean", "s_per_step", "ns_per_particle_step", "halo_bytes_per_step",
           "migration_bytes_per_step", "migrated_particles_per_step", "rebalances", "particles_per_rank",
           "drag_ksp_max_iterations", "outflow_water_volume", "eroded_soil_volume", "water_front", "end_time",
           "dt_first", "dt_last", "rss_max_kb", "rss_sum_kb", "kinetic_energy_max", "dt_largest",
           "halo_messages_per_step", "migration_messages_per_step", "outflow_discharge_max",
           "drag_coupled_nodes_rank_mean", "drag_coupled_nodes_rank_max", "drag_solved_nodes_rank_max",
           "drag_rows_s_mean", "drag_rows_s_max", "drag_exchange_s_mean", "drag_exchange_s_max",
           "drag_krylov_s_mean", "drag_krylov_s_max",
           "rank_compute_spread",
           "rank_work_spread", "rank_cost_spread", "rank_slowest_same", "rank_cpu_spread", "rank_off_core",
           "rank_off_core_slowest"]
STEP_PHASES = ["balance", "grid", "halo plan", "stresses", "p2g water", "halo sum", "p2g soil", "grid solve",
               "boundary", "halo copy", "g2p water", "g2p soil", "outflow", "inlet", "migrate", "bed shear"]
CHECKS = ["dt limit", "blow-up check"]
# The step phases without MPI, and the phases with messages or reductions (outflow and bed shear
# reduce over the ranks; their time less their wait is their own work): node_scaling.py's and
# comm_model.py's breakdown. A phase in both would count its wait twice.
COMPUTE_PHASES = ["grid", "stresses", "p2g water", "p2g soil", "grid solve", "boundary", "g2p water", "g2p soil",
                  "inlet"]
COMM_PHASES = ["halo plan", "halo sum", "halo copy", "outflow", "migrate", "bed shear"]


def slug(phase):
    return phase.replace(" ", "_").replace("-", "_")


def phase_sum(row, phases, stat):
    """The sum over `phases` of a row's ph_<phase>_<stat> column (mean, max or wait), empty as 0."""
    return sum(float(row.get(f"ph_{slug(p)}_{stat}") or 0.0) for p in phases)


for _p in STEP_PHASES + CHECKS:
    COLUMNS += [f"ph_{slug(_p)}_mean", f"ph_{slug(_p)}_max", f"ph_{slug(_p)}_wait"]


def series(run):
    path = Path(run) / "series.csv"
    if not path.exists():
        return []
    rows = list(csv.reader(path.read_text().splitlines()))
    if len(rows) < 2:
        return []
    head = [h.split(" [")[0] for h in rows[0]]
    return [dict(zip(head, map(float, r))) for r in rows[1:] if r]


def particles_mean(rows):
    count = lambda r: r["water_particles"] + r["soil_particles"]
    total = weight = 0.0
    for a, b in zip(rows, rows[1:]):
        if b["dt"] > 0:
            w = (b["time"] - a["time"]) / b["dt"]
            total += w * 0.5 * (count(a) + count(b))
            weight += w
    return total / weight if weight > 0 else (count(rows[0]) if rows else float("nan"))


def per_rank_spreads(per_rank):
    """The rank_* columns from run.json's per_rank block (empty without one)."""
    if not per_rank:
        return {}
    step, wait = per_rank["step_s"], per_rank["wait_s"]
    ranks = len(per_rank["soil_particle_steps"])
    own = {p: [t - w for t, w in zip(step[p], wait.get(p, [0.0] * ranks))] for p in COMPUTE_PHASES if p in step}
    compute = [sum(v[r] for v in own.values()) for r in range(ranks)]
    work = [a + b for a, b in zip(per_rank["water_particle_steps"], per_rank["soil_particle_steps"])]
    if min(work) <= 0 or sum(compute) <= 0:
        return {}
    spread = lambda v: max(v) * len(v) / sum(v)
    slowest = compute.index(max(compute))
    big = [v for v in own.values() if sum(v) > 0.01 * sum(compute)]
    same = sum(v.index(max(v)) == slowest for v in big) / len(big)
    m = {"rank_compute_spread": f"{spread(compute):.4g}", "rank_work_spread": f"{spread(work):.4g}",
         "rank_cost_spread": f"{spread([c / w for c, w in zip(compute, work)]):.4g}",
         "rank_slowest_same": f"{same:.3g}"}
    cpu_s = per_rank.get("cpu_s")
    if cpu_s:
        cpu = [sum(cpu_s[p][r] for p in own if p in cpu_s) for r in range(ranks)]
        if sum(cpu) > 0:
            m["rank_cpu_spread"] = f"{spread(cpu):.4g}"
            m["rank_off_core"] = f"{max(0.0, 1 - sum(cpu) / sum(compute)):.4g}"
            m["rank_off_core_slowest"] = f"{max(0.0, 1 - cpu[slowest] / compute[slowest]):.4g}"
    return m


def metrics(run, rss_dir=None):
    run = Path(run)
    m = dict.fromkeys(COLUMNS, "")
    rows = series(run)
    if rows:
        m["particles_first"] = int(rows[0]["water_particles"] + rows[0]["soil_particles"])
        m["particles_last"] = int(rows[-1]["water_particles"] + rows[-1]["soil_particles"])
        m["particles_mean"] = f"{particles_mean(rows):.1f}"
        m["kinetic_energy_max"] = f"{max(r['kinetic_energy'] for r in rows):.6g}"
        if "outflow_water_discharge" in rows[0]:
            m["outflow_discharge_max"] = f"{max(r['outflow_water_discharge'] for r in rows):.6g}"
        dts = [r["dt"] for r in rows if r["dt"] > 0]
        if dts:
            m["dt_first"], m["dt_last"], m["dt_largest"] = f"{dts[0]:.6g}", f"{dts[-1]:.6g}", f"{max(dts):.6g}"
    rj = run / "run.json"
    if not rj.exists():
        m["status"] = "failed"
    else:
        r = json.loads(rj.read_text())
        status = r.get("status", "")
        m["status"] = "completed" if status == "completed" else "stopped" if status.startswith("stopped") else status
        m["ranks"] = r.get("ranks", "")
        step = r.get("phases", {}).get("step", {})
        steps = step.get("calls", 0)
        m["steps"] = steps
        m["step_s"] = f"{step.get('max_s', 0):.6g}"
        m["step_mean_s"] = f"{step.get('mean_s', 0):.6g}"
        m["wall_s"] = f"{r.get('wall_time_s', 0):.6g}"
        if steps:
            m["s_per_step"] = f"{step['max_s'] / steps:.6g}"
            if rows:
                m["ns_per_particle_step"] = f"{1e9 * step['max_s'] / (steps * particles_mean(rows)):.5g}"
        d = r.get("decomposition", {})
        for k in ("halo_bytes_per_step", "migration_bytes_per_step", "migrated_particles_per_step", "rebalances",
                  "halo_messages_per_step", "migration_messages_per_step"):
            if k in d:
                m[k] = f"{d[k]:.6g}"
        if "particles_per_rank" in d:
            m["particles_per_rank"] = " ".join(str(p) for p in d["particles_per_rank"])
        m["drag_ksp_max_iterations"] = r.get("drag_ksp_max_iterations", "")
        coupled = r.get("drag_coupled_nodes_per_rank", {})
        if coupled:
            m["drag_coupled_nodes_rank_mean"] = f"{coupled['mean']:.6g}"
            m["drag_coupled_nodes_rank_max"] = f"{coupled['max']:.6g}"
        solved = r.get("drag_solved_nodes_per_rank", {})
        if solved:
            m["drag_solved_nodes_rank_max"] = f"{solved['max']:.6g}"
        for part, spread in r.get("drag_seconds_per_rank", {}).items():
            m[f"drag_{part}_s_mean"] = f"{spread['mean']:.6g}"
            m[f"drag_{part}_s_max"] = f"{spread['max']:.6g}"
        m.update(per_rank_spreads(r.get("per_rank")))
        phases = r.get("phases", {})
        for p in STEP_PHASES + CHECKS:
            v = phases.get(p if p in CHECKS else f"step/{p}")
            if v:
                w = phases.get(f"step/{p}/wait", {})
                m[f"ph_{slug(p)}_mean"] = f"{v['mean_s']:.6g}"
                m[f"ph_{slug(p)}_max"] = f"{v['max_s']:.6g}"
                m[f"ph_{slug(p)}_wait"] = f"{w.get('mean_s', 0):.6g}"
    sj = run / "summary.json"
    if sj.exists() and m["status"] == "completed":
        s = json.loads(sj.read_text())
        for k in ("outflow_water_volume", "eroded_soil_volume", "water_front", "end_time"):
            m[k] = f"{s.get(k, float('nan')):.10g}"
    if rss_dir:
        kb = [int(p.read_text().split()[-1]) for p in sorted(Path(rss_dir).glob("rss_rank*.txt"))
              if p.read_text().strip()]
        if kb:
            m["rss_max_kb"], m["rss_sum_kb"] = max(kb), sum(kb)
    return m


if __name__ == "__main__":
    if sys.argv[1] == "--header":
        print(",".join(COLUMNS))
    else:
        m = metrics(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else None)
        print(",".join(str(m[c]) for c in COLUMNS))
