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
        [--kinds A,B] [--rules old[,RULE...]] [--passes DIR]
    (CROPSIGHT=build/bin/cropsight)

--kinds picks field kinds by letter (A and B develop a ranking rule, C and D judge it); --rules ranks
the frames with each of RULES (below) and trains on each rule's frames (a rule choosing the same frames
as an earlier one reuses its result); --passes reads simulated passes from another OUT (nothing is
written there).

Writes OUT/results-RECIPE[-with-general]-KINDS.json (every run) and prints the markdown table of docs/adapting.md.
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
    # C and D judge a ranking rule chosen on A and B: defined (values and seeds) before any rule was
    # tried, pinned away from A and B (the third leaf family, a low camera and small heads; a high
    # camera over one dense row of large heads); seeds 86xx, used by no model or earlier experiment.
    "C: obovate leaves, two rows, 1.10 m": {"sets": pinned({
        "camera_height_m": 1.10, "camera_tilt_deg": 1, "row_spacing_m": 0.6, "in_row_spacing_m": 0.45,
        "leaf_count": 7, "leaf_length_m": 0.30, "leaf_elevation_deg": 35,
        "leaf_droop_deg": 60, "leaf_ruffle_m": 0.005, "plant_height_m": 0.50, "head_diameter_mm": [45, 140],
        "head_dome_ratio": 0.75, "floret_ratio": 0.08, "floret_height": 0.2, "head_below_canopy_m": 0.05,
        "inner_leaves": 1, "soil_roughness_m": 0.005, "clod_density_m2": 20, "weed_density_m2": 0,
        "tof_noise_at_1m_m": 0.002, "tof_flying_prob": 0.3, "tof_amplitude_min": 0.04, "random_dropout": 0.005})
        + ["randomize.one_row_prob=0", "randomize.leaf_family_weights=[0,0,1]"], "pools": [8601, 8602], "tests": [8611, 8612, 8613, 8614]},
    "D: broad leaves, one dense row, 1.55 m": {"sets": pinned({
        "camera_height_m": 1.55, "camera_tilt_deg": 5, "row_spacing_m": 0.55, "in_row_spacing_m": 0.27,
        "leaf_count": 16, "leaf_length_m": 0.50, "leaf_elevation_deg": 70,
        "leaf_droop_deg": 20, "leaf_ruffle_m": 0.025, "plant_height_m": 0.72, "head_diameter_mm": [80, 190],
        "head_dome_ratio": 0.4, "floret_ratio": 0.24, "floret_height": 0.85, "head_below_canopy_m": 0.08,
        "inner_leaves": 3, "soil_roughness_m": 0.03, "clod_density_m2": 140, "weed_density_m2": 30,
        "tof_noise_at_1m_m": 0.006, "tof_flying_prob": 0.85, "tof_amplitude_min": 0.15, "random_dropout": 0.025})
        + ["randomize.one_row_prob=1", "randomize.leaf_family_weights=[0,1,0]"], "pools": [8621, 8622], "tests": [8631, 8632, 8633, 8634]},
}
# Ranking rules of `suggest`, written out in full so that the results do not depend on its defaults.
# "old": the rule measured first (uncertainty and diversity); the others add the frame's predicted
# heads (--heads-weight, suggest.hpp). Every rule tried on the development kinds A and B is listed;
# "heads-1" was chosen there and is suggest's default since (docs/experiments/2026-12-07-suggest-rule.md).
RULES = {"old": ["--heads-weight", "0"], "heads-0.5": ["--heads-weight", "0.5"], "heads-1": ["--heads-weight", "1"],
         "heads-2": ["--heads-weight", "2"]}
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


def simulate(out, variety, seed, frames, sets, name, passes=None):
    if passes and os.path.isdir(os.path.join(passes, name)):
        return os.path.join(passes, name)
    path = os.path.join(out, name)
    if not os.path.isdir(path):
        cs("simulate", "broccoli", "--variety", variety, "--seed", str(seed), "--frames", str(frames),
           "--out", path, "--quiet", *[a for s in sets for a in ("--set", s)])
    return path


def train_eval(out, name, pool, frames, tests, recipe, extra=None):
    """Trains on `frames` of `pool` and evaluates on `tests`; a rerun with the same inputs reads the
    result kept beside the model (so that adding a rule to a finished run trains only that rule)."""
    model = os.path.join(out, "models-" + recipe, name + ".json")
    inputs = {"pool": pool, "frames": frames, "tests": tests, "extra": extra, "sets": RECIPES[recipe]}
    kept = model[:-len(".json")] + ".result.json"
    if os.path.exists(kept):
        with open(kept) as f:
            old = json.load(f)
        if old["inputs"] == inputs:
            return old["result"]
    result = train_eval_now(model, pool, frames, tests, recipe, extra)
    with open(kept + ".part", "w") as f:
        json.dump({"inputs": inputs, "result": result}, f)
    os.replace(kept + ".part", kept)
    return result


