#!/usr/bin/env bash
# IES TM-33 through the command line: `candela convert` writes an IES and a EULUMDAT file as
# TM-33-18 XML, `info` gives the twin the same flux as its original, `probe` the same illuminance
# at the same points (issue 21 part 3: within 0.1 %; the table travels exactly, so they agree to
# the printed digits), the hand-written TM-33-23 file loads, and the conversion never writes onto
# an input or leaves a file behind on a refusal.
set -uo pipefail
binary=$1
data="$2/data"
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
source "$2/cli/lib/expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

flux() { sed -n 's/^luminaire flux (exact quadrature of the table): \([0-9.e+]*\) lm$/\1/p' <<<"$1"; }
for source in "$data/photometry/ies/lidrs/iesna2002_example_typec.ies" "$data/photometry/ldt/lidrs/example.ldt"; do
  name=$(basename "$source")
  cp "$source" "$tmp/$name"
  out=$("$binary" convert "$tmp/$name" --out "$tmp/$name.xml" 2>&1)
  check "convert $name exits 0: $out" '[ $? -eq 0 ] && grep -q "(IES TM-33-18)" <<<"$out"'
  check "the document is well-formed XML to Python's parser" \
    'python3 -c "import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); sys.exit(r.tag != \"IESTM33\")" "$tmp/$name.xml"'
  a=$("$binary" info "$tmp/$name" 2>&1)
  b=$("$binary" info "$tmp/$name.xml" 2>&1)
  check "$name's twin has the same flux: $(flux "$a") and $(flux "$b") lm" '[ -n "$(flux "$a")" ] && [ "$(flux "$a")" = "$(flux "$b")" ]'
  check "the twin says it is TM-33: $b" 'grep -q "format: IES TM-33-18" <<<"$b"'
  for file in "$name" "$name.xml"; do
    cat > "$tmp/scene-$file.json" <<JSON
{"luminaires": [{"type": "photometric", "file": "$file", "position": [0, 3, 0], "aim": [0, -1, 0], "c0": [1, 0, 0], "technique": "scattered"}]}
JSON
  done
  printf 'x,y,z,nx,ny,nz\n0,0,0,0,1,0\n1.5,0,-0.5,0,1,0\n-2,0.8,1,0,1,0\n2.5,1.5,0,-1,0,0\n' >"$tmp/points.csv"
  pa=$("$binary" probe "$tmp/scene-$name.json" --points "$tmp/points.csv" 2>/dev/null | tail -n +2 | cut -d, -f7)
  pb=$("$binary" probe "$tmp/scene-$name.xml.json" --points "$tmp/points.csv" 2>/dev/null | tail -n +2 | cut -d, -f7)
  bad=$(paste -d, <(echo "$pa") <(echo "$pb") | awk -F, '{ d = $1 - $2; if (d < 0) d = -d; if (!($1 > 0) || d > 1e-3 * $1) print NR ": " $1 " vs " $2 }')
  check "$name and its twin light the points alike: $bad" '[ -z "$bad" ] && [ $(wc -l <<<"$pa") -eq 4 ]'
done

hand=$("$binary" info "$data/tm33/wallwasher_tm33-23.xml" 2>&1)
check "the hand-written TM-33-23 file loads: $hand" 'grep -q "format: IES TM-33-23, type C goniometry, symmetry: mirror about the C0-C180 plane" <<<"$hand" && grep -q "max intensity: 450 cd" <<<"$hand"'
cosine=$("$binary" info "$data/tm33/cosine_downlight_tm33-18.xml" 2>&1)
check "the stated flux is compared with the table's: $cosine" 'grep -q "luminous flux the file states: 3141.6 lm (table / stated 0.99" <<<"$cosine"'

# Refusals: the output must be TM-33, never an input (here a link to it), and nothing is left.
expect "the output of a photometry conversion is IES TM-33, named NAME.xml or NAME.iesxml" -- convert "$tmp/example.ldt" --out "$tmp/out.ies"
ln -s "$tmp/example.ldt" "$tmp/link.xml"
before=$(sha256sum "$tmp/example.ldt")
expect "link.xml" "input" -- convert "$tmp/example.ldt" --out "$tmp/link.xml"
check "the input is untouched" '[ "$(sha256sum "$tmp/example.ldt")" = "$before" ]'
expect_usage "apply to ray files and procedural luminaires, not to photometry" -- convert "$tmp/example.ldt" --out "$tmp/x.xml" --grid 8x8
check "no file written on a refusal" '[ ! -e "$tmp/x.xml" ] && [ -z "$(find "$tmp" -name ".*tmp*")" ]'
printf '<IESTM33><Version>1.0</Version></IESTM33>\n' >"$tmp/empty.xml"
expect "empty.xml:1: expected an <Emitter> with <LuminousData>" -- info "$tmp/empty.xml"

echo "tm33: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
