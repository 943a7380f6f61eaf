#!/usr/bin/env bash
# One command from a fresh Debian machine: install what is needed, build, run the main demo.
# Results go to out/demo/ (summaries, timeseries, the packed bed).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
FB=build/app/fluidbed
OUT=out/demo
mkdir -p "$OUT"
echo "== the paper's drop test: one sphere onto the floor"
$FB run assets/scenes/drop.toml --out "$OUT/drop"
echo "== the paper's packing: 2400 spheres settle for 0.8 s"
$FB run assets/scenes/packing.toml --out "$OUT/packing"
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
d = json.load(open(f"{out}/drop/summary.json"))
p = json.load(open(f"{out}/packing/summary.json"))
print(f"drop:    restitution {d['restitution']:.4f} (analytic 0.895), rebound height ratio {d['rebound_height_ratio']:.4f}")
print(f"packing: bed height {p['bed_height_m']:.4f} m (peers 0.232-0.236), solid fraction {p['solid_fraction']:.4f} (peers 0.563-0.575)")
print(f"         {p['wall_s_per_sim_s']:.2f} wall s per simulated s, {p['particle_steps_per_s']:.3g} particle-steps/s")
PY
echo "results in $OUT/"
