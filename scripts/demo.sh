#!/usr/bin/env bash
# `make demo` (as scripts/demo.sh BUILD_DIR [DEMO_DIR], from the repository root): runs the five
# systems on built-in or simulated data and writes one self-contained HTML page with
# `cropsight report demo`, a chapter per system, each opening with its result picture, the figures
# the run measured and the commands that reproduce them:
#
#   broccoli  simulate a UK-like pass (a seed the shipped models never saw), detect heads with the
#             general model (detections, masks, temporal filter, field map); report demo evaluates
#             the pass against the simulator's truth
#   seedling  simulate stereo pairs, measure one pair's disparity, detect its seedling, evaluate all
#   potato    simulate an arm's approach, run the harvest loop, score it against the truth
#   grape     simulate one bunch's ROI cloud, segment it with the shipped grape-best model
#   detector  the project's CenterNet (models/potato-cnn.onnx) on two of the potato frames
#
# Nothing is read from ../shared/data and nothing is downloaded. Each system writes its own folder
# under DEMO_DIR (default BUILD_DIR/demo; the layouts are in docs/cli.md, "report demo"), with
# commands.txt listing what ran there; the page is DEMO_DIR/index.html. The broccoli chain runs
# beside the others (two processes, one per core). The last line printed is the absolute path of
# the page. `make demo` builds the CLI and the libtorch plugin (the grape network) before running
# this; tests/cli/test_demo_page.cpp runs it into a temporary folder, with DEMO_BROCCOLI_FRAMES
# (default 30, the broccoli pass's length) lowered to save time, and opens the page in Chromium.
set -euo pipefail

BUILD=${1:-build}
CLI="$BUILD/bin/cropsight"
if [[ ! -x "$CLI" ]]; then
  echo "demo: $CLI not found; build first (make demo or make build)" >&2
  exit 2
fi
DEMO=${2:-$BUILD/demo}
PAGE="$DEMO/index.html"
mkdir -p "$DEMO"/{broccoli,seedling,potato,grape,detector}

# Re-running the demo replaces its own earlier outputs: --force replaces what cropsight wrote
# there before, and nothing else (docs/cli.md, "Outputs").
force=(--force)

# step DIR ARGS...: prints and runs `cropsight ARGS`, and records it in DIR/commands.txt (shown on
# the page). jstep DIR FILE ARGS...: the same with --json, its one JSON object kept in DIR/FILE.
step() {
  local dir=$1
  shift
  echo "== cropsight $*"
  echo "cropsight $*" >>"$dir/commands.txt"
  "$CLI" "$@"
}
jstep() {
  local dir=$1 file=$2
  shift 2
  echo "== cropsight $* --json > $dir/$file"
  echo "cropsight $* --json > $dir/$file" >>"$dir/commands.txt"
  "$CLI" "$@" --json >"$dir/$file"
}
for d in broccoli seedling potato grape detector; do : >"$DEMO/$d/commands.txt"; done

# The broccoli chapter's figures come from report demo, which runs the tracking evaluation of
# `eval broccoli --track` over seq/ itself (as `report --model` does): running eval here too would
# only repeat it. The page shows the sequence's summary (what `info` prints).
broccoli() {
  local B="$DEMO/broccoli" MODEL=models/broccoli-oes-general.json
  step "$B" simulate broccoli --variety uk --frames "${DEMO_BROCCOLI_FRAMES:-30}" --seed 7 --out "$B/seq" --quiet \
    "${force[@]}"
  step "$B" detect broccoli --data "$B/seq" --model "$MODEL" --out "$B/detections.jsonl" --masks "$B/masks" \
    --track --map "$B/map.csv" --quiet "${force[@]}"
  echo "# the figures: report demo --broccoli $B --model $MODEL (the evaluation of eval broccoli --track)" \
    >>"$B/commands.txt"
}

seedling() {
  local S="$DEMO/seedling" P="$DEMO/seedling/data/pair_000"
  step "$S" simulate seedling --pairs 2 --calib-pairs 0 --seed 11 --out "$S/data" --quiet "${force[@]}"
  step "$S" stereo disparity --left "$P/left.png" --right "$P/right.png" --calib "$S/data/rig.yaml" \
    --out "$S/disparity.png" "${force[@]}"
  step "$S" detect seedling --left "$P/left.png" --right "$P/right.png" --calib "$S/data/rig.yaml" \
    --out "$S/detect.json" --mask "$S/mask.png" "${force[@]}"
  jstep "$S" eval.json eval seedling --data "$S/data" --no-opencv --quiet
}

potato() {
  local P="$DEMO/potato"
  step "$P" simulate potato --frames 12 --seed 7 --out "$P/data" --quiet "${force[@]}"
  jstep "$P" harvest.json harvest potato --data "$P/data" --out "$P/targets.jsonl" --quiet "${force[@]}"
  jstep "$P" eval.json eval potato --data "$P/data"
}

grape() {
  local G="$DEMO/grape"
  step "$G" simulate grape --seed 1 --out "$G/data" "${force[@]}"
  # One thread: the broccoli chain has the other core, and libtorch's threads spinning against it
  # cost more than they gain (the labels are the same).
  jstep "$G" segment.json segment grape --config grape-best --clouds "$G/data/cloud.txt" --out "$G/labelled.txt" \
    --threads 1 "${force[@]}"
}

# The 2D detector on two of the potato frames (the first and the middle one), with their labels
# as the truth boxes: copies under the same two names every run, nothing else replaced.
detector() {
  local D="$DEMO/detector" P="$DEMO/potato/data"
  mkdir -p "$D/images" "$D/labels"
  for f in 000000 000006; do
    cp "$P/color/$f.png" "$D/images/"
    cp "$P/labels/$f.png" "$D/labels/"
  done
  jstep "$D" detect.json detect objects --model models/potato-cnn.onnx --images "$D/images" --out "$D/objects" \
    "${force[@]}"
}

# The broccoli chain beside the rest; its lines are printed when it ends, so that they do not
# interleave with the others'.
broccoli >"$DEMO/broccoli.log" 2>&1 &
broccoli_pid=$!
seedling
potato
grape
detector
if ! wait "$broccoli_pid"; then
  cat "$DEMO/broccoli.log" >&2
  echo "demo: the broccoli chain failed" >&2
  exit 1
fi
cat "$DEMO/broccoli.log"

echo "== cropsight report demo --out $PAGE ..."
"$CLI" report demo --broccoli "$DEMO/broccoli" --model models/broccoli-oes-general.json --seedling "$DEMO/seedling" \
  --potato "$DEMO/potato" --grape "$DEMO/grape" --objects "$DEMO/detector" --out "$PAGE" --quiet "${force[@]}" \
  >/dev/null

echo "demo page:"
realpath "$PAGE"
