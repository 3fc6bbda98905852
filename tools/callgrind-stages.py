#!/usr/bin/env python3
"""Instruction counts of the broccoli detector's stages from a callgrind profile.

    tools/callgrind-stages.py CALLGRIND_OUT FRAMES [--json]

CALLGRIND_OUT: valgrind --tool=callgrind of `cropsight bench broccoli --pipelines oes` (one
warm-up frame + FRAMES timed ones, so counts are divided by FRAMES + 1). A stage's count is the
inclusive count of the function its StageTimer scope lives in (callgrind_annotate --inclusive);
"cloud" excludes the denoising, which has its own scope inside it. Callgrind runs the AVX2
clones (valgrind has no AVX-512), so counts are those of an AVX2 machine."""
import json
import re
import subprocess
import sys

# Stage name -> the function holding its StageTimer scope (a substring of the demangled name).
STAGES = {
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


def inclusive_counts(path):
    out = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", path],
                         capture_output=True, text=True, check=True).stdout
    counts = {}
    for line in out.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\([^)]*\)\s+\S*?:(.*)", line)
        if not m:
            continue
        n = int(m.group(1).replace(",", ""))
        for stage, fn in STAGES.items():
            if fn in m.group(2) and stage not in counts:
                counts[stage] = n
    return counts


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    frames = int(sys.argv[2]) + 1
    c = inclusive_counts(sys.argv[1])
    if "cloud" in c and "denoise" in c:
        c["cloud"] -= c["denoise"]
    per_frame = {k: c.get(k, 0) / frames for k in STAGES}
    if "--json" in sys.argv:
        print(json.dumps(per_frame))
        return
    for k, v in per_frame.items():
        print(f"{k:12s} {v / 1e6:8.2f} M instructions a frame")


if __name__ == "__main__":
    main()
