#!/usr/bin/env bash
# Fuzzes cropsight's parsers with libFuzzer (docs/reliability.md, "Fuzzing").
#
#   scripts/fuzz.sh NAME SECONDS     one harness (fuzz/fuzz_NAME.cpp) for SECONDS of wall time
#                                    (of the fuzzer's own CPU time with FUZZ_CPU=1)
#   scripts/fuzz.sh all SECONDS      every harness in turn, SECONDS each
#   scripts/fuzz.sh replay           every harness once over its seeds and past findings (ctest -L fuzz)
#   scripts/fuzz.sh list             the harness names
#
# Configures and builds build-fuzz/ (Clang 14, -fsanitize=fuzzer,address,undefined) on first use.
# Each harness starts from its committed seeds (fuzz/corpus/NAME/) plus what earlier runs found
# (build-fuzz/fuzz-corpus/NAME/, not committed); a crashing input is saved under
# build-fuzz/fuzz-artifacts/NAME/ and the script exits 1. One line per run is printed and
# appended to build-fuzz/fuzz-runs.tsv (date, harness, seconds, executions, coverage, result).
# The network-archive harness loads the regular build's libtorch plugin (build/, built if
# missing): Clang cannot compile libtorch's headers as C++20.
#
# Environment: FUZZ_BUILD (default build-fuzz), MAIN_BUILD (default build), FUZZ_JOBS (default 1:
# parallel libFuzzer workers; each counts its own CPU time), FUZZ_ARGS (extra libFuzzer flags),
# FUZZ_FRESH (non-empty: start from the committed seeds only, in build-fuzz/fuzz-corpus-fresh/,
# not from what earlier runs found; make fuzz sets it so that a run here starts where CI does),
# FUZZ_CPU (non-empty: SECONDS counts the fuzzer's CPU time, user + system, read from /proc, not
# wall time: for the issue's "30 CPU-minutes per harness" on a machine whose cores are shared,
# e.g. `FUZZ_CPU=1 nice -n 19 scripts/fuzz.sh camera_yaml 1800` uses only the idle cycles).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${FUZZ_BUILD:-build-fuzz}
main_build=${MAIN_BUILD:-build}
jobs=${FUZZ_JOBS:-1}

usage() { echo "usage: scripts/fuzz.sh NAME|all|list SECONDS" >&2; exit 2; }
harnesses() { ls fuzz/fuzz_*.cpp | sed 's|fuzz/fuzz_||; s|\.cpp$||' | grep -v '^support$'; }

