#!/usr/bin/env bash
# The debug-image pictures of docs/ros.md: starts a roscore on a free port, runs the broccoli and
# the potato node on a bag of a simulated sequence (rosbag play), and saves each node's 5th
# debug_image as a PNG (scripts/ros-debug-image.py).
# Usage: scripts/ros-debug-image.sh [BUILD (default build)] [OUT_DIR (default docs/images)]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}; out=${2:-docs/images}
work=$(mktemp -d); trap 'scripts/ros-master.sh stop "$work" >/dev/null; kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
scripts/ros-master.sh start "$work" >/dev/null
export ROS_MASTER_URI=$(cat "$work/master_uri") ROS_HOSTNAME=127.0.0.1 ROS_HOME="$work/ros_home"
mkdir -p "$out"
shot() {  # NAME SIMULATE_ARGS NODE_ARGS...
  local name=$1 sim=$2; shift 2
  "$build/bin/cropsight" simulate $sim --out "$work/$name-seq" >/dev/null 2>&1
  "$build/bin/cropsight" export --data "$work/$name-seq" --out "$work/$name.bag" >/dev/null
  "$build/bin/cropsight_${name}_node" __ns:=/camera "$@" >"$work/$name-node.log" 2>&1 &
  local node=$!
  scripts/ros-debug-image.py /camera/debug_image "$out/ros-debug-$name.png" 5 120 &
  local grab=$!
  sleep 3  # the node subscribes once the grabber appears (lazy inputs)
  rosbag play -q -r 0.5 "$work/$name.bag" >/dev/null 2>&1 || true
  wait $grab
  kill -INT $node; wait $node || true
}
shot broccoli "broccoli --frames 12 --seed 77" _model:=models/broccoli-oes-uk.json
shot potato "potato --scene sheet --frames 12 --seed 77" _rate:=0
