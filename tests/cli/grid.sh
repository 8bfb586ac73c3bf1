#!/usr/bin/env bash
# candela grid: the grid and its summary against an independent closed form (Howell's
# configuration factor of a rectangle to a parallel element, by corner superposition, written
# here without Candela's code), the CSV, and bad input giving a clear error and exit code 1.
set -uo pipefail
binary=$1
data="$2/data/measure"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0

source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS

# A 0.2 m square panel of 1000 W/(m2 sr) at (0.3, 3, -0.2) facing down over the floor y = 0.
if "$binary" grid "$data/plane.json" --plane y=0 --extent -2,-2,2,2 --spacing 0.5 \
    --out "$out/grid.csv" >"$out/grid.txt" 2>"$out/err.txt"; then
  python3 - "$out/grid.txt" "$out/grid.csv" <<'PY' || failures=$((failures + 1))
import math, sys
L, CX, H, CZ, HALF = 1000.0, 0.3, 3.0, -0.2, 0.1

def corner(a, b, h):
    """Howell C-11: element parallel to an a x b rectangle, h below one of its corners."""
    x, y = a / h, b / h
    return (x / math.sqrt(1 + x * x) * math.atan(y / math.sqrt(1 + x * x)) +
            y / math.sqrt(1 + y * y) * math.atan(x / math.sqrt(1 + y * y))) / (2 * math.pi)

def exact(px, pz):
    def g(x, z):
        return math.copysign(1, x) * math.copysign(1, z) * corner(abs(x), abs(z), H) if x and z else 0.0
    x0, x1, z0, z1 = CX - HALF - px, CX + HALF - px, CZ - HALF - pz, CZ + HALF - pz
    return math.pi * L * (g(x1, z1) - g(x0, z1) - g(x1, z0) + g(x0, z0))

text = open(sys.argv[1]).read().splitlines()
coords = [-1.75 + 0.5 * i for i in range(8)]   # 4 m at 0.5 m: 8 points at cell centres
fail = []
header = [l for l in text if l.strip().startswith("z\\x")]
cols = [float(v) for v in header[0].split()[1:]] if header else []
if cols != coords: fail.append("columns %s, want %s" % (cols, coords))
rows = [l.split() for l in text if l.split() and l.split()[0].replace('.', '').replace('-', '').isdigit()]
values = []
for r in rows:
    z = float(r[0])
    for x, v in zip(coords, r[1:]):
        want = exact(x, z)
        values.append(want)
        # Printed with 4 significant digits: rounding is below 5e-4 relative.
        if abs(float(v) - want) > 6e-4 * want: fail.append("E(%g, %g) = %s, want %.6g" % (x, z, v, want))
if len(values) != 64: fail.append("%d grid values, want 64" % len(values))
summary = dict(l.split(":", 1) for l in text if ":" in l and not l.startswith("plane"))
def num(key): return float(summary[key].split()[0])
emin, emax = min(values), max(values)
eavg = sum(values) / len(values)
# Emin, Eavg, Emax printed with 6 significant digits (rounding < 5e-6 relative); the CPU closed
# form is double precision: 1e-5 relative.
for key, want in (("Emin", emin), ("Eavg", eavg), ("Emax", emax)):
    got = num(key)
    print("%s: candela %.6g W/m2, closed form %.6g W/m2, rel. error %.1e (tolerance 1e-5)" % (key, got, want, abs(got - want) / want))
    if abs(got - want) > 1e-5 * want: fail.append("%s %g, want %g" % (key, got, want))
    # The panel is radiometric (W/(m2 sr)): the whole scene reports W/m2, never lx.
    if "W/m2" not in summary[key] or "lx" in summary[key]: fail.append("%s without its unit W/m2" % key)
# Ratios printed with 4 decimals: 6e-5 absolute.
for key, want in (("U0 (Emin/Eavg)", emin / eavg), ("Emin/Emax", emin / emax)):
    got = num(key)
    print("%s: candela %.4f, closed form %.6f" % (key, got, want))
    if abs(got - want) > 6e-5: fail.append("%s %g, want %g" % (key, got, want))
if num("points") != 64: fail.append("points %s" % summary["points"])
# Far field sanity (independent of the corner formula): 0.2 m at 3 m is nearly a point of
# intensity L A cos(theta), E = L A cos^4(theta) / H^2; within 1 % at the brightest point.
best = max((exact(x, z), x, z) for x in coords for z in coords)
r2 = H * H + (best[1] - CX) ** 2 + (best[2] - CZ) ** 2
point = L * 0.04 * (H * H / r2) ** 2 / (H * H)
if abs(best[0] - point) > 0.01 * point: fail.append("point-source check %g vs %g" % (best[0], point))
# CSV: header and one row per point, 10 significant digits.
csv = open(sys.argv[2]).read().split()
# The lone floor reflects, so its interreflected columns are there, and 0: a flat floor does not
# light itself.
if csv[0] != ("x,y,z,E_W_m2,E_stderr_W_m2,maintenance_factor,E_initial_W_m2,E_direct_W_m2,"
              "E_direct_stderr_W_m2,E_indirect_W_m2,E_indirect_stderr_W_m2"):
    fail.append("CSV header %s" % csv[0])
