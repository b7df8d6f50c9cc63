#!/usr/bin/env bash
# The granular column collapse (solvers/mpm2grid/scenes/granular_column_collapse.yaml) over the
# aspect ratio a = H0/L0 = 0.5, 1, 3, 6 and three resolutions (grid.spacing 10, 5 and 2.5 mm),
# against the quasi-2D experiments' runout fit (Lube et al. 2005) and its band
# (tests/mpm2grid/check_granular_collapse.py measures each run: the point 98% of the deposit lies
# behind, the front where it is 3% of H0 thick, and the farthest particle). Columns: a = 0.5 and
# 1 with H0 = 0.2 m, a = 3 and 6 with H0 = 0.3 m (L0 = 0.4, 0.2, 0.1, 0.05 m). One run per
# configuration (no timing is compared; wall times are reported).
#   benchmarks/mpm2grid/run_granular_collapse.sh [MPM2GRID]   (about 25 min on one core)
#   env: SPACINGS ("10 5", mm), RATIOS ("0.5 1 3 6"), END (1 s), and common.sh's MPM2GRID OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
spacings=${SPACINGS:-10 5 2.5} ratios=${RATIOS:-0.5 1 3 6} end=${END:-1}
declare -A box=([0.5]="[0.4, 0.2]" [1]="[0.2, 0.2]" [3]="[0.1, 0.3]" [6]="[0.05, 0.3]")
work_dir granular_collapse
csv=$out/granular_collapse.csv
echo "a,spacing_mm,L0_m,H0_m,runout_deposit,runout_thin,runout_farthest,fit,band_lo,band_hi,H_inf_over_H0,at_rest,wall_s,steps" > "$csv"
for h in $spacings; do
  for a in $ratios; do
    run=$work/a$a-h$h
    rc=$(run_one "$run" 1 "$scenes/granular_column_collapse.yaml" "grid.spacing=$h mm" "soil.regions.0.box.hi=${box[$a]}" \
      "time.end=$end s")
    [ "$rc" = 0 ] || { echo "run $run failed ($rc): $(tail -2 "$run.err")" >&2; exit 1; }
    /usr/bin/python3 "$root/tests/mpm2grid/check_granular_collapse.py" "$run" --report "$run.json" > "$run.check" || true
    /usr/bin/python3 - "$run" "$a" "$h" >> "$csv" <<'PY'
import json, sys
run, a, h = sys.argv[1:]
r, info = json.load(open(run + ".json")), json.load(open(run + "/run.json"))
steps = json.load(open(run + "/summary.json"))["steps"]
print(f"{a},{h},{r['L0']:.4f},{r['H0']:.4f},{r['runout_deposit']:.4f},{r['runout_thin']:.4f},{r['runout_farthest']:.4f},"
      f"{r['fit']:.4f},"
      f"{r['band'][0]:.4f},{r['band'][1]:.4f},{r['H_inf_over_H0']:.4f},{int(r['at_rest'])},{info['wall_time_s']:.1f},{int(steps)}")
PY
    echo "a=$a h=$h mm: $(tail -1 "$csv")"
  done
done
{
  echo "## Granular column collapse: runout over the aspect ratio and the resolution (run_granular_collapse.sh)"
  echo
  provenance "$run/run.json"
  echo
  $plot "$here/plot_granular_collapse.py" "$csv" "$out/granular_collapse.png"
} | tee "$out/granular_collapse.md"
