#!/usr/bin/env bash
# Batch throughput of `seedcarve batch` (issue 4's benchmark list, item 3; issue 30, item 6): four
# synthetic seeds (three wheat-sized ellipsoids of different sizes and poses, and the creased
# grain) are rendered once, 36 views of 640 x 480 px each, and saved in each image FORMAT (png as
# rendered; bmp, uncompressed, the Kansas State rig's format; jpg at quality 95, a camera's;
# converted with Debian's Pillow). A manifest repeats them to ROWS rows with distinct ids, and the
# batch is timed from start to finish (MPI start-up included) on
#   1 rank  (one process measures every seed, pinned to one core: the per-core rate),
#   2 ranks (rank 0 hands out seeds and writes the table, 1 rank measures),
#   3 ranks (2 measuring ranks; more processes than this 2-core machine's cores, so rank 0 is told
#            to yield its core while it waits: --mca mpi_yield_when_idle 1).
# The runs take turns, REPEATS times, so that the machine's noise falls on all alike. Each row
# also has the medians over its seeds of seed.json's phase times (reading the 36 images,
# segmenting them, measuring: carve, quality checks and mesh, writing the overlays and the mesh).
#   benchmarks/carving/run_carving_batch.sh BUILD_DIR OUT.csv [REPEATS] [ROWS] [FORMATS]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$1
csv=$2
repeats=${3:-5}
rows=${4:-40}
formats=${5:-png bmp jpg}
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

# Each seed's views in each format, beside its profile (which names no image format).
for s in "${seeds[@]}"; do
  for f in $formats; do
    [[ $f == png ]] && continue
    mkdir -p "$work/$f/$s"
    cp "$work/$s/profile.yaml" "$work/$f/$s/"
    /usr/bin/python3 - "$work/$s" "$work/$f/$s" "$f" <<'PY'
import pathlib, sys
from PIL import Image
src, dst, fmt = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3]
for view in sorted(src.glob("view_*.png")):
    image = Image.open(view).convert("RGB")
    image.save(dst / f"{view.stem}.{fmt}", **({"quality": 95} if fmt == "jpg" else {}))
PY
  done
done

# The manifests: the seeds in turn, each row with its own id and the seed's rendered profile.
for f in $formats; do
  dir=$work
  [[ $f == png ]] || dir=$work/$f
  {
    echo "id,images,method,weight_mg,profile"
    for ((i = 0; i < rows; i++)); do
      s=${seeds[i % ${#seeds[@]}]}
      printf 'S%03d-%s,%s,carving,,%s/profile.yaml\n' "$i" "$s" "$dir/$s" "$dir/$s"
    done
  } > "$work/manifest_$f.csv"
done

now() { date +%s.%N; }
# The median of the numbers on standard input, one a line.
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
git_hash=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
git -C "$root" diff --quiet 2>/dev/null || git_hash="$git_hash+dirty"
{
  echo "# carving_batch: host $(hostname), $(nproc) cores, $(date -u '+%Y-%m-%d %H:%M UTC'), git $git_hash," \
    "seedcarve batch of $rows rows (seeds ${seeds[*]} repeated; profiles from seedcarve render: resolution 256," \
    "search 48, mesh 128), $repeats repeats, wall time from launch to exit; phase columns: medians over the" \
    "seeds of seed.json times_s"
  echo "format,ranks,workers,mpi_options,repeat,seeds,ok,wall_s,seeds_per_s,median_seed_s,median_read_s,median_segment_s,median_measure_s,median_outputs_s"
} > "$csv"

# The median over the seeds of one of seed.json's "times_s" entries.
phase() { cat "$1"/seeds/*/seed.json | sed -n "/\"times_s\"/,/}/s/.*\"$2\": *\([0-9.e+-]*\).*/\1/p" | median; }

for ((r = 1; r <= repeats; r++)); do
  for f in $formats; do
    for ranks in 1 2 3; do
      out=$work/out_${f}_np${ranks}
      rm -rf "$out"
      options=""
      launch=(taskset -c 0 "$seedcarve")
      if ((ranks > 1)); then
        launch=(mpiexec --oversubscribe --allow-run-as-root -n "$ranks")
        if ((ranks > 2)); then
          options="--mca mpi_yield_when_idle 1"
          launch+=(--mca mpi_yield_when_idle 1)
        fi
        launch+=("$seedcarve")
      fi
      start=$(now)
      "${launch[@]}" batch "$work/manifest_$f.csv" --out "$out" --log-level warn
      end=$(now)
      workers=$((ranks > 1 ? ranks - 1 : 1))
      ok=$(grep -c ',ok,' "$out/results.csv" || true)
      # Median of the per-seed wall time the measuring ranks wrote (results.csv column wall_s).
      seed_s=$(awk -F, '/^#/ {next} $1 == "id" {for (i = 1; i <= NF; i++) if ($i == "wall_s") c = i; next} {print $c}' \
        "$out/results.csv" | median)
      awk -v f="$f" -v n="$ranks" -v w="$workers" -v o="$options" -v r="$r" -v s="$rows" -v ok="$ok" -v a="$start" \
        -v b="$end" -v m="$seed_s" -v rd="$(phase "$out" read_images)" -v sg="$(phase "$out" segment)" \
        -v c="$(phase "$out" measure)" -v wr="$(phase "$out" write_outputs)" \
        'BEGIN {t = b - a; printf "%s,%d,%d,%s,%d,%d,%d,%.3f,%.4f,%s,%s,%s,%s,%s\n", f, n, w, o, r, s, ok, t, s / t, m, rd, sg, c, wr}' |
        tee -a "$csv"
    done
  done
done