if not any(l.startswith("irradiance E [W/m2]") for l in text): fail.append("no 'irradiance E [W/m2]' header")
for line in csv[1:]:
    x, y, z, e, se, mf, initial, direct, dse, indirect, ise = map(float, line.split(","))
    # No maintenance factor in this scene: 1, and the initial value is the value.
    if y != 0.0 or abs(e - exact(x, z)) > 1e-8 * exact(x, z) or se != 0.0 or mf != 1.0 \
            or abs(initial - e) > 1e-9 * e or direct != e or indirect != 0.0 or ise != 0.0:
        fail.append("CSV row %s, want E %.10g" % (line, exact(x, z)))
if len(csv) != 65: fail.append("CSV has %d rows, want 65" % len(csv))
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
PY
  [ $? -eq 0 ] && passed=$((passed + 1))
else
  echo "FAIL: candela grid exited $?: $(cat "$out/err.txt")"
  failures=$((failures + 1))
fi

# The back side of the floor (facing down, away from the panel) receives nothing: U0 is 0.
if "$binary" grid "$data/plane.json" --plane -y=0 --extent -1,-1,1,1 --spacing 1 >"$out/down.txt" 2>&1 &&
    grep -q "^Emax: 0 W/m2" "$out/down.txt" && grep -q "^U0 (Emin/Eavg): 0.0000" "$out/down.txt"; then
  passed=$((passed + 1))
else
  echo "FAIL: grid on the floor's back side: $(cat "$out/down.txt")"
  failures=$((failures + 1))
fi

# The photometric room (two real luminaires, IES and LDT): with --visibility the points under
# the table (1.6 x 0.9 m top at 0.75 m, centred on (0, -0.5)) lose the pendant's light, the
# ones beyond it keep theirs; without it nothing changes (issue 17: the CPU estimators ignored
# occluders for photometric luminaires).
# Shadows are the default (with the interreflected light, the same in both runs); --no-shadows
# leaves them out.
room="$2/../resources/scenes/photometric.json"
if "$binary" grid "$room" --plane y=0.0 --extent -0.6,-0.8,0.6,-0.2 --spacing 0.2 --no-shadows >"$out/open.txt" 2>&1 &&
    "$binary" grid "$room" --plane y=0.0 --extent -0.6,-0.8,0.6,-0.2 --spacing 0.2 >"$out/vis.txt" 2>&1 &&
    "$binary" grid "$room" --plane y=0.0 --extent -0.6,1.2,0.6,1.6 --spacing 0.2 --no-shadows >"$out/open2.txt" 2>&1 &&
    "$binary" grid "$room" --plane y=0.0 --extent -0.6,1.2,0.6,1.6 --spacing 0.2 >"$out/vis2.txt" 2>&1; then
  python3 - "$out/open.txt" "$out/vis.txt" "$out/open2.txt" "$out/vis2.txt" <<'PY' || failures=$((failures + 1))
import sys
def summary(path):
    d = dict(l.split(":", 1) for l in open(path).read().splitlines() if l.startswith("E"))
    return {k: float(v.split()[0]) for k, v in d.items() if k in ("Emin", "Eavg", "Emax")}, open(path).read()
(o, to), (v, tv), (o2, _), (v2, _) = (summary(p) for p in sys.argv[1:5])
fail = []
# Under the table only the wall washer's light through the open sides is left: far below the
# unshadowed minimum (159 lx).
if not v["Eavg"] < 0.5 * o["Emin"]: fail.append("under the table: Eavg %g with visibility vs Emin %g without" % (v["Eavg"], o["Emin"]))
# Beyond the table nothing blocks either luminaire: the same direct light (6-digit output,
# 1e-5). (The interreflected light differs a little: the table's shadow darkens the floor
# that reflects it, 0.05 % here.)
def direct(path):
    line = [l for l in open(path).read().splitlines() if l.startswith("direct:")][0]
    parts = line.replace(",", "").split()
    return {k: float(parts[parts.index(k) + 1]) for k in ("Emin", "Em", "Emax")}
d2, do2 = direct(sys.argv[4]), direct(sys.argv[3])
for k in ("Emin", "Em", "Emax"):
    if abs(d2[k] - do2[k]) > 1e-5 * do2[k]: fail.append("beyond the table direct %s %g vs %g" % (k, d2[k], do2[k]))
if "illuminance E [lx]" not in tv: fail.append("the photometric room is not reported in lx")
if "light: direct light with shadows, and interreflected light" not in tv: fail.append("the default does not say it has shadows and interreflected light")
if "light: direct light without shadows (switched off), and interreflected light" not in to: fail.append("--no-shadows is not stated")
print("photometric room under the table: Eavg %.4g lx with --visibility, %.4g lx without" % (v["Eavg"], o["Eavg"]))
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
PY
  [ $? -eq 0 ] && passed=$((passed + 1))
