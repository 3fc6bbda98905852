"""cropsight.Detector against `detect objects` on real images of the grape dataset (../shared/data):
the same boxes, classes and scores."""
import json
import os
import shutil

import numpy as np
import pytest

import cropsight as cs
from conftest import run_cli, shared_data

MODEL = "detector-grape.onnx"


def test_detect_equals_detect_objects(tmp_path):
    folder = shared_data("grape", "coco_train", "JPEGImages")
    names = sorted(os.listdir(folder))[:2]
    os.makedirs(tmp_path / "images")
    for name in names:
        shutil.copy(os.path.join(folder, name), tmp_path / "images")
    run_cli("detect", "objects", "--images", tmp_path / "images", "--model", MODEL, "--out", tmp_path / "out")
    want = json.loads((tmp_path / "out" / "detections.json").read_text())
    detector = cs.Detector(model=MODEL)
    assert detector.class_names and len(want) > 0
    got = []
    for name in sorted(names):
        for box in detector.detect(cs.read_image(str(tmp_path / "images" / name))):
            x1, y1, x2, y2 = (np.float32(v) for v in box.corners)
            got.append({"file_name": name, "category_id": box.class_id + 1, "score": box.score,
                        "bbox": [float(x1), float(y1), float(x2 - x1), float(y2 - y1)]})
    assert got == [{k: w[k] for k in ("file_name", "category_id", "score", "bbox")} for w in want]


def test_detect_bad_image():
    detector = cs.Detector(model=MODEL)
    with pytest.raises(ValueError) as e:
        detector.detect(np.zeros((32, 32), np.uint8))
    assert str(e.value) == "image: expected a uint8 array of shape (H, W, 3) (RGB), got uint8 array of shape (32, 32)"
    with pytest.raises(cs.Error) as e:
        cs.Detector(model="no-such-detector")
    assert "no-such-detector" in str(e.value) and "\n" not in str(e.value)


def test_detector_by_name_runs_the_same_weights():
    """A model named without extension runs on libtorch where the plugin is installed (else OpenCV
    DNN): the same boxes as the .onnx within float rounding."""
    image = cs.read_image(os.path.join(shared_data("grape", "coco_train", "JPEGImages"), "grape_image_1.jpg"))
    want = cs.Detector(model=MODEL).detect(image)
    got = cs.Detector(model="detector-grape", threads=2).detect(image)
    assert len(want) > 0 and len(got) == len(want)
    for g, w in zip(got, want):
        assert g.class_id == w.class_id and abs(g.score - w.score) < 1e-4
        assert np.allclose(g.corners, w.corners, atol=0.05)
