#!/usr/bin/env python3
"""Compares two folders written by tools/golden-outputs.sh (before and after a change).

    tools/golden-compare.py BEFORE AFTER

JSON outputs must agree on every key they share, numbers to 1e-9 relative, except timings and
paths (key names with a part ms, fps, seconds, time, stages or speedup, or with ratio_to_ as the bench
commands' ratios of two timings; the keys out, masks, model, data, map); keys only in
AFTER are listed as new, keys only in BEFORE are an error. Other files must be byte-identical
(the HTML report only in its figures, not compared). A file on one side only, or a command that
failed on either side ("exit N" in its .err), is a difference too. Exit 1 on any difference."""
import filecmp
import json
import math
import os
import re
import sys

TIMING = ("ms", "fps", "seconds", "time", "stages", "speedup")  # parts of a key name: "tracking_ms_per_frame"
PATHS = ("out", "masks", "model", "data", "map")      # whole key names


def skipped(key):
    return any(s in key.lower().split("_") for s in TIMING) or "ratio_to_" in key or key in PATHS


def compare(a, b, path, errors, new):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in a:
            if skipped(k):
                continue
            if k not in b:
                errors.append(f"{path}.{k}: missing after")
            else:
                compare(a[k], b[k], f"{path}.{k}", errors, new)
        new.extend(f"{path}.{k}" for k in b if k not in a)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            errors.append(f"{path}: {len(a)} vs {len(b)} items")
        for i, (x, y) in enumerate(zip(a, b)):
            compare(x, y, f"{path}[{i}]", errors, new)
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        if not (a == b or (math.isfinite(a) and abs(a - b) <= 1e-9 * max(1.0, abs(a)))):
            errors.append(f"{path}: {a} vs {b}")
    elif a != b:
        errors.append(f"{path}: {a!r} vs {b!r}")


def json_documents(path):
    """One document (a pretty-printed file) or one per line (JSON lines)."""
    text = open(path).read()
    try:
        return [json.loads(text)] if text.strip() else []
    except json.JSONDecodeError:
        return [json.loads(l) for l in text.splitlines() if l.strip()]


def failed_runs(folder):
    """The commands golden-outputs.sh saw fail: their .err ends with "exit N"."""
    out = []
    for name in sorted(os.listdir(folder)):
        if name.endswith(".err"):
            lines = open(os.path.join(folder, name)).read().splitlines()
            if lines and lines[-1].startswith("exit "):
                out.append(f"{name[:-4]} failed in {folder} ({lines[-1]})")
    return out


def main(before, after):
    errors, new = failed_runs(before) + failed_runs(after), []
    # A run that stopped early leaves fewer files on one side: that is a difference, not agreement.
    for name in sorted(set(os.listdir(after)) - set(os.listdir(before))):
        if not (name == "data" or name.endswith(".err") or name.endswith(".html")):
            errors.append(f"{name}: missing before")
    for name in sorted(os.listdir(before)):
        pa, pb = os.path.join(before, name), os.path.join(after, name)
        if name == "data" or name.endswith(".err") or name.endswith(".html"):
            continue
        if not os.path.exists(pb):
            errors.append(f"{name}: missing after")
        elif os.path.isdir(pa):
            d = filecmp.dircmp(pa, pb)
            if d.left_only or d.right_only or filecmp.cmpfiles(pa, pb, d.common_files, shallow=False)[1]:
                errors.append(f"{name}/: differs")
        elif name.endswith(".json") or name.endswith(".jsonl"):
            la, lb = json_documents(pa), json_documents(pb)
            if len(la) != len(lb):
                errors.append(f"{name}: {len(la)} vs {len(lb)} lines")
            for i, (x, y) in enumerate(zip(la, lb)):
                compare(x, y, f"{name}:{i + 1}", errors, new)
        elif not filecmp.cmp(pa, pb, shallow=False):
            errors.append(f"{name}: differs")
    for n in sorted(set(re.sub(r":\d+\.", ": ", k) for k in new)):  # one line per key, not per JSON line
        print("new:", n)
    for e in errors:
        print("DIFF:", e)
    print(f"{len(errors)} differences")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
