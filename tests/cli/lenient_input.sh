#!/usr/bin/env bash
# Real-world leniency with honesty (issue 18, part 5): `candela info` loads photometry files that
# depart from their format the way DIALux and Relux accept, printing one warning per assumption
# (file and line); `--strict` refuses them with one line naming the file, the line and the
# leniency, also where a scene loads the file (probe, grid, render). Defective values are errors,
# never printed as results; every message is one line of valid UTF-8.
set -uo pipefail
binary=$1
lenient="$2/data/photometry/lenient"
data="$2/data"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS
utf8() { python3 -c 'import sys; sys.stdin.buffer.read().decode("utf-8")' <<<"$1"; }
lines() { [ -z "$1" ] && echo 0 || wc -l <<<"$1"; }

# The issue's Done-when file: ten direct ratios, colour temperature and CRI empty.
f="$lenient/empty_fields.ldt"
info=$("$binary" info "$f" 2>&1); rc=$?
check "info loads empty_fields.ldt (exit $rc): $info" '[ $rc -eq 0 ] && grep -q "luminaire flux (exact quadrature of the table): " <<<"$info"'
check "three warnings with file and line: $info" \
  'grep -qxF "warning: $f:30: empty colour temperature of lamp set 1; left unknown" <<<"$info" &&
   grep -qxF "warning: $f:31: empty colour rendering index of lamp set 1; left unknown" <<<"$info" &&
   grep -qF "warning: $f:33-42: the ten direct ratios are empty" <<<"$info" && [ $(grep -c "^warning:" <<<"$info") -eq 3 ]'
expect "$f:30: empty colour temperature of lamp set 1 (refused by --strict)" -- info --strict "$f"
expect "$f:30: empty colour temperature" -- info "$f" --strict
err=$("$binary" info --strict "$f" 2>&1 >/dev/null)
check "--strict's error is one line naming the file once: $err" \
  '[ $(lines "$err") -eq 1 ] && [ $(grep -o "empty_fields.ldt" <<<"$err" | wc -l) -eq 1 ]'

# The other lenient files: each loads with its warning and --strict refuses it.
for case in "lorl_zero.ldt:23: light output ratio LORL 0 %" "repeated_c360.ldt:67: C360 repeats the C0 plane" \
            "utf16le_bom.ldt:1: text in UTF-16LE with a byte-order mark" \
            "latin1_mixed_endings.ies:3: text in Windows-1252 (Latin-1), not UTF-8"; do
  file=${case%%:*}
  info=$("$binary" info "$lenient/$file" 2>&1); rc=$?
  check "info $file warns '$case' (exit $rc): $info" '[ $rc -eq 0 ] && grep -qF "warning: $lenient/$case" <<<"$info"'
  check "info $file is valid UTF-8 and prints no inf or nan: $info" 'utf8 "$info" && ! grep -qiw -e inf -e nan <<<"$info"'
  expect "$lenient/$case" "(refused by --strict)" -- info --strict "$lenient/$file"
done
info=$("$binary" info "$lenient/utf16le_bom.ldt" 2>&1)
check "UTF-16 name shown as UTF-8: $info" 'grep -qF "luminaire: Leuchte Straße" <<<"$info"'
info=$("$binary" info "$lenient/latin1_mixed_endings.ies" 2>&1)
check "Latin-1 file: three warnings: $info" \
  'grep -qF "latin1_mixed_endings.ies:6: mixed line endings (CRLF before this line, LF here)" <<<"$info" &&
   grep -qF "latin1_mixed_endings.ies:11-12: 2 trailing blank lines; ignored" <<<"$info"'

# The issue's two defects: flux 0 declared (was "table / declared inf"), an IES table holding
# 1e308 (was "flux: inf lm").
info=$("$binary" info "$lenient/lorl_zero.ldt" 2>&1)
check "LORL 0: no ratio to a declared flux of 0: $info" \
  'grep -qF "lamp flux 1500 lm, light output ratio 0: no declared luminaire flux to compare" <<<"$info" && ! grep -q "table / declared" <<<"$info"'
expect "huge_candela.ies:8: expected candela values (after the multipliers) of at most 1e+15 cd" "found 1e+308 cd" \
  -- info "$data/cli/huge_candela.ies"
out_huge=$("$binary" info "$data/cli/huge_candela.ies" 2>/dev/null)
check "nothing printed as a result for the 1e308 table: $out_huge" '[ -z "$out_huge" ]'

# --strict where a scene loads the file: probe, grid, render (and polar).
cp "$lenient/empty_fields.ldt" "$out/lamp.ldt"
cat >"$out/scene.json" <<'JSON'
{ "geometry": [],
  "luminaires": [ {"type": "photometric", "name": "Lenient", "file": "lamp.ldt",
                   "position": [0, 3, 0], "aim": [0, -1, 0], "c0": [1, 0, 0], "technique": "point"} ],
  "environment": null,
  "camera": {"position": [0, 1.5, 6], "target": [0, 0, 0], "fov_deg": 45} }
JSON
printf 'x,y,z,nx,ny,nz\n0,0,0,0,1,0\n' >"$out/points.csv"
info=$("$binary" info "$out/scene.json" 2>&1)
check "info on the scene counts the luminaire's warnings: $info" 'grep -qF "3 warning(s) reading lamp.ldt" <<<"$info"'
probe=$("$binary" probe "$out/scene.json" --points "$out/points.csv" 2>/dev/null); rc=$?
check "probe loads the lenient luminaire (exit $rc): $probe" '[ $rc -eq 0 ] && [ $(lines "$probe") -eq 2 ]'
expect "lamp.ldt:30: empty colour temperature of lamp set 1 (refused by --strict)" \
  -- probe "$out/scene.json" --points "$out/points.csv" --strict
expect "lamp.ldt:30:" "refused by --strict" -- grid "$out/scene.json" --plane y=0 --spacing 1 --strict
expect "lamp.ldt:30:" "refused by --strict" -- render "$out/scene.json" --out "$out/a.png" --size 16x16 --spp 1 --strict
expect "lamp.ldt:30:" "refused by --strict" -- polar "$out/lamp.ldt" --out "$out/polar.png" --strict
[ ! -e "$out/a.png" ] || { echo "FAIL: a refused render left $out/a.png"; failures=$((failures + 1)); }

# A file name in Latin-1 gives a valid UTF-8 message.
latin=$(printf '%s/Leuchte_\xe9t\xe9.ldt' "$out")
cp "$lenient/empty_fields.ldt" "$latin"
err=$("$binary" info --strict "$latin" 2>&1 >/dev/null)
check "Latin-1 file name: one line of valid UTF-8: $err" \
  'utf8 "$err" && [ $(lines "$err") -eq 1 ] && grep -qF "Leuchte_été.ldt:30:" <<<"$err"'

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
