#!/usr/bin/env bash
# candela polar: the C0-C180 / C90-C270 table of a small IES file written for this test (its
# values at the file's own angles come back exactly), a PNG from gnuplot for it and for the
# photometry test files when present, and bad input giving a clear error and exit code 1.
set -uo pipefail
binary=$1
data="$2/data/measure"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0

source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS

is_png() { [ -s "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }

# quadrant.ies: quadrant symmetric, C0 = 1000 800 400 0 cd and C90 = 1000 500 300 0 cd at
# gamma 0 30 60 90; the mirror images C180 = C0 and C270 = C90.
if "$binary" polar "$data/quadrant.ies" --out "$out/quadrant.png" >"$out/table.txt" 2>&1; then
  want="0 1000 1000 1000 1000|30 800 800 500 500|60 400 400 300 300|90 0 0 0 0"
  got=$(awk '$1 ~ /^[0-9.]+$/ {printf "%s%s %s %s %s %s", sep, $1, $2, $3, $4, $5; sep="|"}' "$out/table.txt")
  if [ "$got" = "$want" ] && is_png "$out/quadrant.png" && grep -q "\[cd\]" "$out/table.txt"; then
    passed=$((passed + 1))
  else
    echo "FAIL: polar quadrant.ies: table [$got], want [$want]; $(cat "$out/table.txt")"
    failures=$((failures + 1))
  fi
else
  echo "FAIL: candela polar quadrant.ies: $(cat "$out/table.txt")"
  failures=$((failures + 1))
fi

# Every photometry test file (IES and EULUMDAT) the repository has plots to a PNG.
n=0
while IFS= read -r -d '' f; do
  n=$((n + 1))
  if "$binary" polar "$f" --out "$out/p$n.png" >"$out/p$n.txt" 2>&1 && is_png "$out/p$n.png"; then
    passed=$((passed + 1))
  elif grep -q "cannot\|expected" "$out/p$n.txt" && ! is_png "$out/p$n.png"; then
    passed=$((passed + 1))  # a file the loader rejects (a defect test file): a clear error
  else
    echo "FAIL: candela polar $f: $(cat "$out/p$n.txt")"
    failures=$((failures + 1))
  fi
  [ $n -ge 6 ] && break
done < <(find "$2/data/photometry" -type f \( -iname '*.ies' -o -iname '*.ldt' \) -print0 2>/dev/null | sort -z)

expect "nothing_here.ies" "cannot open" -- polar "$data/nothing_here.ies" --out "$out/a.png"
expect "a.jpg" "unsupported" -- polar "$data/quadrant.ies" --out "$out/a.jpg"
expect "--step" "integer" -- polar "$data/quadrant.ies" --step 0
expect_usage "usage" -- polar
expect_usage "unknown option" -- polar "$data/quadrant.ies" --frobnicate
[ ! -e "$out/a.jpg" ] || { echo "FAIL: a refused polar left $out/a.jpg"; failures=$((failures + 1)); }

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
