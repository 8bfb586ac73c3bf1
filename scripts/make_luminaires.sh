#!/usr/bin/env bash
# Generates the procedural headlight light fields (too big for the repository) into
# resources/luminaires/generated/: bike-headlight (9x7 images of 300x300) and car-headlight
# (11x9 images of 256x256), about 15 s each on two cores.
# Usage: bash scripts/make_luminaires.sh [path/to/candela]  (default: build/candela, built if absent)
# The committed resources/luminaires/osram-lertduw.lf.json is made by the command in
# resources/luminaires/LICENSE.md.
set -euo pipefail
cd "$(dirname "$0")/.."
candela=${1:-build/candela}
if [ ! -x "$candela" ]; then
  bash scripts/build.sh
  candela=build/candela
fi
out=resources/luminaires/generated
mkdir -p "$out"
for preset in bike-headlight car-headlight; do
  "$candela" convert --procedural "$preset" --out "$out/$preset.lf.json"
done
