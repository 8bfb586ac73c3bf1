#!/usr/bin/env bash
# Replays one fuzz target's regression inputs (fuzz/regressions/TARGET/) and its seeds, once each
# (the ctest of the fuzzing build; scripts/fuzz.sh runs it before fuzzing). Exit 0 when every input
# runs without a crash, a sanitizer report or a failed check.
# Usage: replay.sh FUZZ_BINARY TARGET SOURCE_DIR
set -euo pipefail
binary=$1
target=$2
cd "$3"
source fuzz/targets.sh
mapfile -d '' inputs < <(fuzz_regressions "$target"; fuzz_seeds "$target")
if [ ${#inputs[@]} -eq 0 ]; then
  echo "replay $target: no inputs"
  exit 0
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# Files as arguments: libFuzzer runs each once and stops at the first failure.
if "$binary" -rss_limit_mb=2048 -timeout=60 "${inputs[@]}" >"$log" 2>&1; then
  echo "replay $target: ${#inputs[@]} inputs ($(fuzz_regressions "$target" | tr -cd '\0' | wc -c) regressions), no failure"
else
  grep -v "^Running: " "$log" | tail -80
  echo "replay $target: FAILED"
  exit 1
fi
