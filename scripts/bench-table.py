#!/usr/bin/env python3
"""`make bench`: the headline workloads in one table, each beside a baseline timed in the same
process, and the callgrind instruction counts of the broccoli detector's stages.

    scripts/bench-table.py BUILD [--out FILE] [--no-callgrind] [--frames N] [--label TEXT]

Prints the table and writes it as JSON (default BUILD/bench/summary.json; compare two with
tools/bench-compare A.json B.json). Rows whose binary is missing are listed as skipped. Times on a
shared VM move with the machine: the stable figures are the ratio to the same-run baseline and
the instruction counts (callgrind runs the AVX2 clones: valgrind has no AVX-512). --label names
the binaries in the JSON (default: the checkout's commit, which need not be what BUILD holds).

Rows (single thread unless the workload says otherwise):
  broccoli-oes       cropsight bench broccoli, general model, 512x424, vs the PCL reference
  broccoli-oes-cnn   the same with the head CNN (cnn.model), vs the PCL reference
  potato-loop        cropsight bench potato, `potato` preset, vs one cv::cvtColor to Lab
  census-sgm         bench_stereo census SGM 640x480x128 vs OpenCV SGBM_3WAY (wall clock)
  seedling-pair      bench_stereo seedling pipeline, default preset, vs SGBM_3WAY (wall clock)
  grape-detector     bench_detector, boxes + masks of a 1280x720 image by the default runtime (libtorch
                     where the plugin is built, else OpenCV DNN) with the masks inside the boxes, vs
                     OpenCV DNN with whole-image masks (the path before both) on the same weights (wall clock)
  grape-best         bench_grape, the shipped grape segmenter (PointResNet 6 votes + fast GBDT, 2
                     threads) on one shared cloud vs PCL's k = 30 normals of the same cloud (one
                     thread; wall clock); needs ../shared/data/grape (unpacked under BUILD/bench/grape)
"""
import datetime
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODEL = "broccoli-oes-general"
CNN = "models/broccoli-head-cnn.onnx"


