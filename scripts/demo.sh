#!/usr/bin/env bash
# One command from a fresh Debian machine: install what is needed, build, run the main demo.
# Everything goes to out/demo/: the drop test, the packing, and the paper's bubbling bed with
# frames, a video, a montage like the paper's Figs 9-11 and the plots of Figs 8, 12-13 and 15.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
FB=build/app/fluidbed
OUT=out/demo
mkdir -p "$OUT"
echo "== the paper's drop test: one sphere onto the floor"
$FB run assets/scenes/drop.toml --out "$OUT/drop"
echo "== the paper's packing: 2400 spheres settle for 0.8 s in still air"
$FB run assets/scenes/packing.toml --out "$OUT/packing"
echo "== the paper's bed at U = 2.8 m/s (jet 42 m/s): 2 s with frames, video and plots"
$FB run assets/scenes/xu_yu_1997.toml --until 2 --set diagnostics.averaging_start=0.5 \
  --frames --video --plots --montage 0.1,0.2,0.3,0.5,1.0,1.5,2.0 --out "$OUT/bed"
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
d = json.load(open(f"{out}/drop/summary.json"))
p = json.load(open(f"{out}/packing/summary.json"))
b = json.load(open(f"{out}/bed/summary.json"))
print(f"drop:    restitution {d['restitution']:.4f} (analytic 0.895), rebound height ratio {d['rebound_height_ratio']:.4f}")
print(f"packing: bed height {p['bed_height_m']:.4f} m (peers 0.232-0.236), solid fraction {p['solid_fraction']:.4f} (peers 0.563-0.575)")
print(f"bed:     mean dp {b['dp_mean_pa']:.0f} Pa (bed weight per area {b['bed_weight_per_area_pa']:.0f} Pa), "
      f"{b['wall_s_per_sim_s']:.1f} wall s per simulated s")
PY
echo "results in $OUT/ (bed/video.mp4, bed/montage.png, bed/frames/, bed/dp.png, bed/trajectory.png)"
