#!/usr/bin/env bash
# Sets up, builds and opens the editor on the bundled demo scene. Without a display it renders
# the demo scene offscreen and writes the screenshots into ./candela-screenshots/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
exec ./build/candela edit resources/scenes/demo.json "$@"
