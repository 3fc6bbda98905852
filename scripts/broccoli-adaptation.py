#!/usr/bin/env python3
"""Adapting the broccoli detector to a field kind from N labelled frames, chosen by `suggest` or at random.

For each field kind (the simulator's randomised fields pinned to a description, none of their seeds
used by the general model: models/README.md), a labelling pass and four test passes are simulated.
For N = 5, 10, 20 the frames of the labelling pass are chosen by `cropsight suggest` (with the
general model) and, as the baseline, at random (several draws, reported as their mean); a model is
trained on only those frames (`train broccoli --frame-list`, the general model's detector settings) and
evaluated on the kind's test passes (`eval broccoli`: kappa and precision per cluster). With
--with-general the N frames are trained together with the general model's own training passes
(`--extra-data`), for N = 10 only (each such training takes minutes).

    scripts/broccoli-adaptation.py OUT [--recipe small|general] [--with-general] [--draws 5] [--pools 2]
    (CROPSIGHT=build/bin/cropsight)

Writes OUT/results-RECIPE[-with-general].json (every run) and prints the markdown table of docs/adapting.md.
"""
import argparse
import json
import os
import random
import subprocess
import sys

CS = os.environ.get("CROPSIGHT", "build/bin/cropsight")

# A field kind is what a farm's own fields share: one variety, one rig, one soil. Every
# randomize.* range of `--variety random-wide` is pinned to one value (head sizes to a window), so
# that the kind's passes differ only in their plants' layout, size and leaves drawn within it. The
# values lie in random-wide's ranges and are no preset's; no seed here trains or tunes a shipped model.
def pinned(values):
    return [f"randomize.{k}=[{v},{v}]" if not isinstance(v, list) else f"randomize.{k}=[{v[0]},{v[1]}]"
            for k, v in values.items()] + ["randomize.stereo_prob=0", "randomize.sunlight_prob=0"]


KINDS = {
    "A: broad leaves, two rows, 1.25 m": {"sets": pinned({
        "camera_height_m": 1.25, "camera_tilt_deg": 2, "row_spacing_m": 0.75, "in_row_spacing_m": 0.38,
        "leaf_count": 10, "leaf_length_m": 0.38, "leaf_elevation_deg": 50,
        "leaf_droop_deg": 45, "leaf_ruffle_m": 0.01, "plant_height_m": 0.62, "head_diameter_mm": [55, 165],
        "head_dome_ratio": 0.6, "floret_ratio": 0.12, "floret_height": 0.4, "head_below_canopy_m": 0.12,
        "inner_leaves": 2, "soil_roughness_m": 0.01, "clod_density_m2": 40, "weed_density_m2": 5,
        "tof_noise_at_1m_m": 0.003, "tof_flying_prob": 0.5, "tof_amplitude_min": 0.08, "random_dropout": 0.01})
        + ["randomize.one_row_prob=0", "randomize.leaf_family_weights=[0,1,0]"], "pools": [8501, 8502], "tests": [8511, 8512, 8513, 8514]},
    "B: pointed leaves, one row, 1.40 m": {"sets": pinned({
        "camera_height_m": 1.40, "camera_tilt_deg": 4, "row_spacing_m": 0.9, "in_row_spacing_m": 0.30,
        "leaf_count": 14, "leaf_length_m": 0.45, "leaf_elevation_deg": 60,
        "leaf_droop_deg": 30, "leaf_ruffle_m": 0.02, "plant_height_m": 0.70, "head_diameter_mm": [70, 180],
        "head_dome_ratio": 0.45, "floret_ratio": 0.2, "floret_height": 0.7, "head_below_canopy_m": 0.18,
        "inner_leaves": 4, "soil_roughness_m": 0.02, "clod_density_m2": 100, "weed_density_m2": 20,
        "tof_noise_at_1m_m": 0.005, "tof_flying_prob": 0.7, "tof_amplitude_min": 0.12, "random_dropout": 0.02})
        + ["randomize.one_row_prob=1", "randomize.leaf_family_weights=[1,0,0]"], "pools": [8521, 8522], "tests": [8531, 8532, 8533, 8534]},
}
POOL_FRAMES, TEST_FRAMES, NS = 40, 30, [5, 10, 20]

# The general model's detector settings (models/README.md), so that only the training data differ.
GENERAL_SETS = [
    "oes.distance_tolerance=0.007", "detection.score_margin=0.4", "oes.debris_tolerance=0.01",
    "normals.max_depth_change_factor=0.04", "detection.grow_tolerance=0.013", "normals.nan_breaks_window=false",
    "classifier.rbf_c=0.5", "detection.split_concave_angle_deg=20", "detection.split_score_margin=0.7",
    "denoise.above=0.006", "denoise.sigma_factor=2.5", "denoise.in_training=false", "range.soil_relative=true",
    "range.extend_only=true", "range.min_height_above_soil=0.25", "detection.split_score_window=2",
    "oes.max_size=40000", "detection.split_oversized_above=10000", "detection.split_accepted=true"]
# The recipes: "general" trains with exactly those settings; "small" sets back the two that were
# tuned for the general model's 39 k samples to the presets' values (score margin 0: the classifier's
# own threshold; C = 2), since a model of a few frames scores its heads closer to the threshold.
RECIPES = {"general": GENERAL_SETS, "small": GENERAL_SETS + ["detection.score_margin=0", "classifier.rbf_c=2"]}
GENERAL_DATA = ([("random", s, 40) for s in range(5001, 5017)] +
                [("uk", 1001, 80), ("uk", 1003, 80), ("spain", 1002, 80), ("spain", 1004, 80)])


