#!/usr/bin/env bash
# `<exe> [args] --dakota params.in results.out` (core/dakota/analysis_driver.hpp): variables named
# by scene keys, responses by summary keys. The results file holds the same responses as a normal
# run with the same values (within TOLERANCE, relative); a value the scene rejects gives a results
# file that says FAIL, and exit status 0.
#   check_dakota_driver.sh EXE WORKDIR PYTHON TOLERANCE "KEY=VALUE ..." "RESPONSE ..." BAD_KEY=VALUE [ARGS ...]
# ARGS (a scene file, fixed overrides) go to both runs; VALUEs are numbers in the keys' SI units.
set -euo pipefail
exe=$1 work=$2 python=$3 tolerance=$4 variables=$5 responses=$6 bad=$7
shift 7
rm -rf "$work" && mkdir -p "$work" && cd "$work"
read -r -a vars <<< "$variables"
read -r -a resps <<< "$responses"
# A Dakota parameters file (standard format) for these variables and responses.
params() {  # params FILE KEY=VALUE...
  local file=$1
  shift
  {
    printf '%42s %s\n' $# variables
    for kv in "$@"; do printf '%21s%22.15e %s\n' "" "${kv#*=}" "${kv%%=*}"; done
    printf '%42s %s\n' ${#resps[@]} functions
    local i=1
    for r in "${resps[@]}"; do printf '%42s %s\n' 1 "ASV_$i:$r"; i=$((i + 1)); done
    printf '%42s %s\n' 0 derivative_variables 0 analysis_components 1 eval_id
  } > "$file"
}
params params.in "${vars[@]}"
"$exe" "$@" --dakota params.in results.out --out dakota_run --log-level warn
"$exe" "$@" "${vars[@]}" --out direct --log-level warn
"$python" - "$tolerance" "${resps[@]}" <<'PY'
import json, sys
tolerance, responses = float(sys.argv[1]), sys.argv[2:]
lines = [l.split() for l in open("results.out") if l.strip()]
assert [l[1] for l in lines] == responses, lines
s = json.load(open("direct/summary.json"))
for value, key in lines:
    assert abs(float(value) - s[key]) <= tolerance * abs(s[key]), (key, value, s[key])
print("dakota driver agrees with the direct run:", lines)
PY
# One variable set to a value the scene rejects.
bad_vars=()
for kv in "${vars[@]}"; do [ "${kv%%=*}" = "${bad%%=*}" ] && bad_vars+=("$bad") || bad_vars+=("$kv"); done
params bad.in "${bad_vars[@]}"
"$exe" "$@" --dakota bad.in failed.out --out dakota_bad --log-level warn
grep -qi '^fail' failed.out || { echo "expected a FAIL results file"; cat failed.out; exit 1; }
echo "a rejected value (${bad}) gives FAIL"
