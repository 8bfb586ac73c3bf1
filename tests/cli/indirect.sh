#!/usr/bin/env bash
# Interreflected light from the command line (issue 17, parts 3-5) on the office scene (six
# downlights, reflectances 0.7 / 0.5 / 0.2, a desk) and bad rooms:
# - grid --indirect reports Emin / Em / Emax / U0 of the direct, interreflected and total light,
#   the total is their sum at every point (CSV), and the interreflected part is what the energy
#   balance of the room allows (between 5 and 60 lx: 4780 lm, 104 m2, mean reflectance ~0.5);
# - probe --indirect keeps its columns, adds light with a standard error (the ceiling, which the
#   downlights barely reach, gets nearly all of it);
# - render --indirect on lights the ceiling that --indirect off leaves black;
# - validate --closed passes the closed office and refuses, naming the file and what is wrong,
#   an open room, surfaces facing out, no surfaces, a reflectance above 1 and a NaN albedo;
# - validate --case runs one case of the suite; --list lists them; an unknown case is an error.
set -uo pipefail
binary=$1
data="$2/data/rooms"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0
source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS

check() {  # check NAME COMMAND...
  local name=$1
  shift
  if "$@"; then passed=$((passed + 1)); else echo "FAIL: $name"; failures=$((failures + 1)); fi
}

"$binary" grid "$data/office.json" --plane y=0.8 --spacing 0.5 --indirect --spp 256 --out "$out/grid.csv" \
    >"$out/grid.txt" 2>"$out/grid.err"
check "grid --indirect exits 0" [ $? -eq 0 ]
check "grid --indirect says how the interreflected light was found" grep -q "^interreflected light: the patches' solution, refined near surfaces; a final gather of 256 rays at [0-9]* of [0-9]* points" "$out/grid.txt"
check "grid --indirect reports the three parts" python3 - "$out/grid.txt" "$out/grid.csv" <<'PY'
import sys
text = open(sys.argv[1]).read().splitlines()
parts = {}
for line in text:
    for name in ("direct:", "interreflected:", "total:"):
        if line.startswith(name):
            fields = dict(f.strip().split(" ", 1) for f in line[len(name):].split(","))
            parts[name[:-1]] = {k: float(v.split()[0]) for k, v in fields.items()}
            if "lx" not in fields["Em"]: sys.exit("%s without its unit" % name)
if set(parts) != {"direct", "interreflected", "total"}: sys.exit("parts %s" % sorted(parts))
d, i, t = parts["direct"], parts["interreflected"], parts["total"]
print("work plane: direct Em %g lx (U0 %g), interreflected %g lx (U0 %g), total %g lx (U0 %g)" %
      (d["Em"], d["U0"], i["Em"], i["U0"], t["Em"], t["U0"]))
# Means add up (printed with 6 digits: 1e-5 relative).
if abs(d["Em"] + i["Em"] - t["Em"]) > 1e-5 * t["Em"]: sys.exit("Em do not add up")
if not 5.0 < i["Em"] < 60.0: sys.exit("interreflected Em %g lx outside the energy balance's range" % i["Em"])
# Interreflected light is far more uniform than the downlights' pools.
if not i["U0"] > d["U0"]: sys.exit("interreflected U0 not above direct U0")
rows = [l.split(",") for l in open(sys.argv[2]).read().split()]
want = "x,y,z,E_lx,E_stderr_lx,maintenance_factor,E_initial_lx,E_direct_lx,E_direct_stderr_lx,E_indirect_lx,E_indirect_stderr_lx".split(",")
if rows[0] != want: sys.exit("CSV header %s" % rows[0])
for r in rows[1:]:
    e, direct, indirect = float(r[3]), float(r[7]), float(r[9])
    # The office has no maintenance factor: the factor column is 1 and E_initial is E.
    # The interreflected light's standard error: the gather's where it gathered, 0 where the
    # patches' deterministic solution served (GridSpec::Indirect::Adaptive).
    if abs(direct + indirect - e) > 1e-8 * e or indirect <= 0.0 or float(r[10]) < 0.0 \
            or float(r[5]) != 1.0 or abs(float(r[6]) - e) > 1e-9 * e:
        sys.exit("CSV row %s" % r)
PY

# The ceiling's centre, facing down, and the desk top, facing up.
printf 'x,y,z,nx,ny,nz\n0.5,2.79,0.5,0,-1,0\n0.4,0.76,-0.3,0,1,0\n' >"$out/points.csv"
"$binary" probe "$data/office.json" --points "$out/points.csv" --spp 2048 >"$out/direct.csv" 2>/dev/null
"$binary" probe "$data/office.json" --points "$out/points.csv" --spp 2048 --indirect >"$out/total.csv" 2>"$out/probe.err"
check "probe --indirect names what E holds" grep -q "direct plus interreflected light" "$out/probe.err"
check "probe --indirect adds light with a standard error" python3 - "$out/direct.csv" "$out/total.csv" <<'PY'
import sys
a = [l.split(",") for l in open(sys.argv[1]).read().split()]
b = [l.split(",") for l in open(sys.argv[2]).read().split()]
if a[0] != b[0] or b[0] != "x,y,z,nx,ny,nz,E,E_r,E_g,E_b,E_stderr".split(","): sys.exit("columns changed")
ceiling_direct, ceiling = float(a[1][6]), float(b[1][6])
desk_direct, desk = float(a[2][6]), float(b[2][6])
print("ceiling: %.4g lx direct, %.4g lx with interreflection (+- %s); desk: %.4g -> %.4g lx" %
      (ceiling_direct, ceiling, b[1][10], desk_direct, desk))
