#!/usr/bin/env bash
# `candela bench --lightfield` runs end to end on a tiny light field: every technique and sample
# count gets a CSV row with finite, positive time and error, errors fall with samples for the
# restricted sampler, and the summary and images are written. (A smoke test of the tool; the
# figures themselves are benchmarks, committed under docs/bench/, never asserted here.)
set -uo pipefail
binary=$1
data="$2/data/lightfield"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }

"$binary" bench --lightfield "$data/tiny.lf.json" --out "$out" --spp 2,32 --reference-spp 256 --size 48x32 \
  >"$out/stdout" 2>"$out/stderr"
rc=$?
check "bench exits 0 (rc $rc): $(tail -3 "$out/stderr")" '[ $rc -eq 0 ]'
check "bench.csv has a header and 7 rows" '[ "$(wc -l <"$out/bench.csv")" -eq 8 ]'
bad=$(tail -n +2 "$out/bench.csv" | awk -F, '!($3 > 0 && $4 >= 0 && $5 >= 0 && $3 == $3 && $4 == $4) {print}')
check "finite, positive figures: $bad" '[ -z "$bad" ]'
falls=$(awk -F, '$1 == "restricted-cdf" {e[$2] = $6} END {print (e[32] < e[2]) ? "yes" : "no"}' "$out/bench.csv")
check "restricted-cdf error falls from 2 to 32 spp" '[ "$falls" = yes ]'
check "summary and images written" '[ -s "$out/summary.txt" ] && [ -s "$out/reference.png" ] && [ -s "$out/bench_scene.json" ]'
err=$("$binary" bench --lightfield "$data/nothing.lf.json" --out "$out/x" 2>&1 >/dev/null); rc=$?
check "missing light field (rc $rc): $err" '[ $rc -eq 1 ] && grep -q "nothing.lf.json" <<<"$err"'
echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
