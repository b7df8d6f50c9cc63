#!/usr/bin/env bash
# The largest stable time step against the drag coefficient, explicit (forward Euler) against
# implicit (lumped) drag. Scene: the water column (water_column_collapse.yaml) against a soil block
# standing beside it on the floor, as the ctest mpm2grid_explicit_drag_blow_up_stops
# (tests/mpm2grid/CMakeLists.txt), at grid.spacing a/CELLS (a/8 by default: about 1,100
# particles), time.cfl 0.9. The soil's conductivity k sets c_E = n^2 rho_w g / k (n = 0.4); the
# step is forced with time.dt_max (the wave-speed limits cap it: the dt taken is read back from
# series.csv; a run that blew up is charted at min(dt_max, that cap), since the dt its blow-up
# line names is already shortened by the runaway velocities). Each run lasts STEPS steps of dt_max (time.end = STEPS
# dt_max): stability is a per-step amplification, and a fixed step count keeps the small-dt runs
# cheap. A run is stable when it reaches its end (exit 0); an unstable explicit run stops with
# the energy blow-up line (exit 2). Per (scheme, k) the dt_max ladder is climbed until 2 runs in
# a row fail. The chart (plot_drag_stability.py) draws the stable and unstable runs, the largest
# stable dt per k and the theory 2 tau_d, tau_d = rho_red / c_E, rho_red = rho_s rho_w / (rho_s + rho_w)
# (a node where both species are whole; nodes at the water's or the soil's edge have less).
#   benchmarks/mpm2grid/run_drag_stability.sh [MPM2GRID]     (about 3 min on 2 idle cores)
#   env: CONDUCTIVITIES ("1e-3 3e-4 1e-4 3e-5 1e-5 3e-6 1e-6 3e-7 1e-7"), DT_MAX (a ladder, 1e-8 ... 3.2e-4 s),
#        STEPS (200), CELLS (8), SCHEMES ("explicit lumped"), and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
source "$(dirname "$0")/common.sh"
conductivities=${CONDUCTIVITIES:-1e-3 3e-4 1e-4 3e-5 1e-5 3e-6 1e-6 3e-7 1e-7}
dts=${DT_MAX:-1e-8 1.78e-8 3.16e-8 5.62e-8 1e-7 1.78e-7 3.16e-7 5.62e-7 1e-6 1.78e-6 3.16e-6 5.62e-6 1e-5 1.78e-5 3.16e-5 5.62e-5 1e-4 1.78e-4 3.16e-4}
steps=${STEPS:-200} cells=${CELLS:-8} schemes=${SCHEMES:-explicit lumped}
h=$(awk -v n="$cells" 'BEGIN { printf "%.10g", 57.15 / n }')
work_dir drag_stability
csv=$out/drag_stability.csv
echo "drag,conductivity_m_s,dt_max_s,end_s,exit,dt_s,blow_up_step,$("${metrics[@]}" --header)" > "$csv"
for drag in $schemes; do
  for k in $conductivities; do
    fails=0
    for dt in $dts; do
      soil="soil={density: 2000 kg/m^3, young: 1 MPa, poisson: 0.3, friction_angle: 30 deg, cohesion: 0 Pa, porosity: 0.4, conductivity: $k m/s, regions: [{box: {lo: [0.05715, 0], hi: [0.2, 0.05]}}]}"
      end=$(awk -v d="$dt" -v n="$steps" 'BEGIN { printf "%.6g", d * n }')
      run=$work/$drag-$k-$dt
      rc=$(run_one "$run" 1 "$scenes/water_column_collapse.yaml" "$soil" "drag=$drag" "grid.spacing=$h mm" time.cfl=0.9 \
        "time.dt_max=$dt s" "time.end=$end s" "time.series=$(awk -v e="$end" 'BEGIN { printf "%.6g", e / 4 }') s" \
        "time.output=$end s")
      line=$(grep -m1 "blew up" "$run.err" || true)
      bstep=$(sed -n 's/.*blew up at step \([0-9]*\) .*/\1/p' <<< "$line")
      bdt=$(sed -n 's/.*, dt = \([0-9.e+-]*\) s.*/\1/p' <<< "$line")
      row=$("${metrics[@]}" "$run")
      dt_used=${bdt:-$(cut -d, -f27 <<< "$row")}
      echo "$drag,$k,$dt,$end,$rc,$dt_used,$bstep,$row" >> "$csv"
      if [ "$rc" = 0 ]; then fails=0; else
        [ -n "$line" ] || echo "$drag k=$k dt_max=$dt: exit $rc without a blow-up line: $(tail -1 "$run.err")" >&2
        fails=$((fails + 1))
      fi
      ((fails >= 2)) && break
    done
    echo "$drag k=$k: largest stable dt $(awk -F, -v d="$drag" -v k="$k" '$1 == d && $2 == k && $5 == 0 { if ($6 > m) m = $6 } END { print m + 0 }' "$csv") s"
  done
done
{
  echo "## Drag stability: largest stable dt against the drag coefficient (run_drag_stability.sh)"
  echo
  provenance "$(ls "$work"/*/run.json | head -1)"
  echo
  $plot "$here/plot_drag_stability.py" "$csv" "$out/drag_stability.png"
} | tee "$out/drag_stability.md"
