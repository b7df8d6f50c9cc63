#!/usr/bin/env bash
# One dam through the three dam solvers (issue 27, item 3): the dissertation's Table 3.4 dams
# example 2 (3.75 m high, 6 m crest, q = 14.5 m^2/s under its published g = 3 m/s^2) and 05-HR-a
# (3.3 m high, 1 m crest, q = 12.5 m^2/s, g = 9.8 m/s^2) with one soil, kd and tau_c from a
# jet-erosion test, through
#   mpm2grid      solvers/mpm2grid/scenes/table_3_4_<scene>.yaml with the bed-shear closure and
#                 excess-stress erosion (docs/mpm2grid.md, "Bed shear and excess-stress erosion")
#                 and both FLIP shares, over the grid spacing (SPACINGS), with the lumped drag and,
#                 at the spacings CONSISTENT, the consistent (PETSc) drag too;
#   foam-erosion  <scene>.foam.yaml (the same section, pool, inflow and gravity), its walls
#                 rough with the k_s Strickler gives for the same Manning n, over the cell size (CELLS);
#   breach        the breach model foam-erosion runs beside itself on the same dam block, inflow,
#                 pool (the section's storage upstream of the dam) and time (run/breach_comparison).
# The roughness is one: mpm2grid's Manning n is the breach model's grain roughness n_s (its
# default, 0.016 s/m^(1/3): Table 2.1's silty sand, d75 about 1 mm), foam-erosion's wall the
# Nikuradse sand k_s = (21.1 n)^6. plot_three_solvers.py puts the outflow hydrographs, the crest
# (breach invert) and the eroded volume of every run of a scene on one chart and writes its table.
#   benchmarks/dam_three_solvers/run_three_solvers.sh [BUILD_DIR]
#   env: SCENES ("example2 05_hr_a"), SPACINGS ("0.25 0.125 0.0625"), CONSISTENT ("0.125") (empty: none),
#        CELLS ("0.25 0.125"), END (20 s),
#        KD (100 cm^3/(N s)), TAU_C (1 Pa), MANNING (0.016), SETTLING (0.02 m/s),
#        OUT (benchmarks/results/dam_three_solvers), WORK (the runs' folders, kept: $OUT/runs; a
#        run whose folder holds a finished summary.json is not run again, so a long study can be
#        run in parts; remove WORK to rerun), MPM_ARGS (more key=value overrides for the mpm2grid
#        runs, separated by ';') and NAME (appended to the mpm2grid runs' folders and the outputs'
#        names): the free water on its own field (docs/methods/mpm2grid.md, "Free water and pore
#        water") is MPM_ARGS=free_water_field=true NAME=_free_water
# Wall time on 2 cores, per scene: foam-erosion 40 s at 0.25 m, about 4 min at 0.125 m;
# mpm2grid about 1 / 10 / 55 min at 0.25 / 0.125 / 0.0625 m, the consistent drag at 0.125 m about
# 30 min (runs sharing the cores); two scenes run side by side with SCENES=example2 and SCENES=05_hr_a.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
here=$root/benchmarks/dam_three_solvers
scenes=${SCENES:-example2 05_hr_a} spacings=${SPACINGS-0.25 0.125 0.0625} cells=${CELLS-0.25 0.125} end=${END:-20}
consistent=${CONSISTENT-0.125}
kd=${KD:-100 cm^3/(N s)} tau_c=${TAU_C:-1 Pa} manning=${MANNING:-0.016} settling=${SETTLING:-0.02 m/s}
name=${NAME:-}
IFS=';' read -ra mpm_args <<<"${MPM_ARGS:-}"
out=${OUT:-$root/benchmarks/results/dam_three_solvers}
work=${WORK:-$out/runs}
mkdir -p "$out" "$work"
ks=$(awk -v n="$manning" 'BEGIN { printf "%.4g", (21.1 * n) ^ 6 }')  # m, Strickler: n = k_s^(1/6) / 21.1