else
  echo "FAIL: grid on the photometric room: $(cat "$out/vis.txt")"
  failures=$((failures + 1))
fi

expect "nothing_here.json" "cannot open" -- grid "$data/nothing_here.json" --plane y=0
expect "--plane" "x|y|z=VALUE" -- grid "$data/plane.json" --plane w=1
expect "--plane" "x|y|z=VALUE" -- grid "$data/plane.json" --plane y
expect "--plane" "finite number" -- grid "$data/plane.json" --plane y=abc
expect "--plane" "finite number" -- grid "$data/plane.json" --plane y=nan
expect "--spacing" "positive" -- grid "$data/plane.json" --plane y=0 --spacing 0
expect "--spacing" "positive" -- grid "$data/plane.json" --plane y=0 --spacing -0.5
expect "--spacing" "finite number" -- grid "$data/plane.json" --plane y=0 --spacing NaN
expect "the grid at a spacing of 1e-05 m over" "more than the 1000000 allowed" -- grid "$data/plane.json" --plane y=0 --spacing 1e-5
expect "--extent" "four numbers" -- grid "$data/plane.json" --plane y=0 --extent 0,0,1
expect "--extent" "an area" -- grid "$data/plane.json" --plane y=0 --extent 0,0,0,1
expect "--extent" "finite number" -- grid "$data/plane.json" --plane y=0 --extent 0,0,inf,1
expect_usage "usage" "--plane" -- grid "$data/plane.json"
expect_usage "unknown option" -- grid "$data/plane.json" --plane y=0 --frobnicate
expect "--technique" "magic" -- grid "$data/plane.json" --plane y=0 --technique magic

# render --false-colour: the illuminance picture with the legend it used; bad legends refused.
if "$binary" render "$data/plane.json" --out "$out/fc.png" --size 64x48 --false-colour \
    --legend 0,5 --isolux 1,2,3 >"$out/fc.txt" 2>&1 && [ -s "$out/fc.png" ] &&
    grep -q "false colour: 0 .. 5 W/m2 (linear), isolux at 1, 2, 3 W/m2" "$out/fc.txt"; then
  passed=$((passed + 1))
else
  echo "FAIL: render --false-colour: $(cat "$out/fc.txt")"
  failures=$((failures + 1))
fi
# The PNG carries its legend in a strip on the right (72 px at this height): 136 x 48 pixels, and
# the bar's middle (column 76, row 24: t = 0.488 of the scale) holds the scale's colour there,
# mix(stop 3, stop 4, 0.90) = (19, 154, 152) in 8 bits (shaders/shared/FalseColour.h), within 12
# for the bar's anti-aliased drawing.
size=$(identify -format "%wx%h" "$out/fc.png" 2>/dev/null)
mid=$(convert "$out/fc.png" -crop 1x1+76+24 -depth 8 txt:- 2>/dev/null | sed -n 's/.*: (\([0-9]*\),\([0-9]*\),\([0-9]*\)).*/\1 \2 \3/p')
if [ "$size" = "136x48" ] && awk -v c="$mid" 'BEGIN { split(c, v, " "); w[1] = 19; w[2] = 154; w[3] = 152;
     for (i = 1; i <= 3; ++i) { d = v[i] - w[i]; if (d < 0) d = -d; if (d > 12 || v[i] == "") exit 1 } }'; then
  passed=$((passed + 1))
else
  echo "FAIL: render --false-colour's PNG has no legend strip: size $size, bar colour ($mid)"
  failures=$((failures + 1))
fi
expect "--legend" "MAX > MIN" -- render "$data/plane.json" --out "$out/b.png" --false-colour --legend 5,1
expect "--legend" "finite numbers" -- render "$data/plane.json" --out "$out/b.png" --false-colour --legend 0,nan
expect "--legend" "MIN > 0" -- render "$data/plane.json" --out "$out/b.png" --false-colour --legend 0,10 --log
expect "--isolux" "finite numbers" -- render "$data/plane.json" --out "$out/b.png" --false-colour --isolux 1,,2
[ ! -e "$out/b.png" ] || { echo "FAIL: a refused render left $out/b.png"; failures=$((failures + 1)); }

# The old name of --out still works for one release, with a line saying what replaces it, and
# writes the same file.
if err=$("$binary" grid "$data/plane.json" --plane y=0 --extent -2,-2,2,2 --spacing 0.5 \
    --csv "$out/old.csv" 2>&1 >/dev/null) && grep -qF -- "--csv is now called --out" <<<"$err" &&
    cmp -s "$out/old.csv" "$out/grid.csv"; then
  passed=$((passed + 1))
else
  echo "FAIL: grid --csv (the old name of --out): $err"
  failures=$((failures + 1))
fi

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
