"""The GIL is released while a pipeline runs: pipelines in several Python threads (one each, as
the docstrings say) give the same results as one after the other."""
from concurrent.futures import ThreadPoolExecutor

import cropsight as cs


def detections_of(sequence):
    pipe = cs.broccoli.Pipeline(model="broccoli-oes-uk", sets={"track": True})
    out = [[(d.score, d.track_id, d.pixels.tolist()) for d in pipe.process(f).detections] for f in cs.read_sequence(sequence)]
    return out, [(h.id, h.diameter_mm) for h in pipe.field_map()]


def test_threads_equal_sequential(broccoli_pass):
    sequential = [detections_of(broccoli_pass) for _ in range(3)]
    with ThreadPoolExecutor(max_workers=3) as pool:
        threaded = list(pool.map(detections_of, [broccoli_pass] * 3))
    assert threaded == sequential and sequential[0][0]


def test_one_seedling_pipeline_shared_by_threads(tmp_path):
    # A seedling pipeline keeps no state between pairs: one object may serve several threads.
    from conftest import run_cli
    run_cli("simulate", "seedling", "--pairs", 2, "--calib-pairs", 0, "--seed", 9, "--out", tmp_path / "p", "--quiet")
    rig = str(tmp_path / "p" / "rig.yaml")
    pairs = [cs.seedling.read_pair(str(tmp_path / "p" / f"pair_00{i}" / "left.png"),
                                   str(tmp_path / "p" / f"pair_00{i}" / "right.png")) for i in (0, 1)]
    pipe = cs.seedling.Pipeline()
    one_by_one = [pipe.process(l, r, rig).envelope for l, r in pairs] * 2
    with ThreadPoolExecutor(max_workers=4) as pool:
        together = list(pool.map(lambda lr: pipe.process(lr[0], lr[1], rig).envelope, pairs * 2))
    assert together == one_by_one
