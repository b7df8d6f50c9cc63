"""The numbers the foam-erosion benchmarks keep of one run's output folder, as one CSV fragment:
flow cells, interFoam time steps, interFoam wall time (run.json phase "flow", s), wall seconds
per simulated second, water volume over the crest and over the toe (m^3, summary.json's time
integrals of discharge.csv), eroded area (m^2/m) and erosion steps.
    /usr/bin/python3 run_metrics.py RUN_DIR            -> cells,time_steps,flow_wall_s,...
    /usr/bin/python3 run_metrics.py --header           -> the column names
With --coupled first, two more columns: the whole run's wall time (s) and its re-meshes."""
import csv
import json
import sys

COLUMNS = "cells,time_steps,flow_wall_s,wall_s_per_simulated_s,crest_volume_m3,toe_volume_m3,eroded_area_m2,erosion_steps"
COUPLED_COLUMNS = "run_wall_s,remeshes"


def metrics(run):
    summary = json.load(open(f"{run}/summary.json"))
    flow = json.load(open(f"{run}/run.json"))["phases"]["flow"]["max_s"]
    with open(f"{run}/discharge.csv") as f:
        end = float(list(csv.reader(f))[-1][0])  # the simulated time the record reaches
    return (f"{int(summary['cells'])},{int(summary['flow_steps'])},{flow:.3f},{flow / end:.3f},"
            f"{summary['crest_water_volume']:.6e},{summary['toe_water_volume']:.6e},{summary['eroded_area']:.6e},"
            f"{int(summary['erosion_steps'])}")


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
