#!/usr/bin/env bash
# `make package`: CPack builds the .deb; dpkg-deb lists the CLI, the presets, the shipped models, the
# plugin and the package config, and its Depends names the Debian packages install-deps.sh installs.
# Usage: test_package.sh BUILD_DIR
set -euo pipefail
build=$(realpath "$1")
cd "$build"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
cpack -G DEB >"$log" 2>&1 || { cat "$log"; echo "FAIL: cpack"; exit 1; }
deb=$(ls -t "$build"/cropsight_*.deb | head -1)
contents=$(dpkg-deb --contents "$deb")
for f in bin/cropsight share/cropsight/configs/broccoli-oes-uk.yaml share/cropsight/models/broccoli-oes-general.json \
  lib/libcropsight_nn_torch.so lib/cmake/cropsight/cropsightConfig.cmake; do
  grep -q "/usr/local/$f\$" <<<"$contents" || { echo "FAIL: $f not in $deb"; exit 1; }
done
# The Python package, where the build made one (pybind11-dev), in /usr/local's Python path.
if ls "$build"/python/cropsight/_cropsight*.so >/dev/null 2>&1; then
  grep -q "/usr/local/lib/python3\.[0-9]*/dist-packages/cropsight/__init__.py\$" <<<"$contents" ||
    { echo "FAIL: the Python package is not in $deb"; exit 1; }
  grep -q "python3-numpy" <<<"$(dpkg-deb --field "$deb" Depends)" || { echo "FAIL: Depends lacks python3-numpy"; exit 1; }
fi
depends=$(dpkg-deb --field "$deb" Depends)
for p in libpcl-dev libopencv-dev libxgboost-dev libtorch-dev; do
  grep -q "$p" <<<"$depends" || { echo "FAIL: Depends lacks $p: $depends"; exit 1; }
done
rm -rf "$build/_CPack_Packages"  # CPack's staging copy of the install (150 MB), not needed after
echo "package: $(basename "$deb") lists the CLI, presets, models, plugin and package config"