def train_eval_now(model, pool, frames, tests, recipe, extra):
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
    tests = [simulate(out, "random-wide", s, TEST_FRAMES, spec["sets"], f"test-{s}", a.passes) for s in spec["tests"]]
    base = cs("eval", "broccoli", "--data", ",".join(tests), "--model", "broccoli-oes-general", "--json")
    res = {"kind": kind, "general": {"kappa": base["kappa"], "precision": base["precision"]}, "runs": []}
    for pool_seed in spec["pools"][:a.pools]:
        pool = simulate(out, "random-wide", pool_seed, POOL_FRAMES, spec["sets"], f"pool-{pool_seed}", a.passes)
        ns = [10] if with_general else NS
        # The ranking is greedy, so its first n frames are what `suggest --frames n` prints: one run
        # per rule and pass serves every n.
        rankings = {rule: cs("suggest", "--data", pool, "--frames", str(max(ns)), "--json", *RULES[rule])["frames"]
                    for rule in a.rules}
        for n in ns:
            extra = general if with_general else None
            tag = "g" if with_general else ""
            row = {"pool": pool_seed, "n": n, "suggest": {}}
            done = {}  # frames (as a tuple) -> result, so that rules that agree train once
            for rule in a.rules:
                ranked = rankings[rule][:n]
                if tuple(ranked) not in done:
                    done[tuple(ranked)] = train_eval(out, f"s{tag}-{rule}-{pool_seed}-{n}", pool, ranked, tests,
                                                     a.recipe, extra)
                row["suggest"][rule] = done[tuple(ranked)]
            rng = random.Random(pool_seed * 100 + n)
            row["random"] = [train_eval(out, f"r{tag}-{pool_seed}-{n}-{d}", pool,
                                        sorted(rng.sample(range(POOL_FRAMES), n)), tests, a.recipe, extra)
                             for d in range(draws)]
            res["runs"].append(row)
            said = "; ".join(f"{r} kappa {row['suggest'][r]['kappa']:.3f}" for r in a.rules)
            drawn = " ".join(f"{d['kappa']:.3f}" for d in row["random"])
            print(f"{kind} pool {pool_seed} N={n}: {said}; random kappa {drawn}", file=sys.stderr, flush=True)
    return res


def spread(vals):
    m = sum(vals) / len(vals)
    return m, (sum((v - m) ** 2 for v in vals) / max(1, len(vals) - 1)) ** 0.5


def table(results, rules):
    """κ per kind and N: each rule's (mean over labelling passes), the random draws' mean ± standard
    deviation and range, and how many draws beat each rule (a draw against its own pass's rule)."""
    lines = ["| kind | N | " + " | ".join(f"{r}: κ / precision" for r in rules) +
             " | random κ: mean ± sd (min–max) | " + " | ".join(f"draws above {r}" for r in rules) +
             " | general model: κ / precision |", "|---" * (4 + 2 * len(rules)) + "|"]
    for res in results:
        for n in sorted({r["n"] for r in res["runs"]}):
            rows = [r for r in res["runs"] if r["n"] == n]
            rd = [d["kappa"] for r in rows for d in r["random"] if d["kappa"] is not None]
            cells = [f"{mean([r['suggest'][u] for r in rows], 'kappa'):.3f} / "
                     f"{mean([r['suggest'][u] for r in rows], 'precision'):.3f}" for u in rules]
            above = [f"{sum(d['kappa'] > r['suggest'][u]['kappa'] for r in rows for d in r['random'])} of {len(rd)}"
                     for u in rules]
            m, sd = spread(rd) if rd else (float("nan"), float("nan"))
            g = res["general"]
            lines.append(f"| {res['kind'][0]} | {n} | " + " | ".join(cells) +
                         f" | {m:.3f} ± {sd:.3f} ({min(rd, default=float('nan')):.3f}–{max(rd, default=float('nan')):.3f}) | " +
                         " | ".join(above) + f" | {g['kappa']:.3f} / {g['precision']:.3f} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--draws", type=int, default=5, help="random draws per pool and N")
    ap.add_argument("--with-general", action="store_true", help="train with the general model's passes (N = 10)")
    ap.add_argument("--pools", type=int, default=2, help="labelling passes per field kind (1 or 2)")
    ap.add_argument("--recipe", choices=sorted(RECIPES), default="small", help="training settings (above)")
    ap.add_argument("--kinds", default="A,B", help="field kinds by letter, e.g. A,B or C,D")
    ap.add_argument("--rules", default="old", help="suggest's ranking rules, comma-separated: " + ", ".join(RULES))
    ap.add_argument("--passes", help="another OUT whose simulated passes to read (not written)")
    a = ap.parse_args()
    a.rules = a.rules.split(",")
    if bad := [r for r in a.rules if r not in RULES]:
        ap.error(f"unknown rule {bad[0]}; known: {', '.join(RULES)}")
    kinds = {k: v for k, v in KINDS.items() if k[0] in a.kinds.split(",")}
    if not kinds or len(kinds) != len(a.kinds.split(",")):
        ap.error(f"--kinds {a.kinds}: letters of {', '.join(k[0] for k in KINDS)}, comma-separated")
    os.makedirs(os.path.join(a.out, "models-" + a.recipe), exist_ok=True)
    general = None
    if a.with_general:
        general = [simulate(a.out, v, s, f, [], f"general-{v}-{s}") for v, s, f in GENERAL_DATA]
    results = [run_kind(a.out, k, spec, a, general) for k, spec in kinds.items()]
    name = f"results-{a.recipe}{'-with-general' if a.with_general else ''}-{''.join(kinds_[0] for kinds_ in kinds)}.json"
    with open(os.path.join(a.out, name), "w") as f:
        json.dump(results, f, indent=1)
    print(table(results, a.rules))


if __name__ == "__main__":
    main()