[ $# -ge 1 ] || usage
if [ "$1" = list ]; then harnesses; exit 0; fi
if [ "$1" = replay ]; then
  [ $# -eq 1 ] || usage
  name=all seconds=0
else
  [ $# -eq 2 ] || usage
  name=$1 seconds=$2
  [[ "$seconds" =~ ^[0-9]+$ ]] && [ "$seconds" -ge 1 ] || { echo "scripts/fuzz.sh: SECONDS must be a positive integer, got '$seconds'" >&2; exit 2; }
fi
if [ "$name" != all ] && ! harnesses | grep -qx "$name"; then
  echo "scripts/fuzz.sh: no harness '$name' (scripts/fuzz.sh list)" >&2; exit 2
fi
command -v clang++-14 >/dev/null || { echo "scripts/fuzz.sh: clang++-14 not found (scripts/install-deps.sh installs it)" >&2; exit 2; }

export CCACHE_BASEDIR=$root CCACHE_NOHASHDIR=1
if [ ! -f "$build/CMakeCache.txt" ]; then
  # -O1 with line tables: libFuzzer's usual build; no NDEBUG, so assertions are checked too.
  cmake -S . -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" \
    -DCROPSIGHT_FUZZ=ON -DCROPSIGHT_BUILD_TESTS=OFF -DCROPSIGHT_BUILD_BENCH=OFF -DCROPSIGHT_BUILD_EXAMPLES=OFF \
    "-DCROPSIGHT_FUZZ_NN_BACKEND=$root/$main_build/lib/libcropsight_nn_torch.so" >/dev/null
fi
if [ "$name" = all ]; then target=fuzzers; else target=fuzz_$name; fi
cmake --build "$build" --target "$target" -j "$(nproc)" >/dev/null

plugin=$root/$main_build/lib/libcropsight_nn_torch.so
need_plugin() {
  [ -f "$plugin" ] && return 0
  if [ -f "$main_build/CMakeCache.txt" ]; then
    echo "scripts/fuzz.sh: building the libtorch plugin in $main_build/" >&2
    cmake --build "$main_build" --target cropsight_nn_torch -j "$(nproc)" >/dev/null && return 0
  fi
  return 1
}

# LeakSanitizer stays on: a parser that leaks on bad input is a finding too.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
# Leaks inside third-party libraries that cropsight cannot free are listed, with reasons, in fuzz/lsan.supp.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/fuzz/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
if [ "$1" = replay ]; then
  need_plugin || echo "scripts/fuzz.sh: no libtorch plugin (make build): fuzz_network_archive_replay will fail" >&2
  cd "$build" && exec ctest -L fuzz --output-on-failure -j "$(nproc)"
fi

# User + system CPU seconds of process PID and of its children it has waited for (fields 14-17 of
# /proc/PID/stat, in clock ticks: with FUZZ_JOBS > 1 libFuzzer's fork mode runs the fuzzing in
# children); the command name in field 2 may hold spaces, so count from the closing parenthesis.
cpu_seconds() {
  local stat
  stat=$(cat "/proc/$1/stat" 2>/dev/null) || { echo 0; return; }
  echo "${stat##*) }" | awk -v hz="$(getconf CLK_TCK)" '{print int(($12 + $13 + $14 + $15) / hz)}'
}

failed=0
run_one() {
  local h=$1
  if [ "$h" = network_archive ] && ! need_plugin; then
    echo "fuzz $h: skipped (no libtorch plugin: run make build first)"; return 0
  fi
  [ "$h" != bag ] || [ -x "$build/bin/fuzz_bag" ] || { echo "fuzz bag: skipped (built without ROS)"; return 0; }
  local corpus=$build/fuzz-corpus/$h artifacts=$build/fuzz-artifacts/$h log=$build/fuzz-logs/$h.log
  if [ -n "${FUZZ_FRESH:-}" ]; then
    # Only the committed seeds: what a fresh clone (CI) starts from, so a run here repeats CI's.
    corpus=$build/fuzz-corpus-fresh/$h
    rm -rf "$corpus"
  fi
  mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
  local status=0 fork= t0=$SECONDS
  [ "$jobs" -le 1 ] || fork=-fork=$jobs
  local limit=-max_total_time=$seconds
  # CPU mode: no wall limit; a watchdog interrupts the fuzzer once its CPU time reaches SECONDS
  # (SIGINT: libFuzzer prints its final stats and exits 72; clang 14's libFuzzer has no
  # -interrupted_exitcode flag, so that exit after our own SIGINT counts as a clean end).
  [ -z "${FUZZ_CPU:-}" ] || limit="-max_total_time=0"
  CROPSIGHT_NN_BACKEND=$plugin "$build/bin/fuzz_$h" $limit -timeout=30 -rss_limit_mb=2560 \
    -print_final_stats=1 -artifact_prefix="$artifacts/" $fork ${FUZZ_ARGS:-} \
    "$corpus" "fuzz/corpus/$h" >"$log" 2>&1 &
  local pid=$! cpu=0 interrupted=
  if [ -n "${FUZZ_CPU:-}" ]; then
    while kill -0 "$pid" 2>/dev/null; do
      cpu=$(cpu_seconds "$pid")
      if [ "$cpu" -ge "$seconds" ]; then interrupted=1; kill -INT "$pid" 2>/dev/null || true; break; fi
      sleep 5
    done
  fi
  wait "$pid" || status=$?
  if [ -n "$interrupted" ] && [ "$status" -eq 72 ] && grep -q 'libFuzzer: run interrupted' "$log"; then status=0; fi
  local execs cov result elapsed=$((SECONDS - t0))
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | awk '{s += $2} END {if (NR) print s}')
  [ -n "$execs" ] || execs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo "?")
  if [ "$status" -eq 0 ]; then result=ok; else result="FINDING (exit $status; input in $artifacts/, log $log)"; failed=1; fi
  local cpu_note=
  [ -z "${FUZZ_CPU:-}" ] || cpu_note=" wall, ${cpu} s CPU"
  echo "fuzz $h: ${elapsed} s${cpu_note} (of $seconds), ${execs:-?} executions, coverage ${cov:-?} edges: $result"
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%FT%TZ)" "$h" "${elapsed}${FUZZ_CPU:+ s wall, $cpu s CPU}" "${execs:-?}" "${cov:-?}" "$result" >>"$build/fuzz-runs.tsv"
  if [ "$status" -ne 0 ]; then grep -m5 -E 'ERROR|escaped|runtime error|SUMMARY' "$log" >&2 || tail -5 "$log" >&2; fi
}

if [ "$name" = all ]; then
  for h in $(harnesses); do run_one "$h"; done
else
  run_one "$name"
fi
exit $failed
