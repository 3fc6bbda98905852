"""cropsight.read_bag: a sequence exported to a ROS bag by the CLI reads back with the same frames
(pixels, camera), and a bad bag raises cropsight.Error with one line naming it."""
import gc
import os

import numpy as np
import pytest

import cropsight as cs
from conftest import run_cli


def test_bag_round_trip(broccoli_pass, tmp_path):
    bag = tmp_path / "pass.bag"
    run_cli("export", "--data", broccoli_pass, "--out", bag)
    original = cs.read_sequence(broccoli_pass)
    try:
        seq = cs.read_bag(str(bag))
    except cs.Error as e:
        if "without ROS" in str(e):
            pytest.skip(str(e))
        raise
    assert len(seq) == len(original)
    folder = str(seq.path)
    for a, b in zip(seq, original):
        assert np.array_equal(a.depth, b.depth) and np.array_equal(a.color, b.color)
        assert (a.camera.fx, a.camera.width, a.camera.depth_scale) == (b.camera.fx, b.camera.width, b.camera.depth_scale)
    del seq, a
    gc.collect()
    assert not os.path.exists(folder)  # the temporary sequence goes with the Sequence


def test_bad_bag(tmp_path):
    bad = tmp_path / "broken.bag"
    bad.write_bytes(b"#ROSBAG V2.0\nnot a bag")
    with pytest.raises(cs.Error) as e:
        cs.read_bag(str(bad))
    assert "broken.bag" in str(e.value) and "\n" not in str(e.value)
