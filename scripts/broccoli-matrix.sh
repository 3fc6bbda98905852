#!/usr/bin/env bash
# Reproduces the broccoli train/test matrix of docs/pipelines/broccoli-heads.md:
# simulates the training and test sequences (training seeds differ from test seeds), trains the
# OES, ORG and FEC models on uk and on spain, evaluates every model on both test sequences and
# times the pipelines. Results: $OUT/results/*.json.
#
#   scripts/broccoli-matrix.sh [OUT]        (default OUT=broccoli-matrix; CROPSIGHT=build/bin/cropsight)
set -euo pipefail
OUT=${1:-broccoli-matrix}
CS=${CROPSIGHT:-build/bin/cropsight}
# Seeds: training 1001 + 1003 (uk), 1002 + 1004 (spain); test 2001 (uk), 2002 (spain).
TRAIN_FRAMES=${TRAIN_FRAMES:-80}
TEST_FRAMES=${TEST_FRAMES:-50}
mkdir -p "$OUT/results" "$OUT/models"
sim() {  # variety seed frames dir
  [ -d "$OUT/$4" ] || "$CS" simulate broccoli --variety "$1" --seed "$2" --frames "$3" --out "$OUT/$4"
}
sim uk 1001 "$TRAIN_FRAMES" uk-train
sim uk 1003 "$TRAIN_FRAMES" uk-train2
sim spain 1002 "$TRAIN_FRAMES" spain-train
sim spain 1004 "$TRAIN_FRAMES" spain-train2
sim uk 2001 "$TEST_FRAMES" uk-test
sim spain 2002 "$TEST_FRAMES" spain-test
for p in oes org fec; do
  for v in uk spain; do
    "$CS" train broccoli --data "$OUT/$v-train,$OUT/$v-train2" --config "broccoli-$p-$v" \
      --out "$OUT/models/broccoli-$p-$v.json" --json --quiet > "$OUT/results/train-$p-$v.json"
    for t in uk spain; do
      "$CS" eval broccoli --data "$OUT/$t-test" --model "$OUT/models/broccoli-$p-$v.json" --json --quiet \
        > "$OUT/results/eval-$p-$v-to-$t.json"
    done
  done
done
"$CS" bench broccoli --data "$OUT/uk-test" --model "$OUT/models/broccoli-fec-uk.json" --frames 20 --json \
  > "$OUT/results/bench-uk.json"
