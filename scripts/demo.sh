#!/usr/bin/env bash
# Sets up, builds and opens the editor on the demo room (one luminaire of each kind: an area
# light, a measured light field and a photometric file; resources/scenes/editor-room.json, at the
# exposure the scene names). Without a display it renders it offscreen and writes the
# screenshots into ./candela-screenshots/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
exec ./build/candela edit resources/scenes/editor-room.json "$@"