if not (ceiling > ceiling_direct + 5.0 and float(b[1][10]) > 0.0): sys.exit("no interreflected light on the ceiling")
if not desk > desk_direct: sys.exit("no interreflected light on the desk")
PY

"$binary" render "$data/office.json" --out "$out/on.exr" --size 96x54 --spp 4 >/dev/null 2>&1
"$binary" render "$data/office.json" --out "$out/off.exr" --size 96x54 --spp 4 --indirect off >/dev/null 2>&1
# The top rows of the scene's view show the ceiling (the camera looks across the room).
on=$(oiiotool "$out/on.exr" --cut 96x6+0+0 --printstats 2>/dev/null | awk '/Stats Min/ {print $3}')
off=$(oiiotool "$out/off.exr" --cut 96x6+0+0 --printstats 2>/dev/null | awk '/Stats Min/ {print $3}')
echo "render: darkest ceiling pixel with interreflection ${on:-?}, without ${off:-?}"
check "render lights the ceiling with --indirect on only" python3 -c "import sys; sys.exit(0 if float('${on:-0}') > 0.1 and float('${off:-1}') == 0.0 else 1)"

"$binary" validate --closed "$data/office.json" >"$out/closed.txt" 2>&1
check "validate --closed passes the office" grep -q "^closed-room .* pass" "$out/closed.txt"
expect "open.json" "not a closed room" "escape" -- validate --closed "$data/open.json"
expect "outward.json" "back of a surface" "inside" -- validate --closed "$data/outward.json"
expect "empty.json" "geometry: no surfaces" -- validate --closed "$data/empty.json"
expect "empty.json" "no surfaces" -- grid "$data/empty.json" --plane y=0.8 --extent -1,-1,1,1 --indirect
expect "bright.json" "geometry[1].albedo[1]" "[0, 1]" -- grid "$data/bright.json" --plane y=0.8 --indirect
expect "nan_albedo.json" "geometry[0].albedo[0]" "finite number" -- validate --closed "$data/nan_albedo.json"
# --indirect is a switch (--no-indirect its opposite); "on" and "off" its old spelling.
expect_usage "unexpected argument maybe" -- render "$data/office.json" --out "$out/x.png" --indirect maybe
expect "--indirect" "on or off" -- render "$data/office.json" --out "$out/x.png" --indirect=maybe
expect_usage "--indirect" "--no-indirect" -- render "$data/office.json" --out "$out/x.png" --indirect --no-indirect
expect_usage "--indirect" "--no-indirect" -- probe "$data/office.json" --points "$out/points.csv" --indirect --no-indirect
expect "--device gpu" "--indirect" -- probe "$data/office.json" --points "$out/points.csv" --indirect --device gpu
"$binary" grid "$data/outward.json" --plane y=0.8 --spacing 1 --indirect >/dev/null 2>"$out/outward.err"
check "a room facing out is warned about" grep -q "lights the back of surfaces" "$out/outward.err"

# Right by default: with no flag, grid computes what a light meter reads (direct light with
# shadows and the interreflected light), the same numbers as the explicit flags, and says so;
# --light direct and --no-shadows are explicit choices the output states.
"$binary" grid "$data/office.json" --plane y=0.8 --spacing 1 --spp 64 --out "$out/default.csv" >"$out/default.txt" 2>/dev/null
"$binary" grid "$data/office.json" --plane y=0.8 --spacing 1 --spp 64 --indirect --visibility --out "$out/explicit.csv" >/dev/null 2>&1
"$binary" grid "$data/office.json" --plane y=0.8 --spacing 1 --spp 64 --light direct --no-shadows >"$out/direct.txt" 2>/dev/null
check "grid with no flag is the full calculation" cmp -s "$out/default.csv" "$out/explicit.csv"
check "grid with no flag says what it includes" grep -qx "light: direct light with shadows, and interreflected light" "$out/default.txt"
check "grid --light direct --no-shadows says what it left out" grep -qx "light: direct light without shadows (switched off); no interreflected light (switched off)" "$out/direct.txt"
check "the default's direct part is --light direct's light" python3 - "$out/default.txt" "$out/direct.txt" <<'PY'
import sys
full = [l for l in open(sys.argv[1]) if l.startswith("direct:")][0]
direct = [l for l in open(sys.argv[2]) if l.startswith("Eavg:")][0]
em = float(full.split("Em ")[1].split()[0]); eavg = float(direct.split()[1])
# The office has no occluder between a downlight and the work plane's points at 1 m spacing
# except the desk's top, which no point lies under: shadows change nothing there.
sys.exit(0 if abs(em - eavg) <= 1e-5 * eavg else "direct Em %g vs --light direct %g" % (em, eavg))
PY
expect "--light" "total" "direct" "\"all\"" -- grid "$data/office.json" --plane y=0.8 --light all

"$binary" validate --case direct-point-plane >"$out/case.txt" 2>&1
check "validate --case runs one case" grep -q "^direct-point-plane .* pass" "$out/case.txt"
check "validate --list lists every case" bash -c "[ \$('$binary' validate --list | wc -l) -eq 30 ]"
expect "unknown case" "cube-laser" "cube-point-rho0.5" -- validate --case cube-laser

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