def cs(*args):
    r = subprocess.run([CS, *args], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"failed: {CS} {' '.join(args)}\n{r.stderr}")
    return json.loads(r.stdout) if "--json" in args else r.stdout


def simulate(out, variety, seed, frames, sets, name):
    path = os.path.join(out, name)
    if not os.path.isdir(path):
        cs("simulate", "broccoli", "--variety", variety, "--seed", str(seed), "--frames", str(frames),
           "--out", path, "--quiet", *[a for s in sets for a in ("--set", s)])
    return path


def train_eval(out, name, pool, frames, tests, recipe, extra=None):
    model = os.path.join(out, "models-" + recipe, name + ".json")
    args = ["train", "broccoli", "--data", pool, "--frame-list", ",".join(map(str, frames)), "--config",
            "broccoli-oes-uk", "--out", model, "--force", "--json"]
    if extra:
        args += ["--extra-data", ",".join(extra)]
    t = cs(*args, *[a for s in RECIPES[recipe] for a in ("--set", s)])
    e = cs("eval", "broccoli", "--data", ",".join(tests), "--model", model, "--json")
    return {"frames": frames, "kappa": e["kappa"], "precision": e["precision"], "recall": e["recall"],
            "train_s": t["seconds"], "samples": t["samples"], "heads": t["positives"]}


def mean(rows, key):
    vals = [r[key] for r in rows if r[key] is not None]
    return sum(vals) / len(vals) if vals else float("nan")


def run_kind(out, kind, spec, a, general):
    draws, with_general = a.draws, a.with_general
    tests = [simulate(out, "random-wide", s, TEST_FRAMES, spec["sets"], f"test-{s}") for s in spec["tests"]]
    base = cs("eval", "broccoli", "--data", ",".join(tests), "--model", "broccoli-oes-general", "--json")
    res = {"kind": kind, "general": {"kappa": base["kappa"], "precision": base["precision"]}, "runs": []}
    for pool_seed in spec["pools"][:a.pools]:
        pool = simulate(out, "random-wide", pool_seed, POOL_FRAMES, spec["sets"], f"pool-{pool_seed}")
        ns = [10] if with_general else NS
        for n in ns:
            ranked = cs("suggest", "--data", pool, "--frames", str(n), "--json")["frames"]
            extra = general if with_general else None
            tag = "g" if with_general else ""
            row = {"pool": pool_seed, "n": n, "suggest": train_eval(out, f"s{tag}-{pool_seed}-{n}", pool, ranked,
                                                                   tests, a.recipe, extra)}
            rng = random.Random(pool_seed * 100 + n)
            row["random"] = [train_eval(out, f"r{tag}-{pool_seed}-{n}-{d}", pool,
                                        sorted(rng.sample(range(POOL_FRAMES), n)), tests, a.recipe, extra)
                             for d in range(draws)]
            res["runs"].append(row)
            print(f"{kind} pool {pool_seed} N={n}: suggest kappa {mean([row['suggest']], 'kappa'):.3f} "
                  f"P {mean([row['suggest']], 'precision'):.3f}; random kappa {mean(row['random'], 'kappa'):.3f} "
                  f"P {mean(row['random'], 'precision'):.3f}", file=sys.stderr, flush=True)
    return res


def table(results, with_general):
    lines = ["| field kind | N | suggest: κ / precision | random (mean of draws): κ / precision | "
             "general model alone: κ / precision |", "|---|---|---|---|---|"]
    for res in results:
        for n in sorted({r["n"] for r in res["runs"]}):
            rows = [r for r in res["runs"] if r["n"] == n]
            s = [r["suggest"] for r in rows]
            rd = [d for r in rows for d in r["random"]]
            g = res["general"]
            lines.append(f"| {res['kind']}{' + general set' if with_general else ''} | {n} | "
                         f"{mean(s, 'kappa'):.3f} / {mean(s, 'precision'):.3f} | "
                         f"{mean(rd, 'kappa'):.3f} / {mean(rd, 'precision'):.3f} | "
                         f"{g['kappa']:.3f} / {g['precision']:.3f} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--draws", type=int, default=5, help="random draws per pool and N")
    ap.add_argument("--with-general", action="store_true", help="train with the general model's passes (N = 10)")
    ap.add_argument("--pools", type=int, default=2, help="labelling passes per field kind (1 or 2)")
    ap.add_argument("--recipe", choices=sorted(RECIPES), default="small", help="training settings (above)")
    a = ap.parse_args()
    os.makedirs(os.path.join(a.out, "models-" + a.recipe), exist_ok=True)
    general = None
    if a.with_general:
        general = [simulate(a.out, v, s, f, [], f"general-{v}-{s}") for v, s, f in GENERAL_DATA]
    results = [run_kind(a.out, k, spec, a, general) for k, spec in KINDS.items()]
    name = f"results-{a.recipe}{'-with-general' if a.with_general else ''}.json"
    with open(os.path.join(a.out, name), "w") as f:
        json.dump(results, f, indent=1)
    print(table(results, a.with_general))


if __name__ == "__main__":
    main()
