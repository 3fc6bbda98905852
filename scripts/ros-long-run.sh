#!/usr/bin/env bash
# A ROS node fed for a long time (deliverable 5; docs/reliability.md, "Long runs").
# Starts a roscore, the node pinned to core 0 and bench_ros_latency on core 1, which plays a
# simulated sequence's bag (the seedling node: a simulated folder of stereo pairs) in a loop at RATE Hz for MINUTES and checks that every output equals
# the first output for the same bag frame ("differing"). Every SAMPLE seconds the node's resident
# memory (VmRSS) goes to DIR/rss.tsv; at the end one line compares the first sample after
# WARMUP seconds with the last, and the node's log is searched for errors.
#
# Usage: scripts/ros-long-run.sh [NODE=broccoli|potato|seedling] [MINUTES=30] [RATE=15] [BUILD=build]
# Environment: WARMUP (s, default 60), SAMPLE (s, default 10).
set -euo pipefail
node=${1:-broccoli}; minutes=${2:-30}; rate=${3:-15}; build=${4:-build}
warmup=${WARMUP:-60}; sample=${SAMPLE:-10}
case "$node" in broccoli | potato | seedling) ;; *) echo "ros-long-run.sh: NODE must be broccoli, potato or seedling, got '$node'" >&2; exit 2 ;; esac
[[ "$minutes" =~ ^[0-9]+$ && "$minutes" -ge 1 ]] || { echo "ros-long-run.sh: MINUTES must be a positive integer" >&2; exit 2; }
bin="$build/bin"; dir="$build/ros_long_run/$node"
for b in cropsight "cropsight_${node}_node" bench_ros_latency; do
  [[ -x "$bin/$b" ]] || { echo "ros-long-run.sh: $bin/$b not built (make build with ROS)" >&2; exit 2; }
done
mkdir -p "$dir"
scripts/ros-master.sh start "$dir" >/dev/null
trap 'kill "${sampler:-}" "${node_pid:-}" 2>/dev/null || true; scripts/ros-master.sh stop "$dir" >/dev/null' EXIT
export ROS_MASTER_URI=$(cat "$dir/master_uri") ROS_HOSTNAME=127.0.0.1 ROS_HOME="$dir/ros_home"
if [[ $node == seedling ]]; then
  [[ -f "$dir/pairs/rig.yaml" ]] ||
    "$bin/cropsight" simulate seedling --pairs 10 --calib-pairs 0 --seed 9102 --quiet --out "$dir/pairs" >/dev/null
  input=(--stereo "$dir/pairs")
else
  input=(--data "$dir/seq.bag")
fi
if [[ $node != seedling && ! -f "$dir/seq.bag" ]]; then
  if [[ $node == broccoli ]]; then
    "$bin/cropsight" simulate broccoli --frames 30 --seed 9100 --out "$dir/seq" --force >/dev/null
  else
    "$bin/cropsight" simulate potato --scene sheet --frames 30 --seed 9101 --out "$dir/seq" --force >/dev/null
  fi
  "$bin/cropsight" export --data "$dir/seq" --out "$dir/seq.bag" --force >/dev/null
fi
taskset -c 0 "$bin/cropsight_${node}_node" __ns:=/long_$node __name:=$node _rate:=0 >"$dir/node.log" 2>&1 &
node_pid=$!
: >"$dir/rss.tsv"
(
  t0=$SECONDS
  while kill -0 "$node_pid" 2>/dev/null; do
    rss=$(awk '/^VmRSS/ {print $2}' "/proc/$node_pid/status" 2>/dev/null || true)
    [[ -z "$rss" ]] || printf '%s\t%s\n' "$((SECONDS - t0))" "$rss" >>"$dir/rss.tsv"
    sleep "$sample"
  done
) &
sampler=$!
frames=$((minutes * 60 * rate))
taskset -c 1 "$bin/bench_ros_latency" "${input[@]}" --ns "/long_$node" --node "$node" --rate "$rate" \
  --frames "$frames" --warmup "$((warmup * rate))" | tee "$dir/result.json"
kill -INT "$node_pid"; wait "$node_pid" 2>/dev/null || true
node_pid=
kill "$sampler" 2>/dev/null || true; sampler=
errors=$(grep -c -i -E '\[ERROR\]|\[ WARN\]|error' "$dir/node.log" || true)
awk -v w="$warmup" -v errors="$errors" -v logfile="$dir/node.log" '
  $1 >= w && !a { a = $2; at = $1 } { b = $2; bt = $1; if ($2 > peak) peak = $2 }
  END { if (!a) { print "ros-long-run.sh: no memory sample after the warm-up" > "/dev/stderr"; exit 1 }
        printf "resident after warm-up (%d s) %.1f MiB -> end (%d s) %.1f MiB: %+.2f %%; peak %.1f MiB; %d error/warning lines in %s\n",
               at, a / 1024, bt, b / 1024, 100 * (b - a) / a, peak / 1024, errors, logfile }' "$dir/rss.tsv"
