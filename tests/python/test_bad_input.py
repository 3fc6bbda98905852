"""Bad input from Python: the documented exception with one line naming what is wrong; no crash."""
import math

import numpy as np
import pytest

import cropsight as cs

CAMERA = dict(width=64, height=48, fx=60.0, fy=60.0, cx=31.5, cy=23.5)


@pytest.fixture(scope="module")
def pipe():
    return cs.broccoli.Pipeline(model="broccoli-oes-uk", sets={"track": False})


def one_line(exc):
    text = str(exc.value)
    assert "\n" not in text and text
    return text


def test_wrong_dtype_is_a_type_error(pipe):
    with pytest.raises(TypeError) as e:
        pipe.process(depth=np.zeros((48, 64), np.float32), camera=cs.Camera(**CAMERA))
    assert one_line(e).startswith("depth: expected a uint16 array") and "float32 array of shape (48, 64)" in str(e.value)


def test_wrong_shape_is_a_value_error(pipe):
    with pytest.raises(ValueError) as e:
        pipe.process(depth=np.zeros((48, 64, 1), np.uint16), camera=cs.Camera(**CAMERA))
    assert "depth" in one_line(e) and "(48, 64, 1)" in str(e.value)
    with pytest.raises(ValueError) as e:
        pipe.process(depth=np.zeros((40, 64), np.uint16), camera=cs.Camera(**CAMERA))
    assert "differs from the camera's image size (48, 64)" in one_line(e)
    with pytest.raises(ValueError) as e:
        cs.Frame(depth=np.zeros((48, 64), np.uint16), color=np.zeros((48, 64, 4), np.uint8), camera=cs.Camera(**CAMERA))
    assert one_line(e).startswith("color: expected a uint8 array of shape (H, W, 3)")


def test_not_an_array_is_a_type_error(pipe):
    with pytest.raises(TypeError) as e:
        pipe.process(depth=[[0, 1]], camera=cs.Camera(**CAMERA))
    assert one_line(e) == "depth: expected a numpy uint16 array of shape (H, W) (raw depth units), got list object"
    with pytest.raises(TypeError):
        pipe.process(depth=np.zeros((48, 64), np.uint16))  # no camera


def test_nan_intrinsics_are_a_cropsight_error(pipe):
    camera = cs.Camera(**{**CAMERA, "fx": math.nan})
    with pytest.raises(cs.Error) as e:
        pipe.process(depth=np.zeros((48, 64), np.uint16), camera=camera)
    assert one_line(e) == "camera: focal lengths fx, fy must be finite and positive" and e.value.where == "camera"


def test_missing_model_and_unknown_key_are_cropsight_errors(tmp_path):
    with pytest.raises(cs.Error) as e:
        cs.broccoli.Pipeline(model=str(tmp_path / "missing.json"))
    assert "missing.json" in one_line(e)
    with pytest.raises(cs.Error) as e:
        cs.broccoli.Pipeline(model="broccoli-oes-uk", sets={"detector.no_such_key": 1})
    assert one_line(e) == "--set: unknown configuration key 'detector.no_such_key'" and e.value.where == "--set"
    with pytest.raises(TypeError):
        cs.broccoli.Pipeline(sets="track=false")


def test_missing_sequence_is_a_cropsight_error(tmp_path):
    with pytest.raises(cs.Error) as e:
        cs.read_sequence(str(tmp_path / "nope"))
    assert "nope" in one_line(e)


def test_empty_depth_runs(pipe):
    result = pipe.process(depth=np.zeros((48, 64), np.uint16), camera=cs.Camera(**CAMERA))
    assert result.detections == []
