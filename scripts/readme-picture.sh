#!/usr/bin/env bash
# Regenerates docs/images/paper-bed-montage.png, the picture at the top of README.md: the paper's
# bed (xu_yu_1997.toml, 2.8 m/s through the jet) at six times from the packed bed, coloured by the
# force on each sphere with the gas arrows, as in the paper's Figs 9-11 and 14. Two to three minutes on
# two cores (the packed bed is made first if it is not cached). Needs a build (scripts/build.sh)
# and ffmpeg, which shrinks the montage to a width a README shows without scaling.
set -euo pipefail
cd "$(dirname "$0")/.."
FB=${FLUIDBED:-build/app/fluidbed}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
"$FB" run assets/scenes/xu_yu_1997.toml --until 1.5 --threads 2 --colour force \
  --montage 0.1,0.2,0.3,0.5,1.0,1.5 --frame-size 640x1280 --out "$OUT/bed" >/dev/null
mkdir -p docs/images
ffmpeg -loglevel error -y -i "$OUT/bed/montage.png" -vf "scale=900:-2:flags=area" \
  docs/images/paper-bed-montage.png
echo "wrote docs/images/paper-bed-montage.png"
