#!/usr/bin/env bash
# The fold table of docs/experiments/2026-12-06-potato-cnn-fusion.md: the 11
# shared detection images in 3 fixed folds (sorted names, index mod 3); per fold, 300 composites
# and a CNN from the other folds' images only; each fold's CNN, alone and fused with the classical
# detector, detects on its own images; the detections are pooled and scored once over the 11, and
# each fold's models are scored on the 15 orientation shots. About 45 min on 2 cores (folds one
# after the other, one training thread each).
#   tools/potato-cnn-folds.sh BUILD_DIR OUT_DIR
# COUNT and EPOCHS (default 300, 20) only shorten a trial run; the table used the defaults.
set -euo pipefail
bin=$1/bin out=$2
count=${COUNT:-300} epochs=${EPOCHS:-20}
src=$(cd "$(dirname "$0")/.." && pwd)
data=$src/../shared/data/potato
det=$data/detection
mkdir -p "$out"
mapfile -t stems < <(ls "$det/images" | sed 's/\.jpg$//' | sort)
ap() { python3 -c "import json, sys; j = json.load(sys.stdin); print('AP50 %.3f AP75 %.3f mAP50:95 %.3f' % (j['ap50'], j['ap75'], j['map50_95']))"; }
rm -rf "$out/pooled-cnn" "$out/pooled-fusion"
mkdir -p "$out/pooled-cnn" "$out/pooled-fusion"
for k in 0 1 2; do
  fold=()
  for i in "${!stems[@]}"; do (( (i + 1) % 3 == (k + 1) % 3 )) && fold+=("${stems[$i]}"); done
  f=$out/fold$k
  rm -rf "$f" && mkdir -p "$f/held"
  for s in "${fold[@]}"; do ln -s "$det/images/$s.jpg" "$f/held/"; done
  "$bin/potato_paste" --images "$det/images" --voc "$det/annotations_voc" --out "$f/comp" --count "$count" \
    --seed 1 --exclude "$(IFS=,; echo "${fold[*]}")" 2> /dev/null
  "$bin/cropsight" train detector --coco "$f/comp/annotations.json" --images "$f/comp" --classes potato \
    --out "$f/cnn.pt" --epochs "$epochs" --input-size 416x416 --threads 1 --seed 1 --val-split 0 --json > "$f/train.json"
  "$bin/cropsight" export-detector --model "$f/cnn.pt" --out "$f/cnn.onnx" > /dev/null
  for b in cnn fusion; do
    "$bin/cropsight" detect potato --images "$f/held" --out "$f/det-$b" --set detector.backend=$b \
      --set detector.cnn_model="$f/cnn.onnx" > /dev/null
    cp "$f/det-$b"/*.txt "$out/pooled-$b/"
    echo -n "fold $k, $b, 15 orientation shots: "
    "$bin/cropsight" eval potato-detection --images "$data/orientation/rgb" --annotations "$src/data/potato-orientation-boxes" \
      --set detector.backend=$b --set detector.cnn_model="$f/cnn.onnx" --json | ap
  done
done
for b in cnn fusion; do
  echo -n "$b, 3 folds held out, 11 detection images: "
  "$bin/cropsight" eval potato-detection --images "$det/images" --annotations "$det/annotations_voc" \
    --detections "$out/pooled-$b" --json | ap
done
