#!/usr/bin/env bash
# The rice part of the suite's main job: train a classifier of the alkali spreading value (ASV) on a
# rendered, labelled set and classify a held-out batch with it (docs/rice.md).
#   run_demo.sh BIN_DIR OUT_DIR        e.g. run_demo.sh build/release/bin suite-demo-out/rice
#
# 1. `riceasv render` draws the labelled set: two dishes of six grains per grade 2-7 (seed 1,
#    0.03 mm per pixel), one touching pair per dish (flagged, not trained on).
# 2. `riceasv train` measures it and trains the random forest on low / medium / high, with a seeded
#    train/validation/test split and 5-fold cross-validation (OUT/model/evaluation.json,
#    confusion.png).
# 3. `riceasv train --model-type cnn` trains the convolutional network on crops of the same grains
#    (OUT/cnn_model/).
# 4. `riceasv render` draws the held-out batch with another seed and pixel size (seed 11, 0.02 mm),
#    a touching pair and a grain cut by the frame per dish; `riceasv classify` classifies it with
#    each model (OUT/classified/, OUT/cnn_classified/).
# 5. confusion_held_out.py compares the classes with the rendered grades: confusion_held_out.png in
#    each and the accuracy per class.
# About 30 s on one core (the network's training, with its 5-fold cross-validation, is 15 s of it).
set -euo pipefail
BIN=$1 OUT=$2
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$OUT"
mkdir -p "$OUT"
"$BIN/riceasv" render --grades 2,3,4,5,6,7 --per-grade 12 --seed 1 --pixel-size 0.03 --touching-pairs 1 \
  --out "$OUT/labelled" --log-level warn
"$BIN/riceasv" train "$OUT/labelled/truth.csv" --pixel-size 0.03 --out "$OUT/model" --log-level warn
"$BIN/riceasv" train "$OUT/labelled/truth.csv" --pixel-size 0.03 --model-type cnn --out "$OUT/cnn_model" \
  --log-level warn
"$BIN/riceasv" render --grades 2,3,4,5,6,7 --per-grade 6 --seed 11 --pixel-size 0.02 --touching-pairs 1 \
  --frame-cut --out "$OUT/held_out" --log-level warn
for model in model cnn_model; do
  classified=$OUT/${model%model}classified
  "$BIN/riceasv" classify "$OUT/held_out" --model "$OUT/$model" --pixel-size 0.02 --out "$classified" \
    --log-level warn
  /usr/bin/python3 "$here/confusion_held_out.py" "$OUT/held_out" "$classified"
done
