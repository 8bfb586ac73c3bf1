#!/usr/bin/env bash
# One unit system (issue 17, part 2): a scene mixing a radiometric panel (2 W/(m2 sr)) with a
# photometric lamp reports lux with the panel converted at 683 lm/W and says so beside every
# result (grid, probe, false colour, info); the same scene with the panel given as 1366 cd/m2
# (2 x 683) gives the same numbers without the note. A radiometric scene reports W/m2.
set -uo pipefail
binary=$1
data="$2/data/units"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0
note="radiometric sources converted at 683 lm/W"

check() {  # check NAME COMMAND...: runs it, counts a failure with NAME when it fails
  local name=$1
  shift
  if "$@"; then passed=$((passed + 1)); else echo "FAIL: $name"; failures=$((failures + 1)); fi
}

"$binary" grid "$data/mixed.json" --plane y=0 --extent -1.5,-1,1.5,1 --spacing 0.5 --out "$out/mixed.csv" >"$out/mixed.txt" 2>&1
"$binary" grid "$data/photometric.json" --plane y=0 --extent -1.5,-1,1.5,1 --spacing 0.5 --out "$out/photometric.csv" >"$out/photometric.txt" 2>&1
check "mixed grid names lx and the conversion" grep -qF "illuminance E [lx], $note" "$out/mixed.txt"
check "mixed grid summary in lx" grep -q "^Eavg: [0-9.]* lx$" "$out/mixed.txt"
check "photometric grid has no conversion note" bash -c "! grep -q '683' '$out/photometric.txt'"
check "CSV columns name lx" grep -q "^x,y,z,E_lx,E_stderr_lx,maintenance_factor,E_initial_lx,E_direct_lx,E_direct_stderr_lx,E_indirect_lx,E_indirect_stderr_lx$" "$out/mixed.csv"
# The panel's 2 W/(m2 sr) at 683 lm/W is the photometric scene's 1366 cd/m2: the same grid.
check "mixed = photometric at 683 lm/W" python3 - "$out/mixed.csv" "$out/photometric.csv" <<'PY'
import sys
a = [l.split(",") for l in open(sys.argv[1]).read().split()[1:]]
b = [l.split(",") for l in open(sys.argv[2]).read().split()[1:]]
bad = [(x, y) for x, y in zip(a, b) if abs(float(x[3]) - float(y[3])) > 1e-9 * float(y[3])]
print("%d points, largest E %.6g lx; %d differ" % (len(a), max(float(x[3]) for x in a), len(bad)))
sys.exit(1 if bad or len(a) != 24 or len(a) != len(b) else 0)
PY

printf 'x,y,z,nx,ny,nz\n0,0,0,0,1,0\n' >"$out/p.csv"
"$binary" probe "$data/mixed.json" --points "$out/p.csv" >"$out/probe.csv" 2>"$out/probe.err"
"$binary" probe "$data/photometric.json" --points "$out/p.csv" >"$out/probe2.csv" 2>"$out/probe2.err"
check "probe names lx and the conversion on stderr" grep -qF "in lx ($note)" "$out/probe.err"
check "probe of the photometric scene: lx without a note" grep -q "in lx$" "$out/probe2.err"
check "probe columns unchanged" grep -q "^x,y,z,nx,ny,nz,E,E_r,E_g,E_b,E_stderr$" "$out/probe.csv"
check "probe E equal" python3 -c "
import sys
a = float(open('$out/probe.csv').read().split()[1].split(',')[6]); b = float(open('$out/probe2.csv').read().split()[1].split(',')[6])
sys.exit(0 if a > 0 and abs(a - b) <= 1e-9 * b else 1)"

"$binary" render "$data/mixed.json" --out "$out/fc.png" --size 64x48 --false-colour >"$out/fc.txt" 2>&1
check "false colour names lx and the conversion" grep -qF "lx (linear)" "$out/fc.txt"
check "false colour note" grep -qF "($note)" "$out/fc.txt"
"$binary" render "$data/mixed.json" --out "$out/linear.exr" --size 32x24 >"$out/exr.txt" 2>&1
check "EXR values named cd/m2" grep -qF "linear values in cd/m2, $note" "$out/exr.txt"
"$binary" info "$data/mixed.json" >"$out/info.txt" 2>&1
check "info states the units" grep -qF "units: photometric (lm, cd, cd/m2, lx); $note" "$out/info.txt"
"$binary" grid "$2/data/measure/plane.json" --plane y=0 --extent -1,-1,1,1 --spacing 1 >"$out/w.txt" 2>&1
check "a radiometric scene reports W/m2" grep -q "^Emax: [0-9.]* W/m2$" "$out/w.txt"

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
