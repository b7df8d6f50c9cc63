#!/usr/bin/env bash
# Two suite-demo output folders hold the same results, byte for byte: summary.json,
# discharge.csv, the XDMF series, and the data of every field file (h5diff).
#   same_outputs.sh DIR_A DIR_B
set -euo pipefail
a=$1 b=$2
for f in summary.json discharge.csv dam_break.xmf; do
  cmp "$a/$f" "$b/$f" || { echo "$f differs between $a and $b"; diff "$a/$f" "$b/$f" | head; exit 1; }
done
[ "$(ls "$a/fields")" = "$(ls "$b/fields")" ] || { echo "the field files differ in number or names"; exit 1; }
for f in "$a"/fields/*.h5; do
  h5diff "$f" "$b/fields/$(basename "$f")"
done
