#!/usr/bin/env bash
# Peak memory of `cropsight import --data BAG` against the bag's length: a simulated pass of 30
# frames is repeated (hard links, times 1/7.5 s apart) to sequences of each frame count, exported
# to a bag with depth and colour, and imported while GNU time records the peak resident set size.
# Memory flat in the length is the goal (a 9,000-frame bag, 5 minutes at 30 fps, under 300 MB).
#
#   bench/bag_import_rss.sh [BUILD_DIR] [FRAME_COUNTS...]    default: build 300 3000
#   CROPSIGHT_BASELINE=/path/to/other/cropsight  also measures that binary on the same bags
#
# Prints one line per run: frames, bag size, peak RSS (MB), wall seconds. Needs ~1.1 MB of disk
# per frame for the bag and about as much for the imported sequence (under $TMPDIR, removed).
set -euo pipefail
build=${1:-build}
shift || true
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(300 3000)
cli=$(realpath "$build/bin/cropsight")
work=$(mktemp -d "${TMPDIR:-/tmp}/cropsight-bag-rss.XXXXXX")
trap 'rm -rf "$work"' EXIT

"$cli" simulate broccoli --frames 30 --seed 11 --out "$work/base" > /dev/null 2>&1
measure() {  # binary, bag, frames
  local out="$work/imported" log="$work/time.log"
  rm -rf "$out"
  /usr/bin/time -f '%M %e' -o "$log" "$1" import --data "$2" --out "$out" > /dev/null
  read -r kb seconds < "$log"
  printf '%-32s frames %5d  bag %6d MB  peak RSS %6.1f MB  %6.1f s\n' "$1" \
    "$3" "$(( $(stat -c %s "$2") / 1000000 ))" "$(echo "$kb / 1000" | bc -l)" "$seconds"
  rm -rf "$out"
}
for n in "${counts[@]}"; do
  seq="$work/seq-$n"
  mkdir -p "$seq/depth" "$seq/color"
  cp "$work/base/camera.yaml" "$seq/"
  echo "frame,timestamp" > "$seq/timestamps.csv"
  for ((i = 0; i < n; i++)); do
    name=$(printf '%06d.png' "$i")
    src=$(printf '%06d.png' $((i % 30)))
    ln "$work/base/depth/$src" "$seq/depth/$name"
    ln "$work/base/color/$src" "$seq/color/$name"
    echo "$i,$(echo "$i / 7.5" | bc -l)" >> "$seq/timestamps.csv"
  done
  "$cli" export --data "$seq" --out "$work/$n.bag" > /dev/null
  rm -rf "$seq"
  measure "$cli" "$work/$n.bag" "$n"
  # The baseline only up to 300 frames: a binary that holds the bag in memory needs gigabytes beyond.
  if [ -n "${CROPSIGHT_BASELINE:-}" ] && [ "$n" -le 300 ]; then measure "$(realpath "$CROPSIGHT_BASELINE")" "$work/$n.bag" "$n"; fi
  rm -f "$work/$n.bag"
done
