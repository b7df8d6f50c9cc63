#!/usr/bin/env bash
# Strong scaling of mpm2grid on one many-core node, and the node's own ceiling in the same run.
# Needs bash, mpirun and taskset only (no Python), so that it also runs on a node that has the
# executable, its shared libraries and an Open MPI copied over rather than the suite's packages;
# node_scaling.py reads what it leaves, on any machine with Python (results:
# benchmarks/results/mpm2grid/node_scaling.md).
#
#   benchmarks/mpm2grid/run_node_scaling.sh MPM2GRID SCENES_DIR BENCH_DIR OUT_DIR
#     MPM2GRID    the executable; SCENES_DIR solvers/mpm2grid/scenes; BENCH_DIR benchmarks/mpm2grid
#     OUT_DIR     one folder per run (run.json, series.csv, summary.json, stderr; no HDF5)
#   env: RANKS ("1 2 4 8 16"), REPEATS (2), COPIES (the node's cores: the ceiling's pinned copies),
#        CASES ("ex2 ex2fine ex2consistent ex2balanced ex2owners ex2dry ex2jacobi 3d"),
#        BIND ("--bind-to core --map-by core"),
#        HYBRID ("": none; e.g. "8x2 4x4 2x8"): ranks x threads per rank (OMP_NUM_THREADS), each
#        rank bound to its own cores (--map-by slot:PE=T), its threads to one core each; run after
#        each case's rank counts, as often, named CASE-rRANKStTHREADS-REPEAT
#
# Cases (issue 28's table): ex2 = Table 3.4 example 2 at h = 0.025 m (433k particles, 300 steps,
# every rank count, REPEATS times, the ceiling first: it also warms a fresh node's memory);
# ex2fine = h = 0.0125 m (1.73M, 100 steps, 1 and the largest rank count, once, and its ceiling);
# the other cases REPEATS times (their runs are short, a second or two at 16 ranks):
# ex2consistent = h = 0.025 m with the consistent PETSc drag (60 steps; the defaults since
# 2026-11-28: the wet soil balanced beside the particle counts, the solve's rows chosen by how
# even the owners are); at the largest rank count only (one rank is the same run as
# ex2consistent's): ex2balanced = the same with the rows in equal shares (decomposition.drag_rows:
# balanced), ex2owners = with the owners' rows, ex2dry = the defaults before (the particle counts
# alone, the owners' rows); ex2jacobi = ex2consistent with
# the point Jacobi preconditioner of before 2026-11-28 (SOR since); 3d = benchmarks'
# two_species_3d at h = 5 mm (338k, 80 steps). Runs are named CASE-rRANKS-REPEAT.
# A run's length is its step count times the dt that a 5-step probe measures, so that every run
# ends at time.end, as a user's run does.
# The ceiling: COPIES independent one-rank runs (singletons), copy i pinned to core i by taskset,
# all started at once; their step times against the lone one-rank run's are what the node allows
# (the mean copy: the node's shared memory and caches; the slowest: what ranks of equal shares,
# which wait for each other every step, can reach).
set -uo pipefail
bin=$1 scenes=$2 bench=$3 out=$4
ranks_list=${RANKS:-1 2 4 8 16} repeats=${REPEATS:-2} copies=${COPIES:-$(nproc)}
cases=${CASES:-ex2 ex2fine ex2consistent ex2balanced ex2owners ex2dry ex2jacobi 3d} bind=${BIND:---bind-to core --map-by core} hybrid=${HYBRID:-}
mkdir -p "$out"
top=$(echo "$ranks_list" | tr ' ' '\n' | sort -n | tail -1)
quiet=("time.output=1000 s" --log-level warn)

# run DIR RANKS ARGS...: one run; keeps only its small files. THREADS (environment, default 1):
# threads per rank.
run() {
  local dir=$1 ranks=$2; shift 2
  local threads=${THREADS:-1}
  rm -rf "$dir"
  local t0=$SECONDS rc=0
  if [ "$threads" != 1 ]; then
    OMP_NUM_THREADS=$threads OMP_PROC_BIND=close OMP_PLACES=cores mpirun -n "$ranks" --map-by "slot:PE=$threads" \
      --bind-to core -x OMP_NUM_THREADS -x OMP_PROC_BIND -x OMP_PLACES "$bin" "$@" "${quiet[@]}" --out "$dir" \
      2> "$dir.err" || rc=$?
  elif [ "$ranks" = 1 ]; then
    taskset -c 0 "$bin" "$@" "${quiet[@]}" --out "$dir" 2> "$dir.err" || rc=$?
  else
    # shellcheck disable=SC2086
    mpirun -n "$ranks" $bind "$bin" "$@" "${quiet[@]}" --out "$dir" 2> "$dir.err" || rc=$?
  fi
  find "$dir" -name '*.h5' -delete -o -name '*.xmf' -delete 2> /dev/null
  echo "$(basename "$dir"): rc $rc, $((SECONDS - t0)) s"
}

