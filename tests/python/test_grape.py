"""cropsight.grape against `segment grape` on a real cloud of the grape dataset (../shared/data,
unpacked by scripts/unpack-grape.sh): the same label for every point."""
import json
import os
import subprocess

import numpy as np
import pytest

import cropsight as cs
from conftest import run_cli, run_cli_json, shared_data

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


def test_process_with_boxes_equals_detect_grape(broccoli_pass, tmp_path):
    # Any registered colour + depth frame serves: a simulated broccoli frame, boxes given by hand.
    boxes = [(1, 300, 100, 120, 140), (2, 340, 60, 40, 50), (1, 80, 200, 100, 120)]
    coco = tmp_path / "boxes.json"
    coco.write_text(json.dumps([{"bbox": list(b[1:]), "category_id": b[0]} for b in boxes]))
    want = run_cli_json("detect", "grape", "--color", os.path.join(broccoli_pass, "color", "000000.png"),
                        "--depth", os.path.join(broccoli_pass, "depth", "000000.png"),
                        "--camera", os.path.join(broccoli_pass, "camera.yaml"), "--detections", coco,
                        "--model", MODEL, "--threads", 1, "--out", tmp_path / "out")
    got = cs.grape.Pipeline(model=MODEL, threads=1).process(cs.read_sequence(broccoli_pass)[0], boxes)
    assert got["detections"] == want["detections"] == 3 and got["outside_image"] == want["outside_image"]
    assert len(got["bunches"]) == len(want["bunches"]) > 0
    for bunch, line in zip(got["bunches"], want["bunches"]):
        assert list(bunch["roi"]) == line["roi"]
        assert len(bunch["points"]) == len(bunch["labels"]) == line["points"]
        assert bunch["label_counts"] == line["label_counts"]
        assert bunch["cut_point"] == line["cut_point"]  # None on broccoli: no peduncle points
    with pytest.raises(ValueError) as e:
        cs.grape.Pipeline(model=MODEL, threads=1).process(cs.read_sequence(broccoli_pass)[0], [(1, 2, 3)])
    assert str(e.value) == "boxes[0]: expected (category, x, y, width, height[, score]), got (1, 2, 3)"


def test_evaluate_equals_eval_grape(real_cloud):
    folder = os.path.dirname(real_cloud)
    want = run_cli_json("eval", "grape", "--clouds", folder, "--model", MODEL, "--limit", 3, "--threads", 1)
    got = cs.grape.Pipeline(model=MODEL, threads=1).evaluate(folder, limit=3)
    for key, value in got.items():
        if key != "ms_per_cloud":  # wall-clock
            assert value == want[key], key
    assert got["clouds"] == 3 and 0.5 < got["oacc"] <= 1.0
