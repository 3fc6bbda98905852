"""cropsight.broccoli against the CLI on the same pass: the same detections, scores, centroids,
boxes, sizes, track ids, field map and evaluator figures, to the last digit the CLI prints."""
import json

import numpy as np

import cropsight as cs
from conftest import run_cli, run_cli_json

MODEL = "broccoli-oes-uk"


def cli_detections(seq, tmp_path, *extra):
    out = tmp_path / "detections.jsonl"
    summary = run_cli_json("detect", "broccoli", "--data", seq, "--model", MODEL, "--out", out, "--quiet", *extra)
    return summary, [json.loads(line) for line in out.read_text().splitlines()]


def test_detections_equal_the_cli_with_tracking(broccoli_pass, tmp_path):
    summary, lines = cli_detections(broccoli_pass, tmp_path, "--track")
    pipe = cs.broccoli.Pipeline(model=MODEL, sets={"track": True})
    seq = cs.read_sequence(broccoli_pass)
    assert len(seq) == len(lines) == 6
    total = 0
    for frame, line in zip(seq, lines):
        result = pipe.process(frame)
        assert result.frame == line["frame"]
        assert len(result.detections) == len(line["detections"])
        for det, want, head in zip(result.detections, line["detections"], line["heads"]):
            # The CLI prints each float as the shortest text that reads back as the same double.
            assert det.score == want["score"]
            assert det.centroid.tolist() == want["centroid"]
            assert list(det.box) == want["box"]
            assert len(det.pixels) == want["points"]
            assert det.track_id == head["track_id"]
            if head["diameter_mm"] is None:
                assert det.diameter_m is None
            else:  # the detection holds the diameter as float32 metres
                assert det.diameter_m == np.float32(head["diameter_mm"] / 1000.0)
        assert result.camera_estimate.tolist() == line["camera_estimate"]
        assert [p.track_id for p in result.predicted] == [p["track_id"] for p in line["predicted"]]
        total += len(result.detections)
    assert total == summary["detections"] > 0
    field_map = pipe.field_map()
    assert len(field_map) == summary["map_heads"] > 0
    assert sum(h.harvestable for h in field_map) == summary["harvestable"]


def test_arrays_give_the_same_result_as_frames(broccoli_pass):
    seq = cs.read_sequence(broccoli_pass)
    by_frame = cs.broccoli.Pipeline(model=MODEL, sets={"track": False})
    by_arrays = cs.broccoli.Pipeline(model=MODEL, sets=["track=false"])
    for frame in seq:
        a = by_frame.process(frame)
        # Non-contiguous input (a transposed copy transposed back) is accepted with a copy.
        depth = np.ascontiguousarray(frame.depth.T).T
        assert not depth.flags.c_contiguous
        b = by_arrays.process(depth=depth, color=frame.color, camera=frame.camera)
        assert [d.score for d in a.detections] == [d.score for d in b.detections]
        assert [d.pixels.tolist() for d in a.detections] == [d.pixels.tolist() for d in b.detections]
        labels = a.label_image()
        assert labels.shape == frame.depth.shape and labels.max() == len(a.detections)
        if a.detections:
            assert a.detections[0].mask(frame.camera.width, frame.camera.height).sum() == len(a.detections[0].pixels)


def test_evaluate_equals_eval_broccoli_json(broccoli_pass):
    want = run_cli_json("eval", "broccoli", "--data", broccoli_pass, "--model", MODEL, "--quiet")
    got = cs.broccoli.evaluate(broccoli_pass, model=MODEL)
    timing = {"fps", "ms_per_frame"}  # wall-clock: differs between any two runs
    for key, value in got.items():
        if key not in timing:
            assert value == want[key], key
    assert got["frames"] == 6 and got["tp"] > 0


def test_config_documents_every_key():
    doc = cs.broccoli.Config.__doc__
    cfg = cs.broccoli.Config()
    assert len(cfg) > 50
    for key in cfg.keys():
        assert f"\n{key} = " in doc, key
    assert "tracking.use_poses" in cfg and "kusumam" in doc.lower()
    pipe = cs.broccoli.Pipeline(model=MODEL, sets={"tracking.use_poses": True, "track": False})
    assert pipe.config["tracking.use_poses"] == "true" and pipe.config["track"] == "false"


def test_simulator_matches_the_cli_byte_for_byte(broccoli_pass, tmp_path):
    run_cli("simulate", "broccoli", "--variety", "uk", "--frames", 6, "--seed", 7, "--out", tmp_path / "cli", "--quiet")
    import filecmp
    import os
    for sub in ["depth", "labels"]:
        names = sorted(os.listdir(tmp_path / "cli" / sub))
        match, mismatch, errors = filecmp.cmpfiles(tmp_path / "cli" / sub, os.path.join(broccoli_pass, sub), names, shallow=False)
        assert not mismatch and not errors
    for name in ["groundtruth.json", "camera.yaml", "poses.csv"]:
        assert filecmp.cmp(tmp_path / "cli" / name, os.path.join(broccoli_pass, name), shallow=False), name
