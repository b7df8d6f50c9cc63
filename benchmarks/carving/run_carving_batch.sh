#!/usr/bin/env bash
# Batch throughput of `seedcarve batch` (issue 4's benchmark list, item 3): four synthetic seeds
# (three wheat-sized ellipsoids of different sizes and poses, and the creased grain) are rendered
# once, a manifest repeats them to ROWS rows with distinct ids, and the batch is timed from start
# to finish (MPI start-up included) on
#   1 rank  (one process measures every seed),
#   2 ranks (rank 0 hands out seeds and writes the table, 1 rank measures),
#   3 ranks (2 measuring ranks; more processes than this 2-core machine's cores, so rank 0 is told
#            to yield its core while it waits: --mca mpi_yield_when_idle 1).
# The three are run in turn, REPEATS times, so that the machine's noise falls on all alike.
#   benchmarks/carving/run_carving_batch.sh BUILD_DIR OUT.csv [REPEATS] [ROWS]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$1
csv=$2
repeats=${3:-5}
rows=${4:-40}
seedcarve=$build/bin/seedcarve
examples=$root/carving/examples/synthetic
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The seeds: name, scene, overrides.
"$seedcarve" render "$examples/wheat_ellipsoid.yaml" --out "$work/W1" --log-level warn
"$seedcarve" render "$examples/wheat_ellipsoid.yaml" --out "$work/W2" --log-level warn \
  'shape.semi_axes=[3.4, 1.4, 1.7]' 'shape.tilt=35 deg'
"$seedcarve" render "$examples/wheat_ellipsoid.yaml" --out "$work/W3" --log-level warn \
  'shape.semi_axes=[3.8, 1.55, 1.9]' 'shape.tilt=5 deg' 'shape.turn=30 deg'
"$seedcarve" render "$examples/creased_grain.yaml" --out "$work/C1" --log-level warn
seeds=(W1 W2 W3 C1)

# The manifest: the seeds in turn, each row with its own id and the seed's rendered profile.
{
  echo "id,images,method,weight_mg,profile"
  for ((i = 0; i < rows; i++)); do
    s=${seeds[i % ${#seeds[@]}]}
    printf 'S%03d-%s,%s,carving,,%s/profile.yaml\n' "$i" "$s" "$s" "$s"
  done
} > "$work/manifest.csv"

now() { date +%s.%N; }
# The median of the numbers on standard input, one a line.
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
git_hash=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
git -C "$root" diff --quiet 2>/dev/null || git_hash="$git_hash+dirty"
{
  echo "# carving_batch: host $(hostname), $(nproc) cores, $(date -u '+%Y-%m-%d %H:%M UTC'), git $git_hash," \
    "seedcarve batch of $rows rows (seeds ${seeds[*]} repeated; profiles from seedcarve render: resolution 256," \
    "search 48, mesh 128), $repeats repeats, wall time from launch to exit"
  echo "ranks,workers,mpi_options,repeat,seeds,ok,wall_s,seeds_per_s,median_seed_s,median_carve_mesh_s"
} > "$csv"

for ((r = 1; r <= repeats; r++)); do
  for ranks in 1 2 3; do
    out=$work/out_np${ranks}
    rm -rf "$out"
    options=""
    launch=("$seedcarve")
    if ((ranks > 1)); then
      launch=(mpiexec --oversubscribe --allow-run-as-root -n "$ranks")
      if ((ranks > 2)); then
        options="--mca mpi_yield_when_idle 1"
        launch+=(--mca mpi_yield_when_idle 1)
      fi
      launch+=("$seedcarve")
    fi
    start=$(now)
    "${launch[@]}" batch "$work/manifest.csv" --out "$out" --log-level warn
    end=$(now)
    workers=$((ranks > 1 ? ranks - 1 : 1))
    ok=$(grep -c ',ok,' "$out/results.csv" || true)
    # Medians of the per-seed wall time the measuring ranks wrote (results.csv column wall_s) and
    # of its share spent on cameras, carve and mesh (seed.json), the rest being reading and
    # segmenting 36 PNGs and writing the overlays and the PLY mesh.
    seed_s=$(awk -F, '/^#/ {next} $1 == "id" {for (i = 1; i <= NF; i++) if ($i == "wall_s") c = i; next} {print $c}' \
      "$out/results.csv" | median)
    carve_s=$(cat "$out"/seeds/*/seed.json | sed -n 's/.*"views_carve_and_mesh_s": *\([0-9.e+-]*\).*/\1/p' | median)
    awk -v n="$ranks" -v w="$workers" -v o="$options" -v r="$r" -v s="$rows" -v ok="$ok" -v a="$start" -v b="$end" \
      -v m="$seed_s" -v c="$carve_s" \
      'BEGIN {t = b - a; printf "%d,%d,%s,%d,%d,%d,%.3f,%.4f,%s,%s\n", n, w, o, r, s, ok, t, s / t, m, c}' |
      tee -a "$csv"
  done
done
