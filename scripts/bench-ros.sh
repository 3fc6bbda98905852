#!/usr/bin/env bash
# Latency and dropped messages of the ROS nodes at a fixed input rate (docs/ros.md).
# Starts a roscore (scripts/ros-master.sh), simulates a broccoli and a potato sequence, writes
# them as bags, and for each node: the node pinned to core 0 (single-threaded, as on a robot's
# one spare core), bench_ros_latency on core 1 publishing at RATE Hz, one JSON line each.
#
# Usage: scripts/bench-ros.sh [BUILD=build] [RATE=30] [FRAMES=300] [NODE_PARAMS, e.g. _exact_sync:=false]
set -euo pipefail
build=${1:-build}; rate=${2:-30}; frames=${3:-300}; params=${4:-}
bin="$build/bin"; dir="$build/ros_bench"
mkdir -p "$dir"
scripts/ros-master.sh start "$dir" >/dev/null
trap 'kill "${node_pid:-}" 2>/dev/null || true; scripts/ros-master.sh stop "$dir" >/dev/null' EXIT
export ROS_MASTER_URI=$(cat "$dir/master_uri") ROS_HOSTNAME=127.0.0.1 ROS_HOME="$dir/ros_home"
[[ -d "$dir/broccoli" ]] || "$bin/cropsight" simulate broccoli --frames 30 --seed 9100 --out "$dir/broccoli" >/dev/null 2>&1
[[ -d "$dir/potato" ]] || "$bin/cropsight" simulate potato --scene sheet --frames 30 --seed 9101 --out "$dir/potato" >/dev/null 2>&1
for n in broccoli potato; do
  [[ -f "$dir/$n.bag" ]] || "$bin/cropsight" export --data "$dir/$n" --out "$dir/$n.bag" >/dev/null
  taskset -c 0 "$bin/cropsight_${n}_node" __ns:=/bench_$n __name:=$n _rate:=0 $params > "$dir/$n-node.log" 2>&1 &
  node_pid=$!
  taskset -c 1 "$bin/bench_ros_latency" --bag "$dir/$n.bag" --ns /bench_$n --node $n --rate "$rate" --frames "$frames"
  kill -INT $node_pid; wait $node_pid 2>/dev/null || true
  node_pid=
done
