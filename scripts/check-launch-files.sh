#!/usr/bin/env bash
# Checks every ros/launch/*.launch: roslaunch parses it and resolves its node to the executable in
# the build tree's ROS package folder (ros/CMakeLists.txt). Needs no master.
# Usage: scripts/check-launch-files.sh BUILD/ros_package
set -euo pipefail
pkg_root=${1:?ros_package folder}
export ROS_PACKAGE_PATH="$pkg_root" ROS_HOME="${TMPDIR:-/tmp}/cropsight-launch-check-$$"
trap 'rm -rf "$ROS_HOME"' EXIT
fail=0
for f in "$pkg_root"/cropsight/launch/*.launch; do
  name=$(basename "$f")
  nodes=$(roslaunch --nodes cropsight "$name" 2>&1) || { echo "$name: roslaunch cannot parse it: $nodes"; fail=1; continue; }
  for n in $nodes; do
    args=$(roslaunch --args "$n" cropsight "$name" 2>&1) || { echo "$name: $n: $args"; fail=1; continue; }
    # The command line starts with environment assignments (ROS_MASTER_URI=..., ROS_NAMESPACE=...).
    exe=$(tr ' ' '\n' <<<"$args" | grep -v '=' | head -1)
    if [[ ! -x "$exe" || "$(basename "$exe")" != cropsight_*_node ]]; then
      echo "$name: $n resolves to '$exe', not a built cropsight node"; fail=1
    else
      echo "$name: $n -> $args"
    fi
  done
done
exit $fail
