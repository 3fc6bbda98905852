"""cropsight.potato and cropsight.seedling against the CLI on the same simulated data: the same
harvest messages (harvest potato) and seedling figures (detect seedling --json)."""
import json
import os

import numpy as np
import pytest

import cropsight as cs
from conftest import run_cli, run_cli_json

HARVEST_FIELDS = ["frame", "timestamp", "detection", "depth_ok", "x", "y", "z", "height", "width", "angle",
                  "angle_ok", "cut", "target_id", "state", "score"]


@pytest.fixture(scope="module")
def potato_seq(tmp_path_factory):
    out = tmp_path_factory.mktemp("potato") / "seq"
    run_cli("simulate", "potato", "--frames", 4, "--seed", 3, "--out", out, "--quiet")
    return str(out)


@pytest.fixture(scope="module")
def seedling_data(tmp_path_factory):
    out = tmp_path_factory.mktemp("seedling") / "pairs"
    run_cli("simulate", "seedling", "--pairs", 2, "--calib-pairs", 0, "--seed", 5, "--out", out, "--quiet")
    return str(out)


def test_harvest_messages_equal_the_cli(potato_seq, tmp_path):
    out = tmp_path / "harvest.jsonl"
    run_cli("harvest", "potato", "--data", potato_seq, "--out", out, "--quiet")
    want = [json.loads(line) for line in out.read_text().splitlines()]
    pipe = cs.potato.Pipeline()
    got = [pipe.process(frame).target for frame in cs.read_sequence(potato_seq)]
    assert len(got) == len(want) == 4
    assert any(t.detection for t in got)
    for target, line in zip(got, want):
        for field in HARVEST_FIELDS:
            value = getattr(target, field)
            assert value == line[field], field  # floats: the CLI prints each one exactly
        assert (list(target.box) if target.box else None) == line.get("box")


def test_seedling_equals_detect_seedling(seedling_data, tmp_path):
    rig = os.path.join(seedling_data, "rig.yaml")
    pipe = cs.seedling.Pipeline()
    for pair in ["pair_000", "pair_001"]:
        left, right = (os.path.join(seedling_data, pair, f"{side}.png") for side in ("left", "right"))
        want = run_cli_json("detect", "seedling", "--left", left, "--right", right, "--calib", rig)
        l_img, r_img = cs.seedling.read_pair(left, right)
        got = pipe.process(l_img, r_img, rig)
        assert got.found == want["found"]
        assert got.envelope == {k: want["envelope"][k] for k in ("length_m", "width_m", "height_m", "volume_m3")}
        assert got.top_view_area_m2 == want["top_view_area_m2"]
        assert got.plane_normal.tolist() == want["plane"]["normal"] and got.plane_d == want["plane"]["d"]
        points = want["points"]
        assert (got.points_total, got.points_candidates, got.points_sampled, got.points_seedling_sampled,
                len(got.points)) == (points["reconstructed"], points["above_soil"], points["sampled"],
                                     points["seedling_sampled"], points["seedling_dense"])
        assert got.points.shape == (len(got.pixels), 3) and got.points.dtype == np.float32
        assert got.image_mask.shape == l_img.shape[:2]


def test_seedling_bad_input(seedling_data):
    rig = os.path.join(seedling_data, "rig.yaml")
    pipe = cs.seedling.Pipeline()
    left = np.zeros((10, 12, 3), np.uint8)
    with pytest.raises(cs.Error) as e:  # a pair of another size than the calibration's
        pipe.process(left, left, rig)
    assert str(e.value).startswith("left: ") and "\n" not in str(e.value)
    with pytest.raises(TypeError) as e:
        pipe.process(left.astype(np.float64), left, rig)
    assert str(e.value).startswith("left: expected a uint8 array of shape (H, W, 3)")
    with pytest.raises(cs.Error) as e:
        pipe.process(left, left, os.path.join(seedling_data, "missing.yaml"))
    assert "missing.yaml" in str(e.value)


def test_seedling_evaluate_equals_eval_seedling(seedling_data):
    want = run_cli_json("eval", "seedling", "--data", seedling_data, "--no-opencv", "--quiet")
    got = cs.seedling.Pipeline().evaluate(seedling_data)
    timing = {"ms_total", "ms_sgm", "ms_gmm", "ms"}  # wall-clock
    for key, value in got.items():
        if key == "per_pair":
            assert [{k: v for k, v in r.items() if k not in timing} for r in value] == \
                   [{k: v for k, v in r.items() if k not in timing} for r in want[key]]
        elif key not in timing:
            assert value == want[key], key
    assert got["pairs"] == 2


def test_potato_evaluate_equals_eval_potato(potato_seq):
    want = run_cli_json("eval", "potato", "--data", potato_seq)
    got = cs.potato.Pipeline().evaluate(potato_seq)
    for key, value in got.items():
        if key != "ms_per_frame":  # wall-clock
            assert value == want[key], key
    assert got["frames"] == 4
