"""The numbers the foam-erosion benchmarks keep of one run's output folder, as one CSV fragment:
flow cells, interFoam time steps, interFoam wall time (run.json phase "flow", s), wall seconds
per simulated second, water volume over the crest and over the toe (m^3, the time integral of
discharge.csv), eroded area (m^2/m) and erosion steps.
    /usr/bin/python3 run_metrics.py RUN_DIR            -> cells,time_steps,flow_wall_s,...
    /usr/bin/python3 run_metrics.py --header           -> the column names
With --coupled first, two more columns: the whole run's wall time (s) and its re-meshes."""
import csv
import json
import sys

COLUMNS = "cells,time_steps,flow_wall_s,wall_s_per_simulated_s,crest_volume_m3,toe_volume_m3,eroded_area_m2,erosion_steps"
COUPLED_COLUMNS = "run_wall_s,remeshes"


def volume(t, q):
    """Time integral of a discharge sampled at the end of each solver step (interFoam writes the
    surface integral of the step just taken), so each value covers the step before it."""
    return sum((t[i] - t[i - 1]) * q[i] for i in range(1, len(t)))


def metrics(run):
    summary = json.load(open(f"{run}/summary.json"))
    flow = json.load(open(f"{run}/run.json"))["phases"]["flow"]["max_s"]
    rows = list(csv.DictReader(open(f"{run}/discharge.csv")))
    t = [float(x["time_s"]) for x in rows]
    crest = volume(t, [float(x["crest_Q_m3_s"]) for x in rows])
    toe = volume(t, [float(x["toe_Q_m3_s"]) for x in rows])
    return (f"{int(summary['cells'])},{int(summary['flow_steps'])},{flow:.3f},{flow / t[-1]:.3f},"
            f"{crest:.6e},{toe:.6e},{summary['eroded_area']:.6e},{int(summary['erosion_steps'])}")


def coupled_metrics(run):
    summary = json.load(open(f"{run}/summary.json"))
    wall = json.load(open(f"{run}/run.json"))["wall_time_s"]
    return f"{wall:.3f},{int(summary['remeshes'])}"


if __name__ == "__main__":
    args = sys.argv[1:]
    coupled = args[0] == "--coupled"
    if coupled:
        args = args[1:]
    if args[0] == "--header":
        print(COLUMNS + ("," + COUPLED_COLUMNS if coupled else ""))
    else:
        print(metrics(args[0]) + ("," + coupled_metrics(args[0]) if coupled else ""))
