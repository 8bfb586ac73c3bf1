#!/usr/bin/env bash
# Sets up, builds and runs every test: CPU tests, GL tests (OSMesa), CLI tests and the editor's
# end-to-end test under Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
cd build
ctest --output-on-failure -j2 --timeout 600
