"""Per-frame overhead of the Python call over the C++ pipeline (docs/python.md, "Speed").

The same broccoli OES pipeline (made by cropsight.broccoli.Pipeline) runs over the same simulated
frames, in this one process, three ways, interleaved ROUNDS times:
  cpp     one C++ loop over the frames (_cropsight_bench.BroccoliLoop, built from the same spec and
          reading the same folder: no Python per frame)
  frame   for f in frames: pipe.process(f)                 (frames read by read_sequence: no copy)
  arrays  pipe.process(depth=, color=, camera=) on numpy arrays (one copy into the library's images)
and prints the median seconds per frame of each and the overheads over cpp.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_python_overhead.py [FRAMES] [ROUNDS]
"""
import statistics
import sys
import tempfile
import time

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
    med = {k: statistics.median(v) / n_frames for k, v in times.items()}
    print(f"broccoli OES, {n_frames} frames 512x424, {rounds} rounds, median per frame:")
    for k in ("cpp", "frame", "arrays"):
        extra = "" if k == "cpp" else f"  overhead {100.0 * (med[k] / med['cpp'] - 1.0):+.2f} %"
        print(f"  {k:7s} {1000.0 * med[k]:8.3f} ms{extra}")


if __name__ == "__main__":
    main()
