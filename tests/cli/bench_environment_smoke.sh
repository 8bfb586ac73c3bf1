#!/usr/bin/env bash
# `candela bench --environment` runs end to end on a small sky at a tiny size: every technique and
# sample count gets a CSV row with finite, positive time and error, the balanced error falls with
# samples, the rebuild and temporal CSVs and the summary are written, and a missing map is named.
# (A smoke test of the tool; the figures are benchmarks, committed under docs/bench/, never
# asserted here.)
set -uo pipefail
binary=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }

"$binary" bench --environment sky --out "$out" --spp 2,32 --reference-spp 256 --size 48x32 --frames 3 \
  >"$out/stdout" 2>"$out/stderr"
rc=$?
check "bench exits 0 (rc $rc): $(tail -3 "$out/stderr")" '[ $rc -eq 0 ]'
# 4 techniques x 2 sample counts + havran2005, after the header.
check "bench.csv has a header and 9 rows" '[ "$(wc -l <"$out/bench.csv")" -eq 10 ]'
bad=$(tail -n +2 "$out/bench.csv" | awk -F, '!($3 > 0 && $4 >= 0 && $5 >= 0 && $3 == $3 && $4 == $4) {print}')
check "finite, positive figures: $bad" '[ -z "$bad" ]'
falls=$(awk -F, '$1 == "balanced" {e[$2] = $6} END {print (e[32] < e[2]) ? "yes" : "no"}' "$out/bench.csv")
check "balanced error falls from 2 to 32 spp" '[ "$falls" = yes ]'
# 2 face sizes x 2 sample counts x 8 frames; the tables are rebuilt every frame (cdf_ms > 0).
check "rebuild.csv: 32 frames, each with a rebuild" \
  '[ "$(tail -n +2 "$out/rebuild.csv" | awk -F, "\$3 > 0" | wc -l)" -eq 32 ]'
# 3 sun steps x 5 cases x (3 - 1) frame pairs.
check "temporal.csv has 30 rows" '[ "$(tail -n +2 "$out/temporal.csv" | wc -l)" -eq 30 ]'
check "summary states its light" 'grep -q "^light: .*interreflected light" "$out/summary.txt"'
check "summary and images written" '[ -s "$out/summary.txt" ] && [ -s "$out/reference.png" ] && [ -s "$out/bench_scene.json" ]'
err=$("$binary" bench --environment "$out/nothing.hdr" --out "$out/x" 2>&1 >/dev/null); rc=$?
check "missing map (rc $rc): $err" '[ $rc -eq 1 ] && grep -q "nothing.hdr" <<<"$err"'
echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
