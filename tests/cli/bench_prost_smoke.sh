#!/usr/bin/env bash
# `candela bench --prost` runs end to end on two small files: every technique, height and rotation
# gets a CSV row with finite figures; on the Lambertian file scattered sampling is exact up to the
# reference's noise (it must beat the point law there); sheets, plot data and summary are written;
# a broken file is skipped with its error named, not fatal. (A smoke test; the figures themselves
# are benchmarks, committed under docs/bench/prost, never asserted beyond the exactness above.)
set -uo pipefail
binary=$1
data="$2/data"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }

"$binary" bench --prost "$data/photometric/lambert.ies" "$data/photometric/spot.ies" \
  "$data/photometry/ies/ies_rescale/Invalid Profile - 01.ies" --out "$out" --size 16 --reference-spp 256 \
  >"$out/stdout" 2>"$out/stderr"
rc=$?
check "bench exits 0 (rc $rc): $(tail -3 "$out/stderr")" '[ $rc -eq 0 ]'
# 2 files x 4 heights x 5 rotations x 8 techniques, plus the header.
check "results.csv has 321 lines" '[ "$(wc -l <"$out/results.csv")" -eq 321 ]'
bad=$(tail -n +2 "$out/results.csv" | awk -F, '!($5 >= 0 && $5 == $5 && $10 > 0 && $6 >= 0 && $7 <= 0) {print}')
check "finite figures, bounds on the right sides: $bad" '[ -z "$bad" ]'
better=$(awk -F, '$1 ~ /lambert/ && $3 == 1.1 {n[$2] = $4} END {print (n["scattered"] < n["point"]) ? "yes" : "no"}' "$out/nmse_by_height.csv")
check "Lambertian: scattered beats the point law at 1.1 m" '[ "$better" = yes ]'
check "sheets written" '[ -s "$out/lambert_h1_images.png" ] && [ -s "$out/spot_h51_errors.png" ]'
check "summary states its light" 'grep -q "^light: .*interreflected light" "$out/summary.txt"'
check "broken file skipped and named" 'grep -q "skipped: .*Invalid Profile - 01.ies:1" "$out/summary.txt"'
err=$("$binary" bench --prost --out "$out/x" 2>&1 >/dev/null); rc=$?
check "no files is a usage error (rc $rc): $err" \
  '[ $rc -eq 2 ] && grep -q "missing FILE" <<<"$err" && grep -q "^usage:" <<<"$err" && grep -q "candela bench --prost FILE" <<<"$err"'
echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