def run(cmd, env=None):
    e = dict(os.environ, TBB_NUM_THREADS="1", **(env or {}))
    out = subprocess.run(cmd, cwd=HERE, env=e, capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {out.returncode}: {out.stderr.strip()[-300:]}")
    return out.stdout


def cpu_model():
    try:
        for line in run(["lscpu"]).splitlines():
            if line.startswith("Model name:"):
                return line.split(":", 1)[1].strip()
    except (RuntimeError, FileNotFoundError):
        pass
    return platform.processor() or "unknown"


def broccoli_data(build, frames):
    """The uk test pass (seed 2001, never used for training), simulated once under BUILD/bench."""
    data = os.path.join(build, "bench", "data", f"broccoli-uk-2001-{frames}")
    if not os.path.isdir(data):
        run([os.path.join(build, "bin", "cropsight"), "simulate", "broccoli", "--variety", "uk", "--seed", "2001",
             "--frames", str(frames), "--out", data, "--quiet"])
    return data


def broccoli_row(build, data, frames, name, sets):
    cmd = [os.path.join(build, "bin", "cropsight"), "bench", "broccoli", "--data", data, "--model", MODEL,
           "--pipelines", "oes,pcl", "--frames", str(frames), "--json"]
    for s in sets:
        cmd += ["--set", s]
    p = json.loads(run(cmd))["pipelines"]
    oes, pcl = p["oes"], p["pcl_reference"]
    return {"workload": name, "ms": oes["cpu_ms_per_frame"], "baseline": "PCL reference",
            "baseline_ms": pcl["cpu_ms_per_frame"], "ratio": pcl["cpu_ms_per_frame"] / oes["cpu_ms_per_frame"],
            "clock": "CPU, 1 thread", "stages_ms": oes["stages_ms"]}


def callgrind_broccoli(build, data):
    """Instructions a frame per stage of the OES detector (2 frames + the warm-up one)."""
    out = os.path.join(tempfile.mkdtemp(prefix="cropsight-bench-"), "callgrind.out")
    try:
        run(["valgrind", "--tool=callgrind", "--toggle-collect=cropsight::pipeline::broccoli::Detector::process*",
             f"--callgrind-out-file={out}", os.path.join(build, "bin", "cropsight"), "bench", "broccoli", "--data",
             data, "--model", MODEL, "--pipelines", "oes", "--frames", "2"])
        return json.loads(run([sys.executable, os.path.join(HERE, "tools", "callgrind-stages.py"), out, "2", "--json"]))
    finally:
        shutil.rmtree(os.path.dirname(out), ignore_errors=True)


def gbench(build, binary, pattern, env=None):
    """{benchmark name: wall ms} of a Google Benchmark binary's matching benchmarks."""
    path = os.path.join(build, "bin", binary)
    if not os.path.exists(path):
        raise RuntimeError(f"{binary} not built")
    doc = json.loads(run([path, f"--benchmark_filter={pattern}", "--benchmark_format=json",
                          "--benchmark_min_time=0.3"], env))
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
    times = {}
    for b in doc["benchmarks"]:
        if b.get("error_occurred"):
            raise RuntimeError(f"{b['name']}: {b.get('error_message', 'failed')}")
        parts = b["name"].split("/")  # "BM_X/0/process_time/real_time" -> "BM_X/0"
        times["/".join([parts[0]] + [p for p in parts[1:] if p.isdigit()])] = b["real_time"] * scale[b["time_unit"]]
    return times


def potato_row(build):
    doc = json.loads(run([os.path.join(build, "bin", "cropsight"), "bench", "potato", "--frames", "10", "--repeat",
                          "1", "--quiet", "--json"]))
    p = doc["presets"]["potato"]
    return {"workload": "potato-loop", "ms": p["cpu_ms_per_frame"], "baseline": "cvtColor to Lab",
            "baseline_ms": doc["baseline_lab_conversion_ms"], "ratio": doc["baseline_lab_conversion_ms"] /
            p["cpu_ms_per_frame"], "clock": "CPU, 1 thread"}


def stereo_rows(build):
    t = gbench(build, "bench_stereo", "BM_DisparityCensus128|BM_DisparityOpenCvSgbm3Way128|BM_SeedlingPipeline/0")
    sgbm = t["BM_DisparityOpenCvSgbm3Way128"]
    return [{"workload": "census-sgm", "ms": t["BM_DisparityCensus128"], "baseline": "OpenCV SGBM_3WAY",
             "baseline_ms": sgbm, "ratio": sgbm / t["BM_DisparityCensus128"], "clock": "wall"},
            {"workload": "seedling-pair", "ms": t["BM_SeedlingPipeline/0"], "baseline": "OpenCV SGBM_3WAY",
             "baseline_ms": sgbm, "ratio": sgbm / t["BM_SeedlingPipeline/0"], "clock": "wall"}]


def detector_row(build):
    t = gbench(build, "bench_detector", "BM_GrapeDetector(OnnxMasks|OnnxMasksInBoxes|TorchMasksInBoxes)/")
    ours = t.get("BM_GrapeDetectorTorchMasksInBoxes") or t["BM_GrapeDetectorOnnxMasksInBoxes"]  # no plugin: 0
    old = t["BM_GrapeDetectorOnnxMasks"]
    return {"workload": "grape-detector", "ms": ours, "baseline": "DNN, whole masks", "baseline_ms": old,
            "ratio": old / ours, "clock": "wall"}


def grape_row(build):
    archive = os.path.join(HERE, "..", "shared", "data", "grape", "grape_points_train.tar.gz")
    if not os.path.exists(archive):
        raise RuntimeError(f"{archive}: no grape data")
    data = run([os.path.join(HERE, "scripts", "unpack-grape.sh"), archive,
                os.path.join(build, "bench", "grape")]).strip()
    t = gbench(build, "bench_grape", "BM_GrapeNetworkVotes/6/1|BM_KnnNormalsPcl", {"CROPSIGHT_GRAPE_DIR": data})
    best, pcl = t["BM_GrapeNetworkVotes/6/1"], t["BM_KnnNormalsPcl"]
    return {"workload": "grape-best", "ms": best, "baseline": "PCL normals k=30", "baseline_ms": pcl,
            "ratio": pcl / best, "clock": "wall, 2 threads"}


def print_table(doc):
    print(f"cropsight bench, {doc['cpu']}, commit {doc['commit']}, {doc['date']}")
    print(f"{'workload':18s} {'ms':>9s}  {'baseline':18s} {'base ms':>9s} {'ratio':>8s}  clock")
    for r in doc["rows"]:
        if "skipped" in r:
            print(f"{r['workload']:18s} skipped: {r['skipped']}")
            continue
        print(f"{r['workload']:18s} {r['ms']:9.2f}  {r['baseline']:18s} {r['baseline_ms']:9.2f} {r['ratio']:7.2f}x  "
              f"{r['clock']}")
    ins = doc.get("instructions")
    if ins:
        print("callgrind, broccoli-oes, M instructions a frame: " +
              " ".join(f"{k} {v / 1e6:.2f}" for k, v in ins.items()))
    print("ratio: the baseline's time over the workload's (above 1: faster than the baseline)")


def main():
    args = sys.argv[1:]
    if not args or args[0].startswith("-"):
        sys.exit(__doc__)
    build = os.path.abspath(args[0])
    out = args[args.index("--out") + 1] if "--out" in args else os.path.join(build, "bench", "summary.json")
    frames = int(args[args.index("--frames") + 1]) if "--frames" in args else 10
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=HERE, capture_output=True,
                            text=True).stdout.strip()
    if "--label" in args:
        commit = args[args.index("--label") + 1]
    doc = {"cpu": cpu_model(), "commit": commit, "date": datetime.datetime.now(datetime.timezone.utc).isoformat(
        timespec="seconds"), "rows": []}
    data = broccoli_data(build, frames)
    jobs = [("broccoli-oes", lambda: [broccoli_row(build, data, frames, "broccoli-oes", [])]),
            ("broccoli-oes-cnn", lambda: [broccoli_row(build, data, min(frames, 3), "broccoli-oes-cnn",
                                                       [f"cnn.model={CNN}"])]),
            ("potato-loop", lambda: [potato_row(build)]),
            ("census-sgm, seedling-pair", lambda: stereo_rows(build)),
            ("grape-detector", lambda: [detector_row(build)]),
            ("grape-best", lambda: [grape_row(build)])]
    for name, job in jobs:
        try:
            doc["rows"] += job()
        except (RuntimeError, KeyError, ValueError) as e:
            doc["rows"].append({"workload": name, "skipped": str(e)})
    if "--no-callgrind" not in args and shutil.which("valgrind"):
        doc["instructions"] = callgrind_broccoli(build, data)
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    tmp = out + ".partial"
    with open(tmp, "w") as f:
        json.dump(doc, f, indent=1)
    os.replace(tmp, out)
    print_table(doc)
    print(f"JSON: {out}")


if __name__ == "__main__":
    main()
