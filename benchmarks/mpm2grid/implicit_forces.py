#!/usr/bin/python3
"""Explicit against implicit forces (run_implicit_forces.sh).
    implicit_forces.py row REFERENCE_CSV --header
    implicit_forces.py row REFERENCE_CSV CASE RUN_DIR     one CSV fragment of a run
    implicit_forces.py report CSV PNG                     Markdown table on stdout, chart to PNG
A run's fragment: wall time, steps, the implicit solve's Newton and GMRES iterations and residual
evaluations per step, the steps cut after a failed solve, the dam measures (eroded soil volume,
peak water outflow, water front) and, for the water column, the front Z = z / a at Martin &
Moyce's published times (martin_moyce_front.py) and its largest error against them; with the
erosion closure (example2_closure) the erosion law's gross eroded volume (law_eroded_volume).
The report takes the median wall time over the repeats and compares each setting with the case's
reference run, the explicit forces at cfl 0.1 (the smallest time-step error): the water column by
the largest relative difference in Z over the published points, example 2 by the relative
differences of the eroded volume, the peak outflow and the water front (the issue's "equal
accuracy": eroded volume and peak outflow within 5%), example2_closure by those of the law's
eroded volume and the peak outflow.
Each implicit row also gets its best case: the wall time the same steps would take if a perfect
preconditioner cost nothing and left one GMRES product per Newton iteration, i.e. per step the
explicit step's cost (explicit cfl 0.4's wall time over its steps: the P2G, G2P and particle
updates every step does) plus 2 + 2 N residual evaluations (the first guess, the initial residual,
and per Newton iteration one product and one line-search evaluation), N the row's Newton
iterations per step and one evaluation's cost taken from the row itself, (wall - steps x explicit
step) / (steps x evaluations per step)."""
import csv
import json
import statistics
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent
FIELDS = ["wall_s", "steps", "newton_per_step", "krylov_per_step", "evaluations_per_step", "steps_cut",
          "eroded_soil_volume", "peak_water_outflow", "water_front", "front_error_max", "front_Z", "law_eroded_volume"]


def row(reference, case, run):
    j = json.loads((run / "run.json").read_text())
    s = json.loads((run / "summary.json").read_text())
    im = j.get("implicit_forces", {})
    cut = sum(n for why, n in j.get("dt_limiters", {}).items() if why.startswith("implicit solve"))
    front = ["", ""]
    if case == "water_column":
        out = subprocess.run(["/usr/bin/python3", str(HERE / "martin_moyce_front.py"), reference, "3.0", str(run)],
                             check=True, capture_output=True, text=True).stdout.strip().split(",")
        front = [out[0], out[4]]
    values = [j["wall_time_s"], s["steps"], im.get("newton_per_step", 0), im.get("krylov_per_step", 0),
              im.get("residual_evaluations_per_step", 0), cut, s["eroded_soil_volume"], s["peak_water_outflow"],
              s["water_front"]]
    return (",".join(f"{v:.6g}" if isinstance(v, float) else str(v) for v in values) + "," + ",".join(front) + ","
            + f"{s.get('law_eroded_volume', 0):.6g}")


