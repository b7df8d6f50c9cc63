#!/usr/bin/env bash
# Runs the rice ASV classifier benchmark of issue 32 and charts it into benchmarks/results/rice/:
#   a training pool of 30 grains per grade (five dishes of six, seed 101, 0.03 mm per pixel) and a
#   held-out set of 12 per grade (seed 202, 0.02 mm, a touching pair and a grain cut by the frame per
#   dish, which are flagged and left out) are rendered, then rice_classifier_benchmark trains on 1,
#   2, 3 and 5 dishes per grade (5 seeded choices each; 3 for the network), three classes and six
#   grades, random forest, SVM and the convolutional network, and classifies the held-out grains.
#
#   benchmarks/rice/run_rice_classifier_benchmark.sh [BUILD_DIR] [BLEND]   (default build/release, 0)
#
# BLEND P renders both sets with `riceasv render --blend P` (a share P of the grains drawn with a
# neighbouring grade's appearance) and writes its results with the suffix _blend<P>; the chart then
# marks the best accuracy a classifier can expect (1 - P/3 for three classes, 1 - 5P/6 for grades).
#
# Needs the targets riceasv and rice_classifier_benchmark built in BUILD_DIR, e.g.
#   cmake --build build/release --target riceasv rice_classifier_benchmark
# Pinned to one core with taskset when it is available. About 10 minutes on a 2-core machine (the
# network's 5-fold trainings take nearly all of it).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
blend=${2:-0}
suffix=
[ "$blend" = 0 ] || suffix=_blend$blend
here=$root/benchmarks/rice
out=$root/benchmarks/results/rice
sets=$build/rice-benchmark-sets$suffix
mkdir -p "$out" "$sets"
pin=()
if command -v taskset > /dev/null; then pin=(taskset -c 0); fi

rm -rf "$sets/pool" "$sets/held_out"
"$build/bin/riceasv" render --grades 2,3,4,5,6,7 --per-grade 30 --per-image 6 --seed 101 --pixel-size 0.03 \
  --blend "$blend" --out "$sets/pool" --log-level warn
"$build/bin/riceasv" render --grades 2,3,4,5,6,7 --per-grade 12 --per-image 6 --seed 202 --pixel-size 0.02 \
  --touching-pairs 1 --frame-cut --blend "$blend" --out "$sets/held_out" --log-level warn
"${pin[@]}" "$build/bin/rice_classifier_benchmark" "$sets/pool" "$sets/held_out" 0.03 0.02 \
  "$out/rice_classifier$suffix.csv" 5 3

# The whole command as a lab runs it, timed: train on the pool, classify the held-out set; the forest
# (default) and the network.
timed() {  # timed NAME MODEL_ARGS...: train and classify, seconds of each into $sets/NAME.times
  local name=$1 start mid end
  shift
  start=$(date +%s.%N)
  "${pin[@]}" "$build/bin/riceasv" train "$sets/pool/truth.csv" --pixel-size 0.03 "$@" --out "$sets/$name" \
    --log-level warn
  mid=$(date +%s.%N)
  "${pin[@]}" "$build/bin/riceasv" classify "$sets/held_out" --model "$sets/$name" --pixel-size 0.02 \
    --out "$sets/$name-classified" --log-level warn
  end=$(date +%s.%N)
  echo "$start $mid $end" > "$sets/$name.times"
}
timed model
timed cnn-model --model-type cnn
python3 - "$sets" > "$out/rice_commands$suffix.csv" <<'PY'
import json, sys
sets = sys.argv[1]
print("# riceasv train on the pool (180 grains, 30 photographs at 0.03 mm) and classify on the held-out set "
      "(12 photographs at 0.02 mm), one core; seconds")
print("model,command,wall_s,measure_s,fit_s,predict_s_per_grain,grains,test_accuracy,cv_accuracy")
for name, model in (("model", "rtrees"), ("cnn-model", "cnn")):
    start, mid, end = map(float, open(f"{sets}/{name}.times").read().split())
    e = json.load(open(f"{sets}/{name}/evaluation.json"))
    c = json.load(open(f"{sets}/{name}-classified/classify.json"))
    print(f"{model},train,{mid - start:.2f},{e['times_s']['measure']:.2f},{e['times_s']['fit_final_model']:.4f},"
          f"{e['times_s']['predict_per_grain']:.2e},{e['grains']['used']},{e['test']['accuracy']:.4f},"
          f"{e['cross_validation']['pooled']['accuracy']:.4f}")
    print(f"{model},classify,{end - mid:.2f},,,{c['predict_seconds_per_grain']:.2e},{c['grains_ok']},,")
PY
cp "$sets/model/confusion.png" "$out/rice_train_confusion$suffix.png"
cp "$sets/cnn-model/confusion.png" "$out/rice_train_cnn_confusion$suffix.png"
/usr/bin/python3 "$here/plot_rice_classifier.py" "$out/rice_classifier$suffix.csv" "$out/rice_classifier$suffix.png" \
  "$blend"
