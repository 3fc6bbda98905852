#!/usr/bin/env python3
"""Markdown tables of the broccoli train/test matrix from scripts/broccoli-matrix.sh results.

    scripts/broccoli-tables.py OUT/results
"""
import json
import os
import sys

res = sys.argv[1] if len(sys.argv) > 1 else "broccoli-matrix/results"


def load(name):
    p = os.path.join(res, name)
    return json.load(open(p)) if os.path.exists(p) else None


def f(v, d=3):
    return "—" if v is None else f"{v:.{d}f}"


print("| pipeline | train → test | clusters | TP | FP | TN | FN | accuracy | precision | recall | specificity | npv | kappa | AP50 | mAP50:95 | AP50 in view | mAP50:95 in view | fps (wall) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for p in ["oes", "org", "fec"]:
    for tr, te in [("uk", "uk"), ("uk", "spain"), ("spain", "spain"), ("spain", "uk")]:
        j = load(f"eval-{p}-{tr}-to-{te}.json")
        if not j:
            continue
        print(f"| {p.upper()} | {tr} → {te} | {j['clusters']} | {j['tp']} | {j['fp']} | {j['tn']} | {j['fn']} | "
              f"{f(j['accuracy'])} | {f(j['precision'])} | {f(j['recall'])} | {f(j['specificity'])} | {f(j['npv'])} | "
              f"{f(j['kappa'])} | {f(j['ap50'])} | {f(j['map50_95'])} | {f(j.get('ap50_in_view'))} | "
              f"{f(j.get('map50_95_in_view'))} | {f(j['fps'], 1)} |")
b = load("bench-uk.json")
if b:
    print()
    print(f"Bench: {b['frames']} frames of {b['data']}, {b['width']}x{b['height']}, single-threaded.")
    print()
    stages = ["cloud", "normals", "edges", "outliers", "clustering", "features", "classify"]
    print("| pipeline | " + " | ".join(stages) + " | total ms (wall) | fps (wall) | CPU ms | fps (CPU) | speedup vs PCL (wall) | speedup vs PCL (CPU) |")
    print("|---|" + "---|" * (len(stages) + 6))
    for name in ["oes", "org", "fec", "pcl_reference"]:
        t = b["pipelines"][name]
        st = t["stages_ms"]
        cells = [f(st.get(s), 2) if s in st else "—" for s in stages]
        print(f"| {name} | " + " | ".join(cells) + f" | {f(t['ms_per_frame'], 2)} | {f(t['fps'], 1)} | "
              f"{f(t.get('cpu_ms_per_frame'), 2)} | {f(t.get('cpu_fps'), 1)} | {f(t.get('speedup_vs_pcl'), 1)} | "
              f"{f(t.get('cpu_speedup_vs_pcl'), 1)} |")
