#!/usr/bin/env bash
# The dissertation's multidim study (216 breach runs) through `study`: run, lose the tables and
# the last part of the ledger as a kill would, resume, and compare with an uninterrupted run;
# then the dissertation's trends (peak outflow rises with Kd and strongly with Scale) and the
# charts (scatter matrix, peak-outflow surfaces per Scale).
#   check_dissertation_study.sh STUDY SPEC WORKDIR PYTHON
set -euo pipefail
study=$1 spec=$2 work=$3 python=$4
rm -rf "$work"
"$study" run "$spec" --out "$work/whole" --log-level warn
"$study" run "$spec" --out "$work/killed" --log-level warn output.plot=false
head -n 100 "$work/killed/ledger.jsonl" > "$work/killed/l" && mv "$work/killed/l" "$work/killed/ledger.jsonl"
rm "$work/killed/tabular.dat" "$work/killed/tabular.csv" "$work/killed/analysis.json"
"$study" resume "$work/killed" --log-level warn
cmp "$work/whole/tabular.dat" "$work/killed/tabular.dat"
cmp "$work/whole/analysis.json" "$work/killed/analysis.json"
"$python" - "$work/whole" <<'PY'
import json, sys
a = json.load(open(sys.argv[1] + "/analysis.json"))
lines = open(sys.argv[1] + "/tabular.dat").read().splitlines()
assert len(lines) == 217, f"216 rows and a header, got {len(lines)} lines"
assert a["failed"] == 0, a["failed"]
import os
for chart in ("scatter_matrix.png", "surface_peak_outflow.png"):
    path = os.path.join(sys.argv[1], chart)
    assert os.path.getsize(path) > 10000, f"{chart} missing or empty"
    assert open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n", f"{chart} is not a PNG"
pr = a["correlations"]["partial_rank"]  # inputs x responses: Kd, Us, Scale x peak_outflow, ...
assert pr[0][0] > 0.5, f"peak outflow should rise with Kd: partial rank {pr[0][0]}"
assert pr[2][0] > 0.9, f"peak outflow should rise strongly with Scale: partial rank {pr[2][0]}"
print("dissertation study: partial rank correlations of peak outflow with Kd, Us, Scale:",
      [round(r[0], 3) for r in pr])
PY
