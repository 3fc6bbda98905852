#!/usr/bin/env bash
# CTest fixture for the ROS node tests (tests/ros/): starts a real roscore on 127.0.0.1 on a free
# port with ROS_HOME in DIR, waits until the master answers, and records its URI in DIR/master_uri;
# `stop` ends it (CTest runs the cleanup also when a test fails).
#
# Usage: scripts/ros-master.sh start|stop DIR
set -euo pipefail
cmd=${1:?start|stop}; dir=${2:?DIR}
mkdir -p "$dir"
export ROS_HOME="$dir/ros_home" ROS_HOSTNAME=127.0.0.1 ROS_IP=127.0.0.1
mkdir -p "$ROS_HOME"
case "$cmd" in
  start)
    if [[ -f "$dir/roscore.pid" ]] && kill -0 "$(cat "$dir/roscore.pid")" 2>/dev/null; then
      kill "$(cat "$dir/roscore.pid")" 2>/dev/null || true; sleep 1
    fi
    port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
    export ROS_MASTER_URI="http://127.0.0.1:$port"
    setsid roscore -p "$port" > "$dir/roscore.log" 2>&1 < /dev/null &
    echo $! > "$dir/roscore.pid"
    for _ in $(seq 1 100); do
      if /usr/bin/python3 -c "import rosgraph, sys; sys.exit(0 if rosgraph.is_master_online('$ROS_MASTER_URI') else 1)" 2>/dev/null; then
        echo "$ROS_MASTER_URI" > "$dir/master_uri"
        echo "roscore up at $ROS_MASTER_URI (ROS_HOME $ROS_HOME)"
        exit 0
      fi
      sleep 0.2
    done
    echo "ros-master.sh: roscore did not answer within 20 s; see $dir/roscore.log" >&2
    exit 1
    ;;
  stop)
    if [[ -f "$dir/roscore.pid" ]]; then
      pid=$(cat "$dir/roscore.pid")
      # roscore was started with setsid: its process group holds rosmaster and rosout too.
      kill -INT -- "-$pid" 2>/dev/null || kill -INT "$pid" 2>/dev/null || true
      for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -KILL -- "-$pid" 2>/dev/null || true
      rm -f "$dir/roscore.pid" "$dir/master_uri"
    fi
    echo "roscore stopped"
    ;;
  *) echo "usage: $0 start|stop DIR" >&2; exit 2 ;;
esac
