#!/usr/bin/env bash
# The install, moved: `cmake --install` into a temporary prefix, the prefix copied to another path
# and the original removed, then the installed CLI run from an unrelated working folder on a
# simulated pass with a shipped model given by name, and the installed Python package on the same
# pass; no installed file may hold a path of the source or build tree; a small consumer project
# builds and runs against the moved install with find_package(cropsight CONFIG). Usage: test_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(realpath "$1")
src=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" >/dev/null
cp -a "$work/prefix" "$work/moved"
rm -rf "$work/prefix"
prefix="$work/moved"
cli="$prefix/bin/cropsight"
for f in bin/cropsight lib/libcropsight_nn_torch.so share/cropsight/configs/broccoli-oes-uk.yaml \
  share/cropsight/models/broccoli-oes-general.json lib/cmake/cropsight/cropsightConfig.cmake \
  include/cropsight/io/output.hpp share/doc/cropsight/README.md; do
  [[ -e "$prefix/$f" ]] || { echo "FAIL: $f not installed"; exit 1; }
done

# No path of the build machine in an installed file (binaries included).
if leaks=$(grep -rlaF -e "$src" -e "$build" "$prefix"); then
  echo "FAIL: installed files name the source or build tree:"
  echo "$leaks"
  exit 1
fi

mkdir "$work/elsewhere"
cd "$work/elsewhere"
unset CROPSIGHT_DATA_DIR CROPSIGHT_CONFIGS CROPSIGHT_NN_BACKEND
"$cli" simulate broccoli --variety uk --frames 4 --seed 11 --quiet --out "$work/pass"
"$cli" detect broccoli --data "$work/pass" --model broccoli-oes-general --out "$work/det.jsonl" --quiet --json \
  >"$work/summary.json"
grep -q '"frames":4' "$work/summary.json" || { echo "FAIL: detect broccoli: $(cat "$work/summary.json")"; exit 1; }
[[ $(wc -l <"$work/det.jsonl") -eq 4 ]] || { echo "FAIL: det.jsonl has not 4 lines"; exit 1; }
# A preset by name, and its model relative to the preset (configs/potato-fusion.yaml -> ../models).
"$cli" harvest potato --data "$work/pass" --config potato-fusion --out "$work/h.jsonl" --quiet >/dev/null

# The Python package of the moved prefix, where the build made one (pybind11-dev): it finds the
# shipped models by name and the plugin of its own prefix, and detects what the installed CLI did.
site=$(ls -d "$prefix"/lib/python3*/dist-packages 2>/dev/null | head -1)
if [[ -n "$site" && -d "$site/cropsight" ]]; then
  PYTHONPATH="$site" /usr/bin/python3 - "$work/pass" "$work/det.jsonl" "$prefix" <<'PY' || { echo "FAIL: python package"; exit 1; }
import json, os, sys
import cropsight as cs
seq, lines, prefix = sys.argv[1:]
assert os.environ["CROPSIGHT_NN_BACKEND"] == os.path.join(prefix, "lib", "libcropsight_nn_torch.so")
pipe = cs.broccoli.Pipeline(model="broccoli-oes-general", sets={"track": False})
want = [[d["score"] for d in json.loads(line)["detections"]] for line in open(lines)]
got = [[d.score for d in pipe.process(f).detections] for f in cs.read_sequence(seq)]
assert got == want, (got, want)
PY
fi

# A C++ consumer of the moved install.
mkdir "$work/consumer"
cat >"$work/consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.22)
project(consumer LANGUAGES CXX)
find_package(cropsight 0.1 CONFIG REQUIRED)
add_executable(consumer main.cpp)
target_link_libraries(consumer PRIVATE cropsight::cropsight)
file(WRITE ${CMAKE_BINARY_DIR}/data_dir.txt "DATA_DIR=${cropsight_DATA_DIR}\n")
CMAKE
cat >"$work/consumer/main.cpp" <<'CPP'
#include <cstdio>
#include "cropsight/pipeline/broccoli/make_pipeline.hpp"
#include "cropsight/pipeline/seedling/make_pipeline.hpp"
// A program outside the prefix: its shipped models and presets by name through CROPSIGHT_DATA_DIR.
int main() {
  const auto heads = cropsight::pipeline::broccoli::make_pipeline({.model = "broccoli-oes-uk"});
  const auto seedlings = cropsight::pipeline::seedling::make_pipeline({.preset = "seedling-paper"});
  std::printf("pipelines built: broccoli %d, seedling %d\n", heads != nullptr, seedlings != nullptr);
  return heads && seedlings ? 0 : 1;
}
CPP
cmake -S "$work/consumer" -B "$work/consumer/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  >"$work/consumer.log" 2>&1 || { cat "$work/consumer.log"; echo "FAIL: find_package"; exit 1; }
cmake --build "$work/consumer/build" >>"$work/consumer.log" 2>&1 || { tail -30 "$work/consumer.log"; echo "FAIL: consumer build"; exit 1; }
CROPSIGHT_DATA_DIR=$(sed -n 's/^DATA_DIR=//p' "$work/consumer/build/data_dir.txt") "$work/consumer/build/consumer" |
  grep -q "pipelines built: broccoli 1, seedling 1" || { echo "FAIL: consumer run"; exit 1; }
echo "install: moved prefix runs, no build path inside, find_package consumer OK"
