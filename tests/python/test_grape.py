"""cropsight.grape against `segment grape` on a real cloud of the grape dataset (../shared/data,
unpacked by scripts/unpack-grape.sh): the same label for every point."""
import os
import subprocess

import numpy as np
import pytest

import cropsight as cs
from conftest import run_cli, shared_data

MODEL = "grape-gbdt-fast"


@pytest.fixture(scope="module")
def real_cloud():
    archive = shared_data("grape", "grape_points_train.tar.gz")
    script = os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "unpack-grape.sh")
    folder = subprocess.run(["bash", script, archive], capture_output=True, text=True, check=True).stdout.strip()
    return os.path.join(folder, "points", "grape_1(0).txt")


def test_segment_equals_the_cli(real_cloud, tmp_path):
    out = tmp_path / "labelled.txt"
    run_cli("segment", "grape", "--clouds", real_cloud, "--model", MODEL, "--out", out, "--threads", 1)
    want = np.loadtxt(out, usecols=9).astype(np.int32)
    points, truth = cs.grape.read_cloud(real_cloud)
    assert points.shape == (len(truth), 9) and points.dtype == np.float32
    pipe = cs.grape.Pipeline(model=MODEL, threads=1)
    labels = pipe.segment(points)
    assert labels.dtype == np.int32 and labels.shape == want.shape
    assert np.array_equal(labels, want)
    # float64 and non-contiguous input give the same labels (converted with a copy).
    assert np.array_equal(pipe.segment(np.asfortranarray(points.astype(np.float64))), want)


def test_segment_bad_input():
    pipe = cs.grape.Pipeline(model=MODEL, threads=1)
    with pytest.raises(ValueError) as e:
        pipe.segment(np.zeros((5, 8), np.float32))
    assert str(e.value) == "points: expected a float32 or float64 array of shape (N, 9), got float32 array of shape (5, 8)"
    with pytest.raises(TypeError):
        pipe.segment(np.zeros((5, 9), np.int64))
    bad = np.zeros((5, 9), np.float32)
    bad[2, 0] = np.nan
    with pytest.raises(cs.Error) as e:
        pipe.segment(bad)
    assert str(e.value).startswith("points: ") and "\n" not in str(e.value)
