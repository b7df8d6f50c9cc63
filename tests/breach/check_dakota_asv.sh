#!/usr/bin/env bash
# breach as a Dakota driver honours the active set vector and --out: a parameters file asking for
# the second of two responses only (ASV 0, 1) gets one value back, labelled peak_outflow (Dakota
# counts the values it expects from the ASV), and the evaluation's outputs stay in --out.
#   check_dakota_asv.sh BREACH WORKDIR
set -euo pipefail
breach=$1 work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work"
{
  printf '%42s %s\n' 1 variables
  printf '%21s%22.15e %s\n' '' 3.5e-5 soil.erodibility
  printf '%42s %s\n' 2 functions 0 ASV_1:breach_initiation_time 1 ASV_2:peak_outflow
  printf '%42s %s\n' 0 derivative_variables 0 analysis_components 1 eval_id
} > params.in
"$breach" --dakota params.in results.out --out kept --log-level warn output.plot=false
cat results.out
[ "$(grep -c . results.out)" = 1 ] || { echo "expected one value for ASV (0, 1)"; exit 1; }
grep -q ' peak_outflow$' results.out || { echo "expected the peak_outflow value"; exit 1; }
[ -s kept/summary.json ] || { echo "--out kept no summary.json"; exit 1; }
echo "ASV (0, 1): one value; --out kept the evaluation's outputs"
