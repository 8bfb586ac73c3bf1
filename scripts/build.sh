#!/usr/bin/env bash
# Configures and builds Candela into build/ (Release), then makes the generated light fields if
# they are missing. Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j"$(nproc)"
# The procedural headlight light fields (too big for the repository) that the headlight scenes,
# the shadow-map tests and the benches use: made once, about 30 s.
if [ ! -f resources/luminaires/generated/car-headlight.lf.json ] ||
   [ ! -f resources/luminaires/generated/bike-headlight.lf.json ]; then
  bash scripts/make_luminaires.sh build/candela
fi
