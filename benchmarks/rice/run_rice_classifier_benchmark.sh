#!/usr/bin/env bash
# Runs the rice ASV classifier benchmark of issue 32 and charts it into benchmarks/results/rice/:
#   a training pool of 30 grains per grade (five dishes of six, seed 101, 0.03 mm per pixel) and a
#   held-out set of 12 per grade (seed 202, 0.02 mm, a touching pair and a grain cut by the frame per
#   dish, which are flagged and left out) are rendered, then rice_classifier_benchmark trains on 1,
#   2, 3 and 5 dishes per grade (5 seeded choices each), three classes and six grades, random forest
#   and SVM, and classifies the held-out grains.
#
#   benchmarks/rice/run_rice_classifier_benchmark.sh [BUILD_DIR]   (default build/release)
#
# Needs the targets riceasv and rice_classifier_benchmark built in BUILD_DIR, e.g.
#   cmake --build build/release --target riceasv rice_classifier_benchmark
# Pinned to one core with taskset when it is available. About 1-2 minutes on a 2-core machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}
here=$root/benchmarks/rice
out=$root/benchmarks/results/rice
sets=$build/rice-benchmark-sets
mkdir -p "$out" "$sets"
pin=()
if command -v taskset > /dev/null; then pin=(taskset -c 0); fi

rm -rf "$sets/pool" "$sets/held_out"
"$build/bin/riceasv" render --grades 2,3,4,5,6,7 --per-grade 30 --per-image 6 --seed 101 --pixel-size 0.03 \
  --out "$sets/pool" --log-level warn
"$build/bin/riceasv" render --grades 2,3,4,5,6,7 --per-grade 12 --per-image 6 --seed 202 --pixel-size 0.02 \
  --touching-pairs 1 --frame-cut --out "$sets/held_out" --log-level warn
"${pin[@]}" "$build/bin/rice_classifier_benchmark" "$sets/pool" "$sets/held_out" 0.03 0.02 \
  "$out/rice_classifier.csv" 5

# The whole command as a lab runs it, timed: train on the pool, classify the held-out set.
start=$(date +%s.%N)
"${pin[@]}" "$build/bin/riceasv" train "$sets/pool/truth.csv" --pixel-size 0.03 --out "$sets/model" --log-level warn
mid=$(date +%s.%N)
"${pin[@]}" "$build/bin/riceasv" classify "$sets/held_out" --model "$sets/model" --pixel-size 0.02 \
  --out "$sets/classified" --log-level warn
end=$(date +%s.%N)
python3 - "$sets" "$start" "$mid" "$end" > "$out/rice_commands.csv" <<'PY'
import json, sys
sets, start, mid, end = sys.argv[1], *map(float, sys.argv[2:])
e = json.load(open(f"{sets}/model/evaluation.json"))
c = json.load(open(f"{sets}/classified/classify.json"))
print("# riceasv train on the pool (180 grains, 30 photographs at 0.03 mm) and classify on the held-out set "
      "(12 photographs at 0.02 mm), one core; seconds")
print("command,wall_s,measure_s,fit_s,predict_s_per_grain,grains,test_accuracy,cv_accuracy")
print(f"train,{mid - start:.2f},{e['times_s']['measure']:.2f},{e['times_s']['fit_final_model']:.4f},"
      f"{e['times_s']['predict_per_grain']:.2e},{e['grains']['used']},{e['test']['accuracy']:.4f},"
      f"{e['cross_validation']['pooled']['accuracy']:.4f}")
print(f"classify,{end - mid:.2f},,,{c['predict_seconds_per_grain']:.2e},{c['grains_ok']},,")
PY
cp "$sets/model/confusion.png" "$out/rice_train_confusion.png"
/usr/bin/python3 "$here/plot_rice_classifier.py" "$out/rice_classifier.csv" "$out/rice_classifier.png"
