#!/usr/bin/env bash
# Every mpm2grid benchmark in turn, then benchmarks/results/mpm2grid/README.md from their tables.
# Run on an idle machine (the timings are medians of interleaved repeats, but 2 ranks on 2 cores
# take every core).
#   benchmarks/mpm2grid/run_all.sh [MPM2GRID]      (about 73 min on 2 idle cores)
#   env: ONLY ("particle_step table_3_4_scaling message_counts rebalance drag_solver wet_soil threads
#        martin_moyce dam_convergence drag_stability soil_stiffness granular_collapse implicit_forces":
#        a subset),
#        and every driver's own variables (REPEATS, STEPS, ...) and common.sh's MPM2GRID MPIEXEC OUT NICE KEEP_RUNS
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${OUT:-$root/benchmarks/results/mpm2grid}
only=${ONLY:-particle_step table_3_4_scaling message_counts rebalance drag_solver wet_soil threads martin_moyce dam_convergence drag_stability soil_stiffness granular_collapse implicit_forces}
declare -A driver=([particle_step]=run_particle_step.sh [table_3_4_scaling]=run_table_3_4_scaling.sh
  [message_counts]=run_message_counts.sh [rebalance]=run_rebalance.sh [drag_solver]=run_drag_solver.sh
  [wet_soil]=run_wet_soil.sh [threads]=run_threads.sh
  [martin_moyce]=run_martin_moyce.sh [dam_convergence]=run_dam_convergence.sh [drag_stability]=run_drag_stability.sh
  [soil_stiffness]=run_soil_stiffness.sh [granular_collapse]=run_granular_collapse.sh
  [implicit_forces]=run_implicit_forces.sh)
for b in $only; do
  echo "=== $b"
  t0=$(date +%s)
  [ -n "${driver[$b]:-}" ] || continue
  "$here/${driver[$b]}" "$@"
  echo "=== $b: $(($(date +%s) - t0)) s"
done
{
  echo "# mpm2grid benchmark results"
  echo
  echo "Written by \`benchmarks/mpm2grid/run_all.sh\` from the tables each driver writes beside its CSV"
  echo "and PNG (\`<name>.md\`, \`<name>.csv\`, \`<name>.png\`); rerun one driver and then this script with"
  echo "ONLY=none to refresh this file. Timings are medians over repeats run in turn."
  # node_scaling needs a many-core node: run_node_scaling.sh there, node_scaling.py anywhere
  # (node_scaling_vm: the same at RANKS="1 2" on the 2-core development VM, its header has how);
  # comm_model is comm_model.py on node_scaling.csv and message_counts.csv; implicit_forces_h0.25 is
  # DAM_SPACING=0.25 REPEATS=1 NAME=implicit_forces_h0.25 run_implicit_forces.sh (about 8 min);
  # implicit_forces_closure{,_h0.25} are SCENES=example2_closure NAME=... run_implicit_forces.sh
  # (REPEATS=3, about 5 min; DAM_SPACING=0.25 REPEATS=1, about 15 min);
  # dam_convergence_bed_shear is run_dam_convergence.sh with the NAME and SCENE_ARGS its header gives;
  # threads_h0.025 is H="0.025 m" REPEATS=3 NAME=threads_h0.025 run_threads.sh (about 8 min),
  # threads_free_water MPM_ARGS=free_water_field=true CONFIGS="1x1 1x2" REPEATS=4 NAME=... (4 min).
  for b in particle_step table_3_4_scaling message_counts rebalance drag_solver wet_soil node_scaling node_scaling_vm comm_model threads threads_h0.025 \
    threads_free_water martin_moyce dam_convergence \
    dam_convergence_bed_shear drag_stability soil_stiffness granular_collapse implicit_forces implicit_forces_h0.25 \
    implicit_forces_closure implicit_forces_closure_h0.25; do
    if [ -f "$out/$b.md" ]; then
      echo
      sed 's/^## /## /' "$out/$b.md"
      echo
      if [ -f "$out/$b.png" ]; then echo "Chart: \`$b.png\`; every run: \`$b.csv\`."
      elif [ -f "$out/$b.csv" ]; then echo "Every run: \`$b.csv\`."; fi
    fi
  done
} > "$out/README.md"
echo "wrote $out/README.md"