# end_time NAME STEPS ARGS...: the time.end of STEPS steps, from a 5-step probe's stop line.
end_time() {
  local name=$1 steps=$2; shift 2
  taskset -c 0 "$bin" "$@" time.max_steps=5 "${quiet[@]}" --out "$out/$name-probe" 2> "$out/$name-probe.err"
  rm -rf "$out/$name-probe"
  local t5
  t5=$(sed -n 's/.*stopped at step 5 (t = \([0-9.e+-]*\) s).*/\1/p' "$out/$name-probe.err")
  [ -n "$t5" ] || { echo "probe $name failed: $(tail -2 "$out/$name-probe.err")" >&2; return 1; }
  awk -v t="$t5" -v n="$steps" 'BEGIN { printf "%.6g", t / 5 * n }'
}

# ceiling NAME ARGS...: COPIES pinned singletons at once, each with its own Open MPI session
# folder (concurrent singletons sharing one clash in MPI-IO).
ceiling() {
  local name=$1; shift
  local t0=$SECONDS
  for ((i = 0; i < copies; i++)); do
    rm -rf "$out/$name-copy$i"
    OMPI_MCA_orte_tmpdir_base=/tmp/copy$i taskset -c "$i" "$bin" "$@" "${quiet[@]}" --out "$out/$name-copy$i" \
      2> "$out/$name-copy$i.err" &
  done
  wait
  find "$out" -path "*$name-copy*" \( -name '*.h5' -o -name '*.xmf' \) -delete
  echo "$name: $copies pinned copies, $((SECONDS - t0)) s"
}

{
  echo "host $(uname -n), $(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
  echo "kernel $(uname -r); mpirun $(mpirun --version 2>&1 | head -1); bind: $bind"
  date -u +%Y-%m-%dT%H:%MZ
} > "$out/machine.txt"
cat "$out/machine.txt"

# scaling NAME REPEATS RANKS_LIST ARGS...: every rank count in turn, then every HYBRID
# ranks x threads, REPEATS times.
scaling() {
  local name=$1 reps=$2 list=$3; shift 3
  for ((r = 1; r <= reps; r++)); do
    for n in $list; do run "$out/$name-r$n-$r" "$n" "$@"; done
    for rt in $hybrid; do THREADS=${rt#*x} run "$out/$name-r${rt%x*}t${rt#*x}-$r" "${rt%x*}" "$@"; done
  done
}

ex2=$scenes/table_3_4_example2.yaml
for c in $cases; do
  case $c in
    ex2) args=("$ex2" "grid.spacing=0.025 m") steps=300 reps=$repeats list=$ranks_list copy=1;;
    ex2fine) args=("$ex2" "grid.spacing=0.0125 m") steps=100 reps=1 list="1 $top" copy=1;;
    ex2consistent) args=("$ex2" "grid.spacing=0.025 m" drag=consistent) steps=60 reps=$repeats list="1 $top" copy=0;;
    ex2balanced) args=("$ex2" "grid.spacing=0.025 m" drag=consistent decomposition.drag_rows=balanced) steps=60 reps=$repeats
      list=$top copy=0;;
    ex2owners) args=("$ex2" "grid.spacing=0.025 m" drag=consistent decomposition.drag_rows=owners) steps=60 reps=$repeats
      list=$top copy=0;;
    ex2dry) args=("$ex2" "grid.spacing=0.025 m" drag=consistent decomposition.balance_wet_soil=false
      decomposition.drag_rows=owners) steps=60 reps=$repeats list=$top copy=0;;
    ex2jacobi) args=("$ex2" "grid.spacing=0.025 m" drag=consistent "petsc_options=-drag_pc_type jacobi") steps=60
      reps=$repeats list="1 $top" copy=0;;
    3d) args=("$bench/two_species_3d.yaml" "grid.spacing=0.005 m") steps=80 reps=$repeats list="1 $top" copy=0;;
    *) echo "unknown case $c (ex2 ex2fine ex2consistent ex2balanced ex2owners ex2dry ex2jacobi 3d)" >&2; continue;;
  esac
  end=$(end_time "$c" "$steps" "${args[@]}") || continue
  series=$(awk -v e="$end" 'BEGIN { printf "%.6g", e / 4 }')
  args+=("time.end=$end s" "time.series=$series s")
  [ "$copy" = 1 ] && ceiling "$c" "${args[@]}"
  scaling "$c" "$reps" "$list" "${args[@]}"
done
