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
  --fig11 2,64 >"$out/stdout" 2>"$out/stderr"
rc=$?
check "bench exits 0 (rc $rc): $(tail -3 "$out/stderr")" '[ $rc -eq 0 ]'
# Every technique the registry gives the bench (the progressive ones at 2 and 32 spp, the
# deterministic one frame): no hard-coded list, so a new technique needs no edit here.
uneven=$(tail -n +2 "$out/bench.csv" | awk -F, '{s[$1] = s[$1] " " $2} END {for (t in s) if (s[t] != " 2 32" && s[t] != " 1") print t ":" s[t]}')
check "each technique has its rows: $uneven" '[ -z "$uneven" ]'
techniques=$(tail -n +2 "$out/bench.csv" | cut -d, -f1 | sort -u | tr '\n' ' ')
check "restricted-cdf, its baselines and granier2003 are benched: $techniques" \
  '(for t in restricted-cdf uniform-restricted precomputed-global precomputed-shared granier2003; do grep -qw -- "$t" <<<"$techniques" || exit 1; done)'
check "fig11.csv has restricted-cdf at 2 spp and both global techniques at 64" \
  '[ "$(tail -n +2 "$out/fig11.csv" | cut -d, -f1,2 | tr "\n" " ")" = "restricted-cdf,2 precomputed-shared,64 precomputed-global,64 " ]'
bad=$(tail -n +2 "$out/bench.csv" | awk -F, '!($3 > 0 && $4 >= 0 && $5 >= 0 && $3 == $3 && $4 == $4) {print}')
check "finite, positive figures: $bad" '[ -z "$bad" ]'
falls=$(awk -F, '$1 == "restricted-cdf" {e[$2] = $6} END {print (e[32] < e[2]) ? "yes" : "no"}' "$out/bench.csv")
check "restricted-cdf error falls from 2 to 32 spp" '[ "$falls" = yes ]'
check "summary states its light" 'grep -q "^light: .*interreflected light" "$out/summary.txt"'
check "summary and images written" '[ -s "$out/summary.txt" ] && [ -s "$out/reference.png" ] && [ -s "$out/bench_scene.json" ]'
check "fig11 images moved in with the rest, no staging folder left" \
  '[ -n "$(ls "$out/fig11")" ] && [ -z "$(ls -A "$out" | grep "^\.partial")" ]'
err=$("$binary" bench --lightfield "$data/nothing.lf.json" --out "$out/x" 2>&1 >/dev/null); rc=$?
check "missing light field (rc $rc): $err" '[ $rc -eq 1 ] && grep -q "nothing.lf.json" <<<"$err"'
# A bench that fails after it has written some of its files leaves --out as it was: here its
# reference image would land on one of the light field's own images (an input), found when the
# files move into place, so nothing moves.
mkdir "$out/in"
cp "$data"/tiny* "$out/in/"
mv "$out/in/tiny_1_1.exr" "$out/in/reference.exr"
sed -i 's/tiny_1_1.exr/reference.exr/' "$out/in/tiny.lf.json"
before=$(ls -A "$out/in" | tr '\n' ' ')
sum=$(md5sum <"$out/in/reference.exr")
err=$("$binary" bench --lightfield "$out/in/tiny.lf.json" --out "$out/in" --spp 2 --reference-spp 64 \
  --size 48x32 2>&1 >/dev/null); rc=$?
check "a bench refused at the end (rc $rc) writes nothing and keeps the input: $err" \
  '[ $rc -eq 1 ] && grep -q "reference.exr" <<<"$err" && [ "$(ls -A "$out/in" | tr "\n" " ")" = "$before" ] && [ "$(md5sum <"$out/in/reference.exr")" = "$sum" ]'
echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
