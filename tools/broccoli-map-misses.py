#!/usr/bin/env python3
"""Which true heads a broccoli field map missed, and what the detector saw of them.

Usage: tools/broccoli-map-misses.py SEQ DETECTIONS.jsonl MAP.csv
  SEQ: a simulated pass (groundtruth.json); DETECTIONS.jsonl and MAP.csv from
  `cropsight detect broccoli --data SEQ --model M --track --set tracking.use_poses=true --out D --map M.csv`.
A true head counts when its max_visible_pixels >= 300 (the evaluator counts frames with 300 valid
points: close, not identical) and is missed when no map head lies within 5 cm (the map evaluation's
radius; the evaluator's one-to-one matching can differ by a head). For each miss: its size,
frames in view, occlusion, the nearest map head, and every frame's detection within 8 cm of it
(frame, distance m, track id, classifier score, points, box). Standard library only.
"""
import csv
import json
import math
import sys


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    seq, detections, map_csv = sys.argv[1:4]
    truth = json.load(open(seq + "/groundtruth.json"))["instances"]
    mapped = [[float(m[k]) for k in ("x_m", "y_m", "z_m")] for m in csv.DictReader(open(map_csv))]
    frames = [json.loads(line) for line in open(detections)]
    for head in truth:
        if head.get("max_visible_pixels", 0) < 300:
            continue
        p = head["position"]
        nearest = min((math.dist(p, m) for m in mapped), default=float("inf"))
        if nearest <= 0.05:
            continue
        print(f"{seq}: missed head {head['id']} at {[round(x, 3) for x in p]}, {head['diameter_mm']:.0f} mm, "
              f"in view {head['frames_visible']:.0f} frames ({head['frames_fully_in_view']:.0f} whole), "
              f"max {head['max_visible_pixels']:.0f} px, occlusion {head.get('occlusion')}, nearest map head {nearest:.3f} m")
        for f in frames:
            for h in f["heads"]:
                d = math.dist(p, h["field"])
                if d < 0.08:
                    det = next((x for x in f["detections"] if x["id"] == h["id"]), None)
                    print(f"    frame {f['frame']}: {d:.3f} m, track {h['track_id']}",
                          f"score {det['score']:.2f}, {det['points']} points, box {det['box']}" if det else "")


if __name__ == "__main__":
    main()
