#!/usr/bin/env bash
# Reproduces the broccoli train/test matrix of docs/pipelines/broccoli-heads.md and the sizing /
# field-map figures of docs/pipelines/broccoli-sizing-tracking.md: simulates the training and test
# sequences (training seeds differ from test seeds), trains the OES, ORG and FEC models on uk and
# on spain, evaluates every model on both test sequences, fits the size bias correction of the OES
# models on their training sequences and evaluates sizing + temporal filter + map on the test
# sequence of the same variety, and times the pipelines. Results: $OUT/results/*.json; tables:
# scripts/broccoli-tables.py $OUT/results.
#
#   scripts/broccoli-matrix.sh [OUT]        (default OUT=broccoli-matrix; CROPSIGHT=build/bin/cropsight)
#
# Environment: TRAIN_FRAMES (80), TEST_FRAMES (50); REUSE_SEQUENCES=1 keeps sequences already in
# $OUT (by default they are simulated again, so that a changed simulator never leaves stale data);
# INSTALL_MODELS=1 copies the trained models to models/ (the shipped ones).
set -euo pipefail
OUT=${1:-broccoli-matrix}
CS=${CROPSIGHT:-build/bin/cropsight}
# Seeds: training 1001 + 1003 (uk), 1002 + 1004 (spain); test 2001 (uk), 2002 (spain).
TRAIN_FRAMES=${TRAIN_FRAMES:-80}
TEST_FRAMES=${TEST_FRAMES:-50}
mkdir -p "$OUT/results" "$OUT/models"
sim() {  # variety seed frames dir
  if [ "${REUSE_SEQUENCES:-0}" = 1 ] && [ -d "$OUT/$4" ]; then return; fi
  "$CS" simulate broccoli --variety "$1" --seed "$2" --frames "$3" --out "$OUT/$4" --force --json \
    > "$OUT/results/sim-$4.json"
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

# Sizing, temporal filter and map with the OES models. The bias correction is fitted on
# the training sequences only, then applied on the test sequence of the same variety.
for v in uk spain; do
  m="$OUT/models/broccoli-oes-$v.json"
  "$CS" eval broccoli --data "$OUT/$v-train,$OUT/$v-train2" --model "$m" --track --fit-size-bias --json --quiet \
    --set tracking.use_poses=true > "$OUT/results/fit-oes-$v.json"
  for est in bbox hull; do
    sets=$(python3 -c "import json,sys; print(' '.join('--set ' + s for s in json.load(open(sys.argv[1]))['size_bias_fit'][sys.argv[2]]['set'].split()))" \
      "$OUT/results/fit-oes-$v.json" "$est")
    # shellcheck disable=SC2086
    "$CS" eval broccoli --data "$OUT/$v-test" --model "$m" --track --json --quiet --set tracking.use_poses=true \
      --set sizing.estimator="$est" $sets > "$OUT/results/track-oes-$v-$est.json"
    if [ "$est" = bbox ]; then
      "$CS" eval broccoli --data "$OUT/$v-test" --model "$m" --track --json --quiet --set tracking.use_poses=false \
        --set sizing.estimator=bbox $sets > "$OUT/results/track-oes-$v-no-odometry.json"
    fi
  done
  "$CS" eval broccoli --data "$OUT/$v-test" --model "$m" --track --json --quiet --set tracking.use_poses=true \
    > "$OUT/results/track-oes-$v-raw.json"
done

"$CS" bench broccoli --data "$OUT/uk-test" --model "$OUT/models/broccoli-fec-uk.json" --frames 20 --json \
  > "$OUT/results/bench-uk.json"
if [ "${INSTALL_MODELS:-0}" = 1 ]; then
  cp "$OUT"/models/broccoli-*.json models/
fi
