#!/usr/bin/env bash
# candela surfaces on the office scene: the desk's task area, immediate surrounding and background
# (their grids as the standard's rule gives them, worked by hand in surfaces_test.cpp), each
# summary equal to the mean of its own CSV rows and the task area's equal to `candela grid` over
# the same points, the verdicts, and bad input refused with a clear error.
set -uo pipefail
binary=$1
office="$2/../resources/scenes/office.json"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0

source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS

if "$binary" surfaces "$office" --out "$out/s.csv" >"$out/s.txt" 2>"$out/err.txt" &&
    "$binary" grid "$office" --plane y=0.75 --extent -0.4,-0.7,1.2,0.1 --spacing 0.16 \
      >"$out/grid.txt" 2>>"$out/err.txt"; then
  python3 - "$out/s.txt" "$out/s.csv" "$out/grid.txt" <<'PY' || failures=$((failures + 1))
import csv, re, sys
text = open(sys.argv[1]).read()
rows = list(csv.DictReader(open(sys.argv[2])))
grid = open(sys.argv[3]).read()
fail = []
for want in ["Desk (task area), plane y=0.75 (normal +y)",
             "grid 10 x 5 cells of 0.160 x 0.160 m, 50 points",
             "grid 16 x 11 cells of 0.163 x 0.164 m, 126 points",
             "grid 9 x 5 cells of 0.556 x 0.600 m, 35 points",
             "required: Em >= 500 lx, U0 >= 0.60: FAIL",
             "required: Em >= 300 lx, U0 >= 0.40:",
             "required: Em >= 100 lx, U0 >= 0.10: PASS",
             "Seated face at (0.400, 1.200, 0.600) m: cylindrical Ez",
             "maintenance factor 1 (initial values)"]:
    if want not in text: fail.append("missing: " + want)
# Each surface's Em, Emin and Emax from its own CSV rows (printed to 4 significant digits).
summaries = re.findall(r"\n(.+?) \((task area|immediate surrounding|background)\).*?\n.*?\n.*?\n"
                       r"  Em ([\d.e+]+) lx, U0 ([\d.]+), Emin ([\d.e+]+) lx, Emax ([\d.e+]+) lx",
                       text)
if len(summaries) != 3: fail.append("%d summaries, want 3" % len(summaries))
for name, role, em, u0, emin, emax in summaries:
    values = [float(r["E_lx"]) for r in rows if r["surface"] == name]
    mean = sum(values) / len(values)
    for label, printed, want in [("Em", em, mean), ("Emin", emin, min(values)),
                                 ("Emax", emax, max(values)), ("U0", u0, min(values) / mean)]:
        if abs(float(printed) - want) > 1e-3 * want:
            fail.append("%s %s printed %s, CSV gives %.6g" % (name, label, printed, want))
# The task area is the grid command's grid over the same extent and spacing: the same numbers.
desk = [float(r["E_lx"]) for r in rows if r["surface"] == "Desk"]
m = re.search(r"Eavg: ([\d.e+]+) lx", grid)
if not m or abs(float(m.group(1)) - sum(desk) / len(desk)) > 1e-5 * float(m.group(1)):
    fail.append("grid's Eavg %s differs from the task area's %.8g" %
                (m.group(1) if m else "?", sum(desk) / len(desk)))
if len(rows) != 50 + 126 + 35 + 2: fail.append("%d CSV rows, want 213" % len(rows))
for f in fail: print("FAIL: surfaces:", f)
sys.exit(1 if fail else 0)
PY
  [ $? -eq 0 ] && passed=$((passed + 1))
else
  echo "FAIL: candela surfaces: $(cat "$out/err.txt")"
  failures=$((failures + 1))
fi

# A scene with nothing to evaluate, a CSV onto the scene itself, an unknown option.
printf '{"geometry": [], "luminaires": []}\n' >"$out/empty.json"
expect "empty.json" "no task_areas or calculation_points" -- surfaces "$out/empty.json"
cp "$office" "$out/office.json"
resources=$(cd "$2/../resources" && pwd)
sed -i "s#\.\./luminaires/#$resources/luminaires/#" "$out/office.json"
before=$(md5sum <"$out/office.json")
expect "--out" "would overwrite" -- surfaces "$out/office.json" --out "$out/office.json"
[ "$(md5sum <"$out/office.json")" = "$before" ] || { echo "FAIL: the scene changed"; failures=$((failures + 1)); }
expect_usage "unknown option" -- surfaces "$out/office.json" --frobnicate
printf '{"task_areas": [{"plane": "y=1", "extent": [0, 0, 1, 1], "required": {"u0": 2}}]}\n' >"$out/bad.json"
expect "bad.json" "task_areas[0].required.u0" -- surfaces "$out/bad.json"

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
