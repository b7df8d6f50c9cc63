#!/usr/bin/env bash
# Two mpm2grid output folders hold the same results, byte for byte: summary.json, series.csv,
# profiles.csv, the XDMF series and the data of every particle file (h5diff). summary.json holds
# no wall times (those are in run.json, which is not compared).
#   same_outputs.sh DIR_A DIR_B
set -euo pipefail
a=$1 b=$2
for f in summary.json series.csv profiles.csv particles.xmf; do
  cmp "$a/$f" "$b/$f" || { echo "$f differs between $a and $b"; diff "$a/$f" "$b/$f" | head; exit 1; }
done
[ "$(ls "$a/particles")" = "$(ls "$b/particles")" ] || { echo "particle files differ in number or names"; exit 1; }
for f in "$a"/particles/*.h5; do h5diff "$f" "$b/particles/$(basename "$f")"; done
