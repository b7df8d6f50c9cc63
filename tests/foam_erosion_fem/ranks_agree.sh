#!/usr/bin/env bash
# foam-erosion with interFoam on 2 ranks (decomposePar, mpirun, reconstructPar before each
# erosion step, decomposePar again after each re-mesh) against the same run on 1 rank: the
# decomposition only changes the round-off path of the linear solvers (p_rgh to 1e-7), so the
# eroded area and the water volume over the crest must agree within 1%.
#   ranks_agree.sh FOAM_EROSION WORK_DIR
set -euo pipefail
bin=$1 work=$2
scene=("reservoir.initial_level=0.368 m" "coupling.morphological_factor=300" "time.end=1 s")
rm -rf "$work" && mkdir -p "$work"
for n in 1 2; do "$bin" "${scene[@]}" "run.ranks=$n" --out "$work/np$n" --log-level warn; done
grep -q "nProcs : 2" "$work/np2/logs/log.interFoam" || { echo "the 2-rank run did not run interFoam on 2 ranks"; exit 1; }
eroded() { tail -1 "$1/erosion.csv" | cut -d, -f4; }
crest_volume() {  # integral of the crest discharge over time
  awk -F, 'NR > 2 { v += ($1 - t) * $3 } NR > 1 { t = $1 } END { printf "%.9g", v }' "$1/discharge.csv"
}
check() {  # name a b
  awk -v n="$1" -v a="$2" -v b="$3" 'BEGIN {
    d = (a - b) / a; if (d < 0) d = -d
    printf "%s: 1 rank %s, 2 ranks %s, relative difference %.2g\n", n, a, b, d
    exit (d <= 0.01 ? 0 : 1) }'
}
check "eroded area (m^2/m)" "$(eroded "$work/np1")" "$(eroded "$work/np2")"
check "crest water volume (m^3)" "$(crest_volume "$work/np1")" "$(crest_volume "$work/np2")"
