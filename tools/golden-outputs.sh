#!/usr/bin/env bash
# Captures the outputs of the shipped models through one cropsight binary, so that a refactoring
# can be checked to change no result: run it with the binary before and after, then
# tools/golden-compare.py BEFORE AFTER (timings and paths are left out of the comparison).
#
#   tools/golden-outputs.sh BUILD/bin/cropsight OUT_DIR [DATA_DIR]
#
# DATA_DIR (default OUT_DIR/data) keeps the simulated sequences between runs; the grape clouds come
# from scripts/unpack-grape.sh. Takes about two minutes on two cores.
set -euo pipefail
bin="$(realpath "$1")"
out="$2"
here="$(cd "$(dirname "$0")/.." && pwd)"
data="${3:-$out/data}"
mkdir -p "$out" "$data"
cd "$here"
[[ -d "$data/uk-2001" ]] || "$bin" simulate broccoli --variety uk --seed 2001 --frames 50 --out "$data/uk-2001" >/dev/null
[[ -d "$data/spain-2002" ]] || "$bin" simulate broccoli --variety spain --seed 2002 --frames 20 --out "$data/spain-2002" >/dev/null
[[ -d "$data/random-wide-7001" ]] || "$bin" simulate broccoli --variety random-wide --seed 7001 --frames 10 --out "$data/random-wide-7001" >/dev/null
S="$data/uk-2001"; P="$data/spain-2002"; R="$data/random-wide-7001"
run() { local name="$1"; shift; "$bin" "$@" > "$out/$name.json" 2> "$out/$name.err" || echo "exit $?" >> "$out/$name.err"; }
run eval-oes-uk eval broccoli --data "$S" --model models/broccoli-oes-uk.json --json --quiet
run eval-org-spain eval broccoli --data "$P" --model models/broccoli-org-spain.json --json --quiet
run eval-fec-uk eval broccoli --data "$S" --model models/broccoli-fec-uk.json --json --quiet
run eval-track-poses eval broccoli --data "$S,$P" --model models/broccoli-oes-uk.json --track --json --quiet --set tracking.use_poses=true --set sizing.estimator=hull
run eval-track-fit eval broccoli --data "$P" --model models/broccoli-oes-spain.json --track --fit-size-bias --json --quiet
run detect-track detect broccoli --data "$S" --model models/broccoli-oes-uk.json --out "$out/detect.jsonl" --masks "$out/masks" --track --map "$out/map.csv" --json --quiet
# The general model (debris pass, denoising, crease split, completion, soil-following window) on a
# test pass of its own: detections, scores, masks, sizes and the field map, and its figures.
run detect-general detect broccoli --data "$R" --model models/broccoli-oes-general.json --out "$out/detect-general.jsonl" --masks "$out/masks-general" --track --map "$out/map-general.csv" --json --quiet
run eval-general eval broccoli --data "$R,$S" --model models/broccoli-oes-general.json --json --quiet
run detect-plain detect broccoli --data "$P" --model models/broccoli-fec-spain.json --out "$out/detect-plain.jsonl" --json --quiet
run report report --data "$P" --model models/broccoli-oes-spain.json --out "$out/report.html" --json
run train train broccoli --data "$P" --config broccoli-oes-spain --out "$out/train-model.json" --json --quiet
# Grape: the shipped GBDT and the fast recipe on four clouds of fold 1, one cloud segmented.
if grape="$(scripts/unpack-grape.sh 2>/dev/null)"; then
  clouds=("$grape"/points/*.txt)  # the first by name; not `ls | head -1`: under pipefail, head's
  cloud="${clouds[0]}"              # early exit kills ls with SIGPIPE and the script with it (141)
  run segment-grape segment grape --model models/grape-gbdt.json --clouds "$cloud" --out "$out/segment-grape.txt" --json
  run eval-grape eval grape --clouds "$grape" --model models/grape-gbdt-fast4096-fold1.json --fold 1/4 --limit 8 --json
fi
# Seedlings and stereo: a small simulated set.
[[ -d "$data/seedlings" ]] || "$bin" simulate seedling --seed 4711 --pairs 4 --out "$data/seedlings" >/dev/null 2>&1 || true
if [[ -d "$data/seedlings" ]]; then
  run eval-seedling eval seedling --data "$data/seedlings" --no-opencv --quiet --json
  run eval-seedling-paper eval seedling --data "$data/seedlings" --config seedling-paper --no-opencv --quiet --json
fi
[[ -d ../shared/data/middlebury ]] && run eval-stereo eval stereo --middlebury ../shared/data/middlebury --json
# The commands that format library timings, potato detections and grape bunches: their figures
# (timings left out by golden-compare.py) and output folders.
run bench-broccoli bench broccoli --data "$P" --model models/broccoli-oes-spain.json --frames 3 --variety spain --pipelines oes,fec,pcl --track --json
run bench-potato bench potato --frames 3 --repeat 1 --quiet --json
[[ -d "$data/potato" ]] || "$bin" simulate potato --seed 4712 --frames 3 --out "$data/potato" --quiet >/dev/null
run detect-potato detect potato --data "$data/potato" --out "$out/detect-potato" --overlay "$out/potato-overlay" --json
[[ -f "$data/grape-boxes.json" ]] || echo '[{"image_id":0,"category_id":1,"bbox":[250,150,140,120],"score":0.9},{"image_id":0,"category_id":2,"bbox":[300,120,30,40],"score":0.8}]' > "$data/grape-boxes.json"
run detect-grape detect grape --color "$data/potato/color/000000.png" --depth "$data/potato/depth/000000.png" --camera "$data/potato/camera.yaml" --detections "$data/grape-boxes.json" --segmenter models/grape-gbdt-fast.json --threads 1 --out "$out/detect-grape" --json
if [[ -d ../shared/data/grape/coco_train ]]; then  # the trained model is not compared: its file holds no figure
  scratch="$(mktemp -d)"
  run train-detector train detector --coco ../shared/data/grape/coco_train/annotations.json --images ../shared/data/grape/coco_train/JPEGImages --out "$scratch/det.pt" --epochs 1 --input-size 64x64 --width 8 --threads 1 --json --quiet
  rm -rf "$scratch"
fi
echo "$out"
