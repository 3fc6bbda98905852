#!/usr/bin/env bash
# The held-out potato loop tables of docs/pipelines/potatoes.md ("Position and tracking"): seeds
# (default 2201-2203; the 2026-12-05 table adds 2301-2303) x sheet/room/chamber, 40 frames, each
# scored with the potato and potato-paper presets.
#   tools/potato-heldout.sh BUILD_DIR OUT_DIR [SEED...]
set -euo pipefail
bin=$1/bin/cropsight out=$2
shift 2
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(2201 2202 2203)
mkdir -p "$out"
for s in "${seeds[@]}"; do for sc in sheet room chamber; do
  [ -d "$out/${sc}_$s" ] || "$bin" simulate potato --scene $sc --frames 40 --seed $s --out "$out/${sc}_$s" > /dev/null
  for p in potato potato-paper; do
    "$bin" eval potato --data "$out/${sc}_$s" --config $p --json | python3 -c "
import json, sys; j = json.load(sys.stdin); P = j['position']
print('$sc $s $p positioned', j['frames_positioned'], 'cut', j['frames_cut'],
      'MAE x/y/z %.1f / %.1f / %.1f mm' % (P['x']['mae_mm'], P['y']['mae_mm'], P['z']['mae_mm']),
      'mean z %+.1f' % P['z']['mean_mm'], 'switches', j['target_switches'], 'lost', j['lost_events'],
      'angle %.1f deg' % j['angle_mae_deg'])"
  done
done; done
