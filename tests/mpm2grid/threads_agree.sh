#!/usr/bin/env bash
# Threads inside a rank (OMP_NUM_THREADS; transfer/sweep_schedule.hpp): a scene on 2 threads and
# on 3 gives the same outputs byte for byte (P2G adds each node's sums in an order fixed by the
# particles, G2P and the particle updates are per particle), and agrees with one thread, which
# adds P2G's sums in the particles' order, to round-off (check_ranks_agree.py's tolerances). With
# LAUNCH (e.g. "mpiexec -n 2"), the threaded runs are also decomposed over those ranks.
# A bad OMP_NUM_THREADS is refused with one line naming it.
#   threads_agree.sh WORK_DIR PYTHON EXE SCENE [OVERRIDES...]
set -euo pipefail
work=$1 python=$2 exe=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work"
OMP_NUM_THREADS=1 "$exe" "$@" --out "$work/one" --log-level warn
OMP_NUM_THREADS=2 ${LAUNCH:-} "$exe" "$@" --out "$work/two" --log-level warn
OMP_NUM_THREADS=3 ${LAUNCH:-} "$exe" "$@" --out "$work/three" --log-level warn
grep -q '"threads_per_rank": 3' "$work/three/run.json"
"$here/same_outputs.sh" "$work/two" "$work/three"
echo "2 and 3 threads: outputs identical"
# More threads than cores (2 ranks x 2 threads on the 2-core test machine) preempt the ranks between
# their phases' clocks: the phases' sum is not checked then (check_ranks_agree.py).
ranks=1
[ -n "${LAUNCH:-}" ] && ranks=2
over=0
[ $((ranks * 2)) -gt "$(nproc)" ] && over=1
OVERSUBSCRIBED=$over "$python" "$here/check_ranks_agree.py" "$work/one" "$work/two"
OMP_NUM_THREADS=4,2 "$here/../support/expect_input_error.sh" "OMP_NUM_THREADS = '4,2'|whole number of threads" \
  "$exe" "$@" --out "$work/bad" --log-level warn
