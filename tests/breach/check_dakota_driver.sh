#!/usr/bin/env bash
# `breach --dakota params.in results.out`: variables named by scene keys, responses by summary
# keys. The results file holds the same peak outflow as a normal run with the same values (to
# the integrator's stated step independence, 1e-4: the normal run also steps onto its output
# rows); values the scene rejects give a results file that says FAIL, and exit status 0.
#   check_dakota_driver.sh BREACH WORKDIR PYTHON
set -euo pipefail
breach=$1 work=$2 python=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work"
pad() { printf '%42s %s\n' "$1" "$2"; }
{
  pad 2 variables
  printf '%21s%22s %s\n' "" 3.500000000000000e-05 soil.erodibility
  printf '%21s%22s %s\n' "" 2.000000000000000e+04 soil.undrained_shear_strength
  pad 2 functions
  pad 1 ASV_1:peak_outflow
  pad 1 ASV_2:breach_initiation_time
  pad 2 derivative_variables
  pad 1 DVV_1:soil.erodibility
  pad 2 DVV_2:soil.undrained_shear_strength
  pad 0 analysis_components
  pad 1 eval_id
} > params.in
"$breach" --dakota params.in results.out
"$breach" "soil.erodibility=3.5e-5" "soil.undrained_shear_strength=2e4" --out direct --log-level warn output.plot=false
"$python" - <<'PY'
import json
lines = [l.split() for l in open("results.out") if l.strip()]
assert [l[1] for l in lines] == ["peak_outflow", "breach_initiation_time"], lines
s = json.load(open("direct/summary.json"))
for value, key in lines:
    assert abs(float(value) / s[key] - 1) < 1e-4, (key, value, s[key])
print("dakota driver agrees with the direct run:", lines)
PY
sed -i 's/ 3.500000000000000e-05 soil.erodibility/-3.500000000000000e-05 soil.erodibility/' params.in
"$breach" --dakota params.in failed.out
grep -qi '^fail' failed.out || { echo "expected a FAIL results file"; cat failed.out; exit 1; }
echo "a rejected value gives FAIL"
