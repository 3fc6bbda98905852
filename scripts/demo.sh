#!/usr/bin/env bash
# `make demo` (as scripts/demo.sh BUILD_DIR): simulates a short UK-like broccoli sequence,
# validates it with `cropsight info`, and writes one self-contained HTML page about it with
# `cropsight report`. The last line printed is the absolute path of the page.
# Later pipelines add their steps (train/detect/eval) before the report and pass their outputs
# to `cropsight report`.
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

# Re-running the demo replaces the previous sequence: with the simulator's --force when it has
# one (the replacement is then atomic), otherwise by removing it first.
force=()
if "$CLI" simulate broccoli --help 2>/dev/null | grep -q -- '--force'; then
  force=(--force)
else
  rm -rf "$SEQ"
fi

echo "== cropsight simulate broccoli --variety uk --frames 30 --seed 7 --out $SEQ"
"$CLI" simulate broccoli --variety uk --frames 30 --seed 7 --out "$SEQ" "${force[@]}"

echo "== cropsight info $SEQ"
"$CLI" info "$SEQ"

echo "== cropsight report --data $SEQ --out $PAGE"
"$CLI" report --data "$SEQ" --out "$PAGE" >/dev/null

echo "demo page:"
realpath "$PAGE"
