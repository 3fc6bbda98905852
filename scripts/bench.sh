#!/usr/bin/env bash
# Runs every micro-benchmark binary in BUILD/bin (bench_*), writing JSON to BUILD/bench/.
set -euo pipefail
BUILD=${1:-build}
mkdir -p "$BUILD/bench"
shopt -s nullglob
for b in "$BUILD"/bin/bench_*; do
  name=$(basename "$b")
  echo "== $name"
  "$b" --benchmark_out="$BUILD/bench/$name.json" --benchmark_out_format=json
done
