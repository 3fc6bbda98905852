"""Per-frame overhead of the Python call over the C++ pipeline (docs/python.md, "Speed").

The same broccoli OES pipeline (made by cropsight.broccoli.Pipeline) runs over the same simulated
frames, in this one process, three ways, interleaved ROUNDS times:
  cpp     one C++ loop over the frames (_cropsight_bench.BroccoliLoop, built from the same spec and
          reading the same folder: no Python per frame)
  frame   for f in frames: pipe.process(f)                 (frames read by read_sequence: no copy)
  arrays  pipe.process(depth=, color=, camera=) on numpy arrays (one copy into the library's images)
and prints per frame the fastest round of each (the least disturbed by other processes on a shared
machine) and the median, with the overheads over cpp.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_python_overhead.py [FRAMES] [ROUNDS]
"""
import statistics
import sys
import tempfile
import time

import numpy as np

import cropsight as cs
import _cropsight_bench


def python_loop(pipe, frames, arrays):
    start = time.perf_counter()
    found = 0
    if arrays:
        for depth, color, camera in frames:
            found += len(pipe.process(depth=depth, color=color, camera=camera).detections)
    else:
        for f in frames:
            found += len(pipe.process(f).detections)
    return time.perf_counter() - start, found


def main():
    n_frames = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 7
    model, sets = "broccoli-oes-uk", ["track=false"]
    with tempfile.TemporaryDirectory() as tmp:
        cs.simulate.broccoli(tmp + "/seq", variety="uk", frames=n_frames, seed=11)
        seq = cs.read_sequence(tmp + "/seq")
        frames = [seq[i] for i in range(len(seq))]
        cpp = _cropsight_bench.BroccoliLoop(tmp + "/seq", model, sets)
    arrays = [(f.depth.copy(), f.color.copy(), f.camera) for f in frames]
    # Without tracking: every frame is judged alone, so each round repeats the same work.
    pipe = cs.broccoli.Pipeline(model=model, sets=sets)
    assert pipe.config["pipeline"] == "oes"
    times = {"cpp": [], "frame": [], "arrays": []}
    found = {}
    cpp.run()  # warm-up: buffers, caches
    python_loop(pipe, frames, False)
    for _ in range(rounds):
        s, found["cpp"] = cpp.run()
        times["cpp"].append(s)
        s, found["frame"] = python_loop(pipe, frames, False)
        times["frame"].append(s)
        s, found["arrays"] = python_loop(pipe, arrays, True)
        times["arrays"].append(s)
    assert len(set(found.values())) == 1, found  # the same work each way
    print(f"broccoli OES, {n_frames} frames 512x424, {rounds} rounds, per frame:")
    for label, pick in (("fastest", min), ("median", statistics.median)):
        per = {k: pick(v) / n_frames for k, v in times.items()}
        for k in ("cpp", "frame", "arrays"):
            extra = "" if k == "cpp" else f"  overhead {100.0 * (per[k] / per['cpp'] - 1.0):+.2f} %"
            print(f"  {label:7s} {k:7s} {1000.0 * per[k]:8.3f} ms{extra}")
    # The call's own cost, apart from the pipeline's: n calls on a 4×4 frame without depth (the
    # pipeline has almost nothing to do), C++ loop against Python loop, fastest of the rounds.
    calls = 2000
    c = frames[0].camera
    tiny = cs.Camera(width=4, height=4, fx=c.fx, fy=c.fy, cx=1.5, cy=1.5, depth_scale=c.depth_scale)
    empty = cs.Frame(depth=np.zeros((4, 4), np.uint16), camera=tiny)
    cpp_empty, py_empty = [], []
    for _ in range(rounds):
        cpp_empty.append(cpp.run_empty(calls))
        start = time.perf_counter()
        for _ in range(calls):
            pipe.process(empty)
        py_empty.append(time.perf_counter() - start)
    per_call_us = 1e6 * (min(py_empty) - min(cpp_empty)) / calls
    print(f"  the Python call itself: {per_call_us:.1f} us per call ({1e6 * min(cpp_empty) / calls:.1f} us in C++ "
          f"on an empty 4x4 frame), {100.0 * per_call_us / (1e6 * min(times['cpp']) / n_frames):.2f} % of a frame")


if __name__ == "__main__":
    main()
