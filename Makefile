# cropsight — top-level entry points. Each target installs what is missing (Debian packages,
# scripts/install-deps.sh), configures and builds before it runs.
#
#   make demo    the five systems on built-in (simulated) data; prints the path of the HTML page.
#                Builds only the CLI, what it needs and the libtorch plugin (not the tests,
#                benchmarks or examples)
#   make test    the test suite (ctest), but for `pip install .` from the checkout
#   make test-pip    `pip install .` offline into a venv and the installed package run (minutes:
#                a second CMake build of the library, tests/install/test_pip_install.sh)
#   make build   build only (Release, portable flags)
#   make bench   one table of the headline workloads, each beside a baseline timed in the same
#                run, with callgrind instruction counts of the broccoli stages (a few minutes;
#                JSON in $(BUILD)/bench/summary.json, tools/bench-compare A.json B.json)
#   make bench-micro   every Google Benchmark binary (bench/), JSON in $(BUILD)/bench/ (long)
#   make asan    ASan+UBSan build in build-asan/ and its tests
#   make tsan    ThreadSanitizer build in build-tsan/ and the thread-safety test (label threads)
#   make fuzz    libFuzzer harnesses (Clang, build-fuzz/): replay the seeds and past findings, then
#                fuzz every parser FUZZ_SECONDS (default 15) each; scripts/fuzz.sh for one harness
#   make format  clang-format every source file (format-check: only check)
#   make install PREFIX=DIR   the CLI, ROS nodes, plugin, presets, models, library and docs under DIR
#                (default /usr/local); the prefix can be moved afterwards (docs/library.md)
#   make package a .deb of the same (CPack) in $(BUILD)/

BUILD      ?= build
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=
# Ninja (Debian ninja-build, scripts/install-deps.sh) where it is installed: it starts a target's
# compiles while the libraries it links are still being built, where Make waits for them, and the
# unity batches make a clean build a few long compiles whose order matters on two cores. A tree
# configured before keeps its generator (cmake refuses to switch one).
GENERATOR  ?= $(if $(shell command -v ninja),Ninja,Unix Makefiles)
CTEST_ARGS ?=
# make test: test labels left out (pip: a second full build of the library, run by make test-pip).
TEST_EXCLUDE ?= ^pip$$
# make asan: the test executables to build (default: all); .ci/run names the fast modules' ones.
ASAN_TARGETS ?=
FUZZ_SECONDS ?= 15
# make fuzz: libFuzzer's random seed. Fixed, so that a CI run repeats (on a fresh build-fuzz/)
# what the same command did here; the long exploratory runs (scripts/fuzz.sh) draw a new one.
FUZZ_SEED ?= 1

# ccache: rewrite absolute paths under the checkout so that caches are shared between clones.
export CCACHE_BASEDIR := $(CURDIR)
export CCACHE_NOHASHDIR := 1

.PHONY: all deps configure build test test-pip demo bench bench-micro asan tsan fuzz format format-check clean install package

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -G "$(GENERATOR)" -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_ARGS)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	@# The real grape clouds ship as an archive; unpack it to the user cache (idempotent) so the
	@# data-driven grape tests run. Without ../shared/data they skip with a message.
	@scripts/unpack-grape.sh >/dev/null 2>&1 || echo "grape archive not unpacked: the real-cloud grape tests will skip"
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) $(if $(TEST_EXCLUDE),-LE '$(TEST_EXCLUDE)') $(CTEST_ARGS)

test-pip: build
	cd $(BUILD) && ctest --output-on-failure -L '^pip$$' $(CTEST_ARGS)

# The demo runs the CLI alone (scripts/demo.sh), so it builds the `cropsight` target and its
# dependencies, and the libtorch plugin that the grape chapter's network loads; `make test` /
# `make build` afterwards build the rest in the same tree.
demo: configure
	cmake --build $(BUILD) -j $(JOBS) --target cropsight cropsight_nn_torch
	@scripts/demo.sh $(BUILD)

PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD) --prefix "$(PREFIX)"

package: build
	cd $(BUILD) && cpack -G DEB

bench: build
	@/usr/bin/python3 scripts/bench-table.py $(BUILD)

bench-micro: build
	@scripts/bench.sh $(BUILD)

# -O1 -g1: ASan's usual optimisation, line tables for the reports; compiles faster than -O2 -g.
asan:
	@scripts/install-deps.sh
	cmake -S . -B build-asan $(if $(wildcard build-asan/CMakeCache.txt),,-G "$(GENERATOR)") -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DCROPSIGHT_SANITIZE=ON -DCROPSIGHT_BUILD_BENCH=OFF $(CMAKE_ARGS)
	cmake --build build-asan -j $(JOBS) $(if $(ASAN_TARGETS),--target $(ASAN_TARGETS))
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS)

# Pipelines in parallel threads under TSan (tests/threads/): only that test and the libraries.
# The suppressions also while building: gtest_discover_tests runs test_threads to list its tests.
tsan: export TSAN_OPTIONS = suppressions=$(CURDIR)/tests/threads/tsan.supp
tsan:
	@scripts/install-deps.sh
	cmake -S . -B build-tsan $(if $(wildcard build-tsan/CMakeCache.txt),,-G "$(GENERATOR)") -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DCROPSIGHT_TSAN=ON -DCROPSIGHT_BUILD_BENCH=OFF -DCROPSIGHT_BUILD_EXAMPLES=OFF -DCROPSIGHT_ROS=OFF $(CMAKE_ARGS)
	cmake --build build-tsan -j $(JOBS) --target test_threads
	cd build-tsan && ctest --output-on-failure -L threads

# The network-archive harness loads $(BUILD)'s libtorch plugin (scripts/fuzz.sh builds it if missing).
fuzz: configure
	@scripts/fuzz.sh replay
	@FUZZ_FRESH=1 FUZZ_ARGS="-seed=$(FUZZ_SEED) $(FUZZ_ARGS)" scripts/fuzz.sh all $(FUZZ_SECONDS)

format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

format-check:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format --dry-run --Werror

clean:
	rm -rf $(BUILD) build-asan build-tsan build-fuzz
