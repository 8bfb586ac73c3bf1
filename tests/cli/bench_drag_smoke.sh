#!/usr/bin/env bash
# `candela bench --drag` runs end to end on the demo room at a tiny size: drag rows for preview
# and full settings, release rows for "moved only" and "everything" with finite figures, and the
# summary. (A smoke test of the tool; the figures are benchmarks, committed under
# docs/bench/drag, never asserted here.)
set -uo pipefail
binary=$1
scene="$2/../resources/scenes/demo.json"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }

"$binary" bench --drag "$scene" --out "$out" --size 96x54 --frames 4 --reference-spp 32 --timeout 5 \
  >"$out/stdout" 2>"$out/stderr"
rc=$?
check "bench exits 0 (rc $rc): $(tail -3 "$out/stderr")" '[ $rc -eq 0 ]'
check "drag.csv: preview and full rows" '[ "$(grep -c ",preview," "$out/drag.csv")" -ge 1 ] && [ "$(grep -c ",full," "$out/drag.csv")" -ge 1 ]'
check "release.csv header" '[ "$(head -1 "$out/release.csv")" = "luminaire,refines,seconds,spp,mean_delta_e,rel_rmse" ]'
check "release rows of both kinds" 'grep -q ",moved only," "$out/release.csv" && grep -q ",everything," "$out/release.csv"'
bad=$(tail -n +2 "$out/release.csv" | awk -F, '!($3 > 0 && $5 >= 0 && $5 == $5 && $6 >= 0 && $6 == $6) {print}')
check "finite figures: $bad" '[ -z "$bad" ]'
check "summary states its light" 'grep -q "^light: .*interreflected light" "$out/summary.txt"'
check "summary names both release times" 'grep -q "refining it alone" "$out/summary.txt" && grep -q "refining everything" "$out/summary.txt"'
echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