def report(path, png):
    rows = list(csv.DictReader(open(path)))
    runs = defaultdict(list)
    for r in rows:
        runs[(r["case"], r["forces"], float(r["cfl"]), float(r["dt_max_s"]))].append(r)
    refs = {case: runs[(case, "explicit", 0.1, d)][0] for case, f, c, d in runs if f == "explicit" and c == 0.1}

    def rel(a, b):
        a, b = float(a), float(b)
        return abs(a / b - 1) if b != 0 else (0.0 if a == 0 else float("inf"))

    def error(case, r):
        ref = refs[case]
        if case == "water_column":
            z = [float(v) for v in r["front_Z"].split(";")]
            zr = [float(v) for v in ref["front_Z"].split(";")]
            return {"front": max(abs(a / b - 1) for a, b in zip(z, zr))}
        measures = ([("law eroded", "law_eroded_volume"), ("peak outflow", "peak_water_outflow")]
                    if case == "example2_closure" else
                    [("eroded", "eroded_soil_volume"), ("peak outflow", "peak_water_outflow"), ("front", "water_front")])
        return {k: rel(r[f], ref[f]) for k, f in measures}

    table = []
    for (case, forces, cfl, dt_max), rs in sorted(runs.items()):
        wall = statistics.median(float(r["wall_s"]) for r in rs)
        r = rs[0]
        table.append(dict(case=case, forces=forces, cfl=cfl, dt_max=dt_max, wall=wall, repeats=len(rs),
                          steps=int(float(r["steps"])), newton=float(r["newton_per_step"]),
                          krylov=float(r["krylov_per_step"]), evals=float(r["evaluations_per_step"]),
                          cut=int(float(r["steps_cut"])), err=error(case, r), row=r))
    for case in sorted({t["case"] for t in table}):
        base = next(t for t in table if t["case"] == case and t["forces"] == "explicit" and t["cfl"] == 0.4)
        ref_wall, explicit_step = base["wall"], base["wall"] / base["steps"]
        print(f"### {case}\n")
        keys = list(next(t["err"] for t in table if t["case"] == case))
        extra = ("| front vs Martin & Moyce " if case == "water_column" else
                 "| law eroded m^2 | peak outflow m^2/s " if case == "example2_closure" else
                 "| eroded m^2 | peak outflow m^2/s ")
        print("| forces | cfl | dt_max s | steps | wall s (median) | vs explicit cfl 0.4 | Newton / step | GMRES / step "
              "| residuals / step | steps cut | best case s (speed-up over explicit cfl 0.4) | "
              + " | ".join(f"{k} vs explicit cfl 0.1" for k in keys) + " " + extra + "|")
        print("|" + "---|" * (11 + len(keys) + (1 if case == "water_column" else 2)))
        for t in (t for t in table if t["case"] == case):
            r = t["row"]
            eroded = "law_eroded_volume" if case == "example2_closure" else "eroded_soil_volume"
            measures = (f"| {float(r['front_error_max']):.3f} " if case == "water_column" else
                        f"| {float(r[eroded]):.3f} | {float(r['peak_water_outflow']):.3f} ")
            best = "-"
            if t["evals"] > 0:
                per_eval = max(0.0, t["wall"] - t["steps"] * explicit_step) / (t["steps"] * t["evals"])
                t["best"] = t["steps"] * (explicit_step + (2 + 2 * t["newton"]) * per_eval)
                best = f"{t['best']:.2f} ({ref_wall / t['best']:.2f}x)"
            print(f"| {t['forces']} | {t['cfl']} | {t['dt_max']:g} | {t['steps']} | {t['wall']:.2f} | "
                  f"{t['wall'] / ref_wall:.2f}x | {t['newton']:.2f} | {t['krylov']:.1f} | {t['evals']:.1f} | {t['cut']} | "
                  f"{best} | " + " | ".join(f"{v:.4f}" for v in t["err"].values()) + " " + measures + "|")
        print()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cases = sorted({t["case"] for t in table})
    fig, axes = plt.subplots(1, len(cases), figsize=(6 * len(cases), 5.5), squeeze=False)
    for ax, case in zip(axes[0], cases):
        for forces, marker in [("explicit", "o"), ("implicit", "s"), ("implicit-after_solve", "^"),
                               ("implicit-exact_krylov", "D")]:
            pts = [t for t in table if t["case"] == case and t["forces"] == forces and not
                   (forces == "explicit" and t["cfl"] == 0.1)]
            worst = [max(t["err"].values()) for t in pts]
            if pts:
                ax.scatter([t["wall"] for t in pts], [max(w, 1e-5) for w in worst], marker=marker, s=50,
                           label=forces.replace("-after_solve", ", soil elastic in the solve")
                           .replace("-exact_krylov", ", GMRES to 1e-8"))
            for t, w in zip(pts, worst):
                ax.annotate(f"cfl {t['cfl']}, dt_max {t['dt_max']:g} s", (t["wall"], max(w, 1e-5)), fontsize=7,
                            xytext=(4, 4), textcoords="offset points")
        bests = [t for t in table if t["case"] == case and "best" in t]
        if bests:
            ax.scatter([t["best"] for t in bests], [max(max(t["err"].values()), 1e-5) for t in bests], marker="x",
                       s=40, color="black", label="implicit's best case (a free, perfect preconditioner)")
        ax.axhline(0.05, color="red", ls="--", lw=0.8, label="5% (the issue's equal accuracy)")
        ref = next(t for t in table if t["case"] == case and t["forces"] == "explicit" and t["cfl"] == 0.1)
        ax.axvline(ref["wall"], color="grey", ls=":", label=f"reference: explicit cfl 0.1 ({ref['wall']:.1f} s)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time, s (median)")
        ax.set_ylabel("largest relative difference from the reference\n" +
                      ("(front Z)" if case == "water_column" else "(law eroded, peak outflow)"
                       if case == "example2_closure" else "(eroded, peak outflow, front)"))
        ax.set_title(case.replace("_", " "))
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(f"Chart: {Path(png).name}. Reference runs: explicit forces at cfl 0.1. Differences below 1e-5 are drawn "
          "at 1e-5.")


if __name__ == "__main__":
    if sys.argv[1] == "row":
        if sys.argv[3] == "--header":
            print(",".join(FIELDS))
        else:
            print(row(sys.argv[2], sys.argv[3], Path(sys.argv[4])))
    else:
        report(sys.argv[2], sys.argv[3])
