#!/usr/bin/env bash
# A user mistake gives a non-zero exit status (2 when the program runs alone) and exactly one
# line from the program, "error: ...", matching every given pattern: no stack trace, and under
# mpiexec no copy from every rank (mpiexec's own notice of the exit status may follow).
#   expect_input_error.sh 'pattern1|pattern2' COMMAND...
set -uo pipefail
IFS='|' read -ra patterns <<<"$1"; shift
err=$(mktemp)
"$@" >/dev/null 2>"$err"
rc=$?
cat "$err"
if grep -q "mpiexec\|mpirun" <<<"$1 $*"; then
  [ "$rc" != 0 ] || { echo "expected a non-zero exit status"; exit 1; }
  lines=$(grep -c "^error: " "$err")
else
  [ "$rc" = 2 ] || { echo "expected exit status 2, got $rc"; exit 1; }
  lines=$(grep -c . "$err")
fi
[ "$lines" = 1 ] || { echo "expected one error line, got $lines"; exit 1; }
if grep -qE "internal error|terminate called|what\(\)|Segmentation fault|MPI_ABORT was invoked" "$err"; then
  echo "the program crashed or aborted instead of reporting the mistake"; exit 1
fi
for p in "${patterns[@]}"; do
  grep -qF -- "$p" "$err" || { echo "stderr lacks: $p"; exit 1; }
done
rm -f "$err"
