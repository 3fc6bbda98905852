#!/usr/bin/env bash
# Throughput of `cropsight batch` against a plain loop over the same recordings, in one run on one
# machine (docs/batch.md quotes its output):
#
#   loop     `cropsight detect broccoli --track --map` over each recording in turn (one process each)
#   local/1  batch --engine local --workers 1
#   local/2  batch --engine local --workers 2
#   slurm    batch --engine slurm on the one-node cluster of scripts/slurm-local.sh (when it answers)
#
# Frames per second of wall time, and frames per CPU-second. CPU time: user+sys of the command
# (GNU time) for loop and local; for slurm the array tasks are not children of the batch process,
# so it is the sum of the shards' own CPU seconds (shard.json), which leaves out each task's
# process start (about 0.1 s) — stated beside the figure.
#
# Usage: scripts/bench-batch.sh BUILD [PASSES] [FRAMES]     (default 8 passes of 60 frames)
set -euo pipefail
build="${1:-build}"
passes="${2:-8}"
frames="${3:-60}"
cli="$(cd "$build" && pwd)/bin/cropsight"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
[[ -z ${SLURM_CONF:-} && -f /tmp/cropsight-slurm/slurm.conf ]] && export SLURM_CONF=/tmp/cropsight-slurm/slurm.conf

echo "simulating $passes passes of $frames frames in $work" >&2
recs=""
for i in $(seq 1 "$passes"); do
  "$cli" simulate broccoli --quiet --seed "$i" --frames "$frames" --out "$work/pass$i" >/dev/null
  recs+="pass$i, "
done
printf 'recordings: [%s]\npipeline: {crop: broccoli}\n' "${recs%, }" >"$work/m.yaml"
total=$((passes * frames))

# GNU time's "%e %U %S" of a command, into $work/time.
timed() { /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" >/dev/null 2>&1; }
row() {  # name wall cpu
  awk -v n="$1" -v w="$2" -v c="$3" -v f="$total" -v l="$4" \
    'BEGIN { printf "| %-8s | %6.1f | %6.1f | %7.1f | %7.1f | %s\n", n, w, c, f / w, f / c, l }'
}
echo "| engine   | wall s | CPU s | frames/s | frames/CPU-s | note"
echo "|----------|--------|-------|----------|--------------|-----"

# The plain loop: the same pipeline (the default model and preset) once per recording.
start=$(date +%s.%N)
cpu=0
for i in $(seq 1 "$passes"); do
  timed "$cli" detect broccoli --track --quiet --data "$work/pass$i" --out "$work/loop$i.jsonl" --map "$work/loop$i.csv"
  cpu=$(awk -v c="$cpu" '{ print c + $2 + $3 }' "$work/time")
done
wall=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { print e - s }')
row loop "$wall" "$cpu" "one process per recording"

for w in 1 2; do
  timed "$cli" batch --quiet --manifest "$work/m.yaml" --out "$work/local$w" --workers "$w"
  read -r wall user sys <"$work/time"
  row "local/$w" "$wall" "$(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }')" "$w worker thread(s)"
done

if scontrol ping 2>/dev/null | grep -q "is UP"; then
  timed "$cli" batch --quiet --engine slurm --mem 500M --poll 0.2 --manifest "$work/m.yaml" --out "$work/slurm"
  read -r wall _ _ <"$work/time"
  cpu=$(/usr/bin/python3 -c "import json,glob; print(sum(json.load(open(f))['cpu_s'] for f in glob.glob('$work/slurm/shards/*/shard.json')))")
  row slurm "$wall" "$cpu" "one-node cluster, $(nproc) CPUs; CPU = shards' own"
  cmp -s "$work/slurm/field-map.csv" "$work/local1/field-map.csv" && echo "(slurm map == local map: byte-equal)"
else
  echo "(slurm: no slurmctld answers; start one with scripts/slurm-local.sh start)"
fi
echo "$(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs; $passes passes x $frames frames = $total frames"
