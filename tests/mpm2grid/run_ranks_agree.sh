#!/usr/bin/env bash
# One scene on 1 rank and on 2 ranks (the domain decomposition), compared by check_ranks_agree.py.
#   run_ranks_agree.sh WORK_DIR PYTHON EXE "MPIEXEC -n 2 ..." SCENE [OVERRIDES...]
set -euo pipefail
work=$1 python=$2 exe=$3 launch=$4
shift 4
rm -rf "$work" && mkdir -p "$work"
"$exe" "$@" --out "$work/one" --log-level warn
$launch "$exe" "$@" --out "$work/two" --log-level warn
"$python" "$(dirname "$0")/check_ranks_agree.py" "$work/one" "$work/two"