# finished DIR END: whether DIR holds a finished run that reached END (mpm2grid: summary.json's
# end_time; foam-erosion: its status and the last erosion step's time).
finished() {
  /usr/bin/python3 - "$1" "$2" <<'EOF' 2>/dev/null
import csv, json, sys
d = json.load(open(sys.argv[1] + "/summary.json"))
if "end_time" in d:
    end = d["end_time"]
else:
    end = float(list(csv.DictReader(open(sys.argv[1] + "/erosion.csv")))[-1]["time_s"])
ok = d.get("status", "finished") == "finished" and float(end) >= float(sys.argv[2]) - 1e-6
sys.exit(0 if ok else 1)
EOF
}

for scene in $scenes; do
  mpm_scene=$root/solvers/mpm2grid/scenes/table_3_4_$scene.yaml
  [ -f "$mpm_scene" ] && [ -f "$here/$scene.foam.yaml" ] || { echo "unknown scene $scene (SCENES)" >&2; exit 2; }
  for cell in $cells; do
    run=$work/$scene/foam-$cell
    if ! finished "$run" "$end"; then
      rm -rf "$run"
      "$build/bin/foam-erosion" "$here/$scene.foam.yaml" "soil.erodibility=$kd" "soil.critical_shear_stress=$tau_c" \
        "flow.wall_roughness=$ks m" "mesh.cell_size=$cell m" "mesh.far_cell_size=$(awk "BEGIN { print 2 * $cell }") m" \
        "time.end=$end s" --out "$run" --log-level warn
    fi
    echo "$scene foam-erosion cell $cell m: $(grep -m1 -o '"eroded_area": [^,]*' "$run/summary.json")"
  done
  mpm_runs=()
  for run_drag in $(for h in $spacings; do echo "$h-lumped"; done) $(for h in $consistent; do echo "$h-consistent"; done); do
    h=${run_drag%-*} drag=${run_drag##*-}
    run=$work/$scene/mpm2grid-$h
    [ "$drag" = lumped ] || run=$run-$drag
    run=$run$name
    mpm_runs+=("--mpm" "$run")
    if ! finished "$run" "$end"; then
      rm -rf "$run"
      "$build/bin/mpm2grid" "$mpm_scene" "grid.spacing=$h m" "drag=$drag" "time.end=$end s" "time.output=1000 s" \
        "soil.erosion=excess_stress" "soil.erodibility=$kd" "soil.critical_shear_stress=$tau_c" \
        "soil.settling_velocity=$settling" "bed_shear.manning_n=$manning" "water.flip=0.99" "soil.flip=0.99" \
        ${mpm_args[@]+"${mpm_args[@]}"} --out "$run" --log-level warn
    fi
    echo "$scene mpm2grid h $h m, $drag drag: $(grep -m1 -o '"shear_eroded_volume": [^,]*' "$run/summary.json")"
  done
  {
    echo "## Table 3.4 $scene through breach, mpm2grid and foam-erosion (run_three_solvers.sh)"
    echo
    echo "One soil: kd $kd, tau_c $tau_c; Manning n $manning s/m^(1/3) (mpm2grid's bed shear, the breach"
    echo "model's grain roughness), k_s $ks m (foam-erosion's rough wall); settling velocity $settling"
    echo "(mpm2grid); $end s of flow.${MPM_ARGS:+ mpm2grid overrides: \`$MPM_ARGS\`.}"
    echo
    echo "Machine: $(uname -n), $(nproc) cores; repository at git $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown); $(date -u +%Y-%m-%dT%H:%MZ)."
    echo
    /usr/bin/python3 "$here/plot_three_solvers.py" --title "Table 3.4 $scene${MPM_ARGS:+ ($MPM_ARGS)}" \
      --out "$out/$scene$name.png" --csv "$out/$scene$name.csv" \
      $(for c in $cells; do echo "--foam $work/$scene/foam-$c"; done) "${mpm_runs[@]}"
  } | tee "$out/$scene$name.md"
done
