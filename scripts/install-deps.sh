#!/usr/bin/env bash
# Installs every build and run dependency of cropsight from Debian packages.
# Idempotent: does nothing when everything is present; runs `apt-get update` only when a
# package is missing and apt cannot find it in its current lists.
#
# Usage: scripts/install-deps.sh [--check]   (--check: only report what is missing, exit 1 if any)
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git lld
  # core libraries (ARCHITECTURE.md "Dependencies")
  libeigen3-dev libopencv-dev libopencv-dnn-dev libpcl-dev libnanoflann-dev libtbb-dev libsvm-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  # Pascal VOC XML annotations (potato detection)
  libtinyxml2-dev zlib1g-dev
  # neural networks and gradient-boosted trees
  libtorch-dev libxgboost-dev
  # the detector's ONNX export writes onnx::ModelProto
  libonnx-dev
  # fast BLAS for libtorch/OpenCV (the generic libblas.so.3 is the slow reference one)
  libopenblas0-pthread
  # tests and benchmarks (python3-onnx: the tiny ONNX graphs of tests/nn/test_onnx_detector.cpp)
  libgtest-dev libgmock-dev libbenchmark-dev python3-onnx
  # cv::rgbd::registerDepth, the reference the colour-registration test compares with
  libopencv-contrib-dev
  clang-14 libclang-rt-14-dev llvm-14
  # report rendering test (headless browser)
  chromium
  # cropsight studio: its HTTP server (cpp-httplib), and its browser test (WebDriver from Python,
  # PIL to read the written label images)
  libcpp-httplib-dev chromium-driver python3-selenium python3-pil
  # ROS 1 nodes, bag files and their tests against a real roscore (ros/CMakeLists.txt)
  libroscpp-dev librosbag-storage-dev libmessage-filters-dev libstd-msgs-dev libgeometry-msgs-dev
  libsensor-msgs-dev libvisualization-msgs-dev libdiagnostic-msgs-dev libtf2-msgs-dev
  python3-roslaunch python3-gencpp python3-genmsg python3-rosbag
  # the Python package (python/) and its tests, notebooks and Dask example (docs/python.md)
  pybind11-dev python3-dev python3-numpy python3-pytest python3-nbconvert python3-nbformat python3-ipykernel
  python3-matplotlib python3-distributed python3-dask
  # pip install . offline (tests/install/test_pip_install.sh): a venv, Debian's pip and setuptools
  python3-venv python3-pip python3-setuptools
  # field batches: the Slurm engine's tests against a real one-node cluster (scripts/slurm-local.sh),
  # PROJ for geo-referenced maps, GDAL's ogrinfo to read the GeoJSON back as QGIS would
  slurm-wlm munge libproj-dev proj-data gdal-bin
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi
if [[ "${1:-}" == "--check" ]]; then
  echo "missing packages: ${missing[*]}"
  exit 1
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
echo "install-deps: installing ${missing[*]}"
# Update the package lists only when apt does not know one of the missing packages.
need_update=0
for p in "${missing[@]}"; do
  if ! apt-cache show "$p" >/dev/null 2>&1; then need_update=1; break; fi
done
if [[ $need_update -eq 1 || ! -d /var/lib/apt/lists || -z "$(ls -A /var/lib/apt/lists 2>/dev/null | grep -v lock)" ]]; then
  $SUDO apt-get update -qq
fi
if ! $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"; then
  # stale lists: refresh once and retry
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
