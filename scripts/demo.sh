#!/usr/bin/env bash
# `make demo` (as scripts/demo.sh BUILD_DIR): simulates a short UK-like broccoli sequence (a
# seed the shipped models never saw), validates it with `cropsight info`, runs the OES broccoli
# head detector with the shipped model (detections, masks, temporal filter and field map),
# evaluates it against the simulator's ground truth, and writes one self-contained HTML report
# with `cropsight report --model`: it opens with the result (detections over frames, field map,
# sizes, timing), then the sequence's data summary. The last line printed is the absolute path of
# the page. `make demo` builds only the `cropsight` target before running this.
set -euo pipefail

BUILD=${1:-build}
CLI="$BUILD/bin/cropsight"
if [[ ! -x "$CLI" ]]; then
  echo "demo: $CLI not found; build first (make build)" >&2
  exit 2
fi
DEMO="$BUILD/demo"
SEQ="$DEMO/uk-seq"
PAGE="$DEMO/index.html"
mkdir -p "$DEMO"

# Re-running the demo replaces its own earlier outputs: --force replaces what cropsight wrote
# there before, and nothing else (docs/cli.md, "Outputs").
force=(--force)

echo "== cropsight simulate broccoli --variety uk --frames 30 --seed 7 --out $SEQ"
"$CLI" simulate broccoli --variety uk --frames 30 --seed 7 --out "$SEQ" "${force[@]}"

echo "== cropsight info --data $SEQ"
"$CLI" info --data "$SEQ"

# The general model: the one measured best on fields it was not trained on.
MODEL=models/broccoli-oes-general.json
echo "== cropsight detect broccoli --data $SEQ --model $MODEL --track --map $DEMO/map.csv"
"$CLI" detect broccoli --data "$SEQ" --model "$MODEL" --out "$DEMO/detections.jsonl" --masks "$DEMO/masks" \
  --track --map "$DEMO/map.csv" --quiet "${force[@]}"

echo "== cropsight eval broccoli --data $SEQ --model $MODEL --track"
"$CLI" eval broccoli --data "$SEQ" --model "$MODEL" --track --quiet

echo "== cropsight report --data $SEQ --model $MODEL --out $PAGE"
"$CLI" report --data "$SEQ" --model "$MODEL" --out "$PAGE" "${force[@]}" >/dev/null

echo "demo page:"
realpath "$PAGE"
