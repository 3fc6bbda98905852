#!/usr/bin/env python3
"""Instruction counts of a pipeline's stages from a callgrind profile.

    tools/callgrind-stages.py CALLGRIND_OUT FRAMES [--grape] [--json]

Broccoli (default): valgrind --tool=callgrind of `cropsight bench broccoli --pipelines oes` (one
warm-up frame + FRAMES timed ones, so counts are divided by FRAMES + 1). A stage's count is the
inclusive count of the function its StageTimer scope lives in (callgrind_annotate --inclusive);
"cloud" excludes the denoising, which has its own scope inside it. Callgrind runs the AVX2
clones (valgrind has no AVX-512), so counts are those of an AVX2 machine.

--grape: valgrind --tool=callgrind --toggle-collect='cropsight::pipeline::grape::Model::segment*'
of `cropsight segment grape --threads 1` on FRAMES clouds, counts divided by FRAMES. One thread,
because callgrind counts a function's callees only on the thread that called it: with two,
the halves that TBB's, OpenMP's or the pass workers' threads run fall outside every stage.
Stages overlap (forward holds fps, cdist, topk and linear; carry-back counts the network's votes
and the GBDT's own; gbdt holds its features, trees and carry-back). "total" is the segmenter's
work on every thread (the program less the main thread's work outside Model::segment)"""
import json
import re
import subprocess
import sys

# Stage name -> the function holding its StageTimer scope (a substring of the demangled name).
BROCCOLI = {
    "denoise": "steps::CloudStep::denoise(",
    "cloud": "steps::CloudStep::run(",
    "normals": "geometry::IntegralNormalEstimator::compute(",
    "edges": "geometry::detect_organized_edges(",
    "clustering": "steps::ClusteringStep::run(",
    "features": "steps::DescriptionStep::run(",
    "classify": "steps::ClassificationStep::run(",
    "split": "steps::CreaseSplit::refine(",
    "completion": "steps::HeadCompletion::refine(",
    "total": "broccoli::Detector::process(",
}

# Grape: the segmenter's parts, by the function that does each (inclusive counts).
GRAPE = {
    "sampling": "nn::TorchSegmenter::sample_for_pass(",
    "batch": "torch_impl::make_batch(",
    "forward": "torch_impl::SegNetImpl::forward(",
    "fps": "geometry::farthest_point_sample(",
    "cdist": "at::_ops::cdist::call(",
    "topk": "at::_ops::topk::call(",
    "linear": "torch::nn::LinearImpl::forward(",
    "carry-back": "grape::grape_carry_back(",
    "gbdt": "grape::segment_grape_gbdt(",
    "gbdt features": "grape::grape_sample_features(",
    "gbdt trees": "learning::Gbdt::predict_flat(",
    "segment": "grape::Model::segment(",
    "main thread": "(below main)",
}


def inclusive_counts(path, stages):
    out = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", path],
                         capture_output=True, text=True, check=True).stdout
    counts = {}
    for line in out.splitlines():
        if line.strip().endswith("PROGRAM TOTALS"):
            counts["program"] = int(line.split()[0].replace(",", ""))
        m = re.match(r"\s*([\d,]+)\s+\([^)]*\)\s+\S*?:(.*)", line)
        if not m:
            continue
        n = int(m.group(1).replace(",", ""))
        for stage, fn in stages.items():
            if fn in m.group(2) and stage not in counts:
                counts[stage] = n
    return counts


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    grape = "--grape" in sys.argv
    stages = GRAPE if grape else BROCCOLI
    frames = int(sys.argv[2]) + (0 if grape else 1)
    c = inclusive_counts(sys.argv[1], stages)
    if grape:
        # The main thread's segment calls plus every other thread (pass workers, TBB's, OpenMP's):
        # the program less what the main thread did outside the segmenter (start-up, loading).
        c["total"] = c.get("program", 0) - c.get("main thread", 0) + c.get("segment", 0)
    elif "cloud" in c and "denoise" in c:
        c["cloud"] -= c["denoise"]
    names = [k for k in stages if k != "main thread"] + (["total"] if grape else [])
    per_frame = {k: c.get(k, 0) / frames for k in names}
    if "--json" in sys.argv:
        print(json.dumps(per_frame))
        return
    unit = "a cloud" if grape else "a frame"
    for k, v in per_frame.items():
        print(f"{k:14s} {v / 1e6:8.2f} M instructions {unit}")


if __name__ == "__main__":
    main()
