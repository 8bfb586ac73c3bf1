#!/usr/bin/env bash
# candela convert: a TM-25 ray file and a procedural headlight to light fields, with the summary
# it prints; bad input gives exit code 1 and a message naming the file, never a crash.
set -uo pipefail
binary=$1
data="$2/data/nearfield"
led="$data/rayfile_LERTDUW_S2WP_green_100k_20161013_IES_TM25.TM25RAY"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0

check() {  # check DESCRIPTION CONDITION...: counts a pass when the command succeeds
  local what=$1
  shift
  if "$@"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $what"; fi
}

source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS

# The OSRAM LED: 337 lm in the header, at least 98 % of it kept (the flux tests allow 2 %).
"$binary" convert "$led" --out "$out/led.lf.json" --grid 5x5 --res 32 >"$out/led.txt" 2>"$out/led.err"
check "LED conversion exits 0" [ $? -eq 0 ]
check "LED summary names the header flux" grep -qF "flux in file header: 337 lm (luminous)" "$out/led.txt"
check "LED summary: rays agree with the header" grep -qF "header / rays = 1.000000" "$out/led.txt"
kept=$(sed -n 's/^flux kept: \([0-9.]*\) lm.*/\1/p' "$out/led.txt")
check "LED keeps 98..100 % of 337 lm (got '$kept')" awk -v k="${kept:-0}" 'BEGIN { exit !(k >= 330.26 && k <= 337) }'
check "LED summary lists the dropped flux" grep -qE "^flux dropped: .*backward .*outside the image" "$out/led.txt"
check "LED summary gives delta, U, S and time" \
  bash -c "grep -q '^delta: ' '$out/led.txt' && grep -q '^U: 5x5 basis' '$out/led.txt' && grep -q '^S: 32x32 pixels' '$out/led.txt' && grep -q '^time: ' '$out/led.txt'"
check "LED progress on stderr" grep -qF "read 100000 rays" "$out/led.err"
images=$(ls "$out"/led_*.exr 2>/dev/null | wc -l)
check "LED wrote the json and 25 images (got $images)" [ -f "$out/led.lf.json" -a "$images" -eq 25 ]

# The cylinder: rays are relative weights (10 000 x the header's 1 lm), half go backwards.
"$binary" convert "$data/Cyl10k.1.tm25ray" --out "$out/cyl.lf.json" --res 16 >"$out/cyl.txt" 2>/dev/null
check "cylinder conversion exits 0" [ $? -eq 0 ]
check "cylinder rays scaled to the header" grep -qF "scaled by 0.0001 to the header's 1 lm" "$out/cyl.txt"
check "cylinder backward flux reported" grep -qE "backward 0\.49[0-9]* lm" "$out/cyl.txt"

# A procedural headlight at a small ray count: 9x7 images.
"$binary" convert --procedural bike-headlight --rays 50000 --out "$out/bike.lf.json" >"$out/bike.txt" 2>/dev/null
check "bike conversion exits 0" [ $? -eq 0 ]
check "bike summary" grep -qF "flux of the dies: 300 lm" "$out/bike.txt"
images=$(ls "$out"/bike_*.exr 2>/dev/null | wc -l)
check "bike wrote 63 images (got $images)" [ "$images" -eq 63 ]

# Bad input.
head -c 50000 "$led" >"$out/truncated.TM25RAY"
printf 'this is not a ray file at all, just text\n' >"$out/garbage.TM25RAY"
expect "nothing_here.TM25RAY" "cannot open" -- convert "$out/nothing_here.TM25RAY" --out "$out/x.lf.json"
expect "garbage.TM25RAY" "not a TM-25 ray file" -- convert "$out/garbage.TM25RAY" --out "$out/x.lf.json"
expect "truncated.TM25RAY" "file size" -- convert "$out/truncated.TM25RAY" --out "$out/x.lf.json"
expect "ThreeRays_PowerOnly.1.ray" "LightTools" -- convert "$data/ThreeRays_PowerOnly.1.ray" --out "$out/x.lf.json"
expect "--grid" "3..64" -- convert "$led" --out "$out/x.lf.json" --grid 2x2
expect "--res" "integer" -- convert "$led" --out "$out/x.lf.json" --res lots
expect "--delta" "number" -- convert "$led" --out "$out/x.lf.json" --delta -1
expect "x.json" "NAME.lf.json" -- convert "$led" --out "$out/x.json"
expect "no_such_dir" "does not exist" -- convert "$led" --out "$out/no_such_dir/x.lf.json"
expect "tail-light" "bike-headlight" -- convert --procedural tail-light --out "$out/x.lf.json"
# Options of another form are bad usage (exit 2), as are a missing input and a missing --out.
expect_usage "--rays applies to --procedural only" -- convert "$led" --out "$out/x.lf.json" --rays 5000
expect_usage "a procedural preset fixes its own layout" -- convert --procedural bike-headlight --out "$out/x.lf.json" --grid 5x5
expect_usage "not both" -- convert "$led" --procedural bike-headlight --out "$out/x.lf.json"
expect_usage "missing the file to convert" -- convert --out "$out/x.lf.json"
expect_usage "missing --out" -- convert "$led"
expect_usage "unknown option" -- convert "$led" --out "$out/x.lf.json" --frobnicate
# A failed conversion leaves nothing behind.
left=$(ls "$out"/x.lf.json "$out"/x_*.exr 2>/dev/null | wc -l)
check "failed conversions wrote no output (found $left files)" [ "$left" -eq 0 ]

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
