#!/usr/bin/env bash
# Two suite-demo output folders hold the same results, byte for byte: summary.json,
# discharge.csv, the XDMF series, and the data of the last field file (h5diff).
#   same_outputs.sh DIR_A DIR_B
set -euo pipefail
a=$1 b=$2
for f in summary.json discharge.csv dam_break.xmf; do
  cmp "$a/$f" "$b/$f" || { echo "$f differs between $a and $b"; diff "$a/$f" "$b/$f" | head; exit 1; }
done
last=$(ls "$a/fields" | tail -1)
h5diff "$a/fields/$last" "$b/fields/$last"
