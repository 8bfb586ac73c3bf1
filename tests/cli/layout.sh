#!/usr/bin/env bash
# `candela layout` on the office: the lumen method's guess and every arrangement
# computed, with units; --out writes a scene whose own `surfaces` run meets the target; the
# layout is not written onto its input, and what it needs is asked for.
set -uo pipefail
binary=$1
root="$2/.."
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
source "$2/cli/lib/expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The office: its layout takes half the classroom's time (the classroom's is a C++ test).
scene="$root/resources/scenes/office.json"
lamp="$root/resources/luminaires/photometric/halo-recessed-downlight.ies"
out=$("$binary" layout "$scene" --luminaire "$lamp" --height 2.79 --out "$tmp/laid.json" 2>/dev/null)
check "layout exits 0: $out" '[ $? -eq 0 ]'
check "the lumen method, with its units: $out" 'grep -q "^lumen method: one luminaire 796.54 lm, maintenance factor 1, .* room index k 1.18, utilisation guessed .*: N = [0-9]*$" <<<"$out"'
check "what light the values include: $out" 'grep -qx "light: direct light with shadows, and interreflected light" <<<"$out"'
check "a table of arrangements in lx: $out" 'grep -q "Em \[lx\]" <<<"$out" && [ $(grep -c "  met" <<<"$out") -ge 1 ] && grep -q "not met" <<<"$out"'
check "one chosen: $out" '[ $(grep -c "<- chosen" <<<"$out") -eq 1 ] && grep -q "^layout: [0-9]* luminaires" <<<"$out"'
count=$(sed -n 's/^layout: \([0-9]*\) luminaires.*/\1/p' <<<"$out")
surfaces=$("$binary" surfaces "$tmp/laid.json" 2>/dev/null)
# Its luminaires are one layout entry, its grid the layout's (the room is a rectangle: no point
# of the grid falls outside it).
check "the written scene's layout has the $count luminaires" '[ $(python3 -c "import json,sys; d = json.load(open(sys.argv[1])); print(sum(l[\"grid\"][0] * l[\"grid\"][1] for l in d[\"layouts\"]) + len(d[\"luminaires\"]))" "$tmp/laid.json") -eq "$count" ]'
check "and its own surfaces run passes: $surfaces" 'grep -A4 "^Desk (task area)" <<<"$surfaces" | grep -q "required: Em >= 500 lx, U0 >= 0.60: PASS"'

# Written into the current folder by a bare name, its paths still lead to the same files.
bare=$(cd "$tmp" && "$binary" layout "$scene" --luminaire "$lamp" --height 2.79 --max 12 --out bare.json 2>&1)
check "--out bare.json into the current folder: $bare" '[ -s "$tmp/bare.json" ] && "$binary" info "$tmp/bare.json" >/dev/null 2>&1'

mkdir -p "$tmp/scenes" "$tmp/luminaires/photometric"
cp "$scene" "$tmp/scenes/scene.json" && cp "$lamp" "$tmp/luminaires/photometric/"
expect "scene.json" "input" -- layout "$tmp/scenes/scene.json" --luminaire "$lamp" --height 2.79 --out "$tmp/scenes/scene.json"
check "the input is untouched" 'cmp -s "$scene" "$tmp/scenes/scene.json"'
expect_usage "--height" -- layout "$scene" --luminaire "$lamp"
expect_usage "--luminaire" -- layout "$scene" --height 2.4
expect "no task area \"Board\"" -- layout "$scene" --luminaire "$lamp" --height 2.79 --area Board
expect "at or below task area" -- layout "$scene" --luminaire "$lamp" --height 0.5

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
