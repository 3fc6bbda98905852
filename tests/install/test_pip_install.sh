#!/usr/bin/env bash
# `pip install .` offline with Debian's packages: a virtual environment that sees Debian's numpy and
# setuptools, pip without build isolation or an index (nothing downloaded), setup.py building the
# extension and the libtorch plugin with the project's CMake in BUILD_DIR/pip-build. The installed
# package, imported from an unrelated folder with no cropsight variable set, finds its models by
# name and the plugin inside the wheel (a grape network runs), and detects broccoli heads.
# Usage: test_pip_install.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$(realpath "$1")
build=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$work/env"
CROPSIGHT_PIP_BUILD_DIR="$build/pip-build" "$work/env/bin/pip" install --no-build-isolation --no-index --quiet "$src" \
  >"$work/pip.log" 2>&1 || { tail -30 "$work/pip.log"; echo "FAIL: pip install"; exit 1; }
cd "$work"
env -u PYTHONPATH -u CROPSIGHT_DATA_DIR -u CROPSIGHT_NN_BACKEND "$work/env/bin/python" - "$work" <<'PY' ||
import os, sys
import numpy as np
import cropsight as cs
work = sys.argv[1]
package = os.path.dirname(cs.__file__)
assert package.startswith(os.path.join(work, "env")), package
assert os.environ["CROPSIGHT_NN_BACKEND"] == os.path.join(package, "lib", "libcropsight_nn_torch.so")
cs.simulate.broccoli(os.path.join(work, "pass"), frames=3, seed=4)
pipe = cs.broccoli.Pipeline(model="broccoli-oes-general")
assert sum(len(pipe.process(f).detections) for f in cs.read_sequence(os.path.join(work, "pass"))) > 0
points = np.random.default_rng(1).normal(size=(2048, 9)).astype(np.float32)
points[:, 3:6] /= np.linalg.norm(points[:, 3:6], axis=1, keepdims=True)
points[:, 6:9] = np.abs(points[:, 6:9]) % 1.0
labels = cs.grape.Pipeline(model="grape-pointresnet", threads=1).segment(points)  # the libtorch plugin
assert labels.shape == (2048,)
PY
  { echo "FAIL: the pip-installed package"; exit 1; }
echo "pip install: offline wheel built with CMake; models by name and the plugin found inside the package"
