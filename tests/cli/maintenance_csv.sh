#!/usr/bin/env bash
# Maintained values in the grid's CSV (issue 21, part 4): each row states the maintenance factor
# in effect at its point and the value before maintenance. Checked against an independent run of
# the same scene without any factor: E_initial equals its E, E = factor x E_initial, and with a
# luminaire that has its own factor (0.5 beside the project's 0.8) the factor is each point's
# mix of the two, from a third run with that luminaire alone.
set -uo pipefail
binary=$1
data="$2/data/units"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

python3 - "$data/photometric.json" "$out" <<'PY'
import json, os, sys
scene = json.load(open(sys.argv[1]))
for l in scene["luminaires"]:
    if "file" in l: l["file"] = os.path.abspath(os.path.join(os.path.dirname(sys.argv[1]), l["file"]))
json.dump(scene, open(os.path.join(sys.argv[2], "initial.json"), "w"))
panel = dict(scene, luminaires=scene["luminaires"][:1])
json.dump(panel, open(os.path.join(sys.argv[2], "panel.json"), "w"))
scene["maintenance_factor"] = 0.8
scene["luminaires"][0]["maintenance_factor"] = 0.5
json.dump(scene, open(os.path.join(sys.argv[2], "maintained.json"), "w"))
PY
for s in initial panel maintained; do
  if ! "$binary" grid "$out/$s.json" --plane y=0 --extent -1.5,-1,1.5,1 --spacing 0.5 \
      --out "$out/$s.csv" >"$out/$s.txt" 2>&1; then
    echo "FAIL: grid $s: $(tail -1 "$out/$s.txt")"
    exit 1
  fi
done
python3 - "$out/initial.csv" "$out/maintained.csv" "$out/maintained.txt" "$out/panel.csv" <<'PY'
import csv, sys
a = list(csv.DictReader(open(sys.argv[1])))
b = list(csv.DictReader(open(sys.argv[2])))
panel = [float(r["E_lx"]) for r in csv.DictReader(open(sys.argv[4]))]
fail = []
if "maintained values: maintenance factor 0.8" not in open(sys.argv[3]).read():
    fail.append("stdout does not state the maintained values")
if len(a) != 24 or len(b) != 24: fail.append("rows: %d and %d, want 24" % (len(a), len(b)))
factors = []
for x, y, p in zip(a, b, panel):
    e0, e, f, initial = float(x["E_lx"]), float(y["E_lx"]), float(y["maintenance_factor"]), float(y["E_initial_lx"])
    if float(x["maintenance_factor"]) != 1.0: fail.append("initial scene's factor %s" % x["maintenance_factor"])
    # Printed to 10 significant digits (E) and 6 (the factor): 1e-9 and 1e-5 relative.
    if abs(initial - e0) > 1e-9 * e0: fail.append("E_initial %g, the scene without factors gives %g" % (initial, e0))
    if abs(f * initial - e) > 1e-5 * e: fail.append("factor %g x E_initial %g != E %g" % (f, initial, e))
    # The panel's share of the light at 0.5, the rest at 0.8.
    want = (0.5 * p + 0.8 * (e0 - p)) / e0
    if abs(f - want) > 1e-5: fail.append("factor %g, the panel's share gives %g" % (f, want))
    factors.append(f)
print("factor in effect: %.4f .. %.4f" % (min(factors), max(factors)))
# The lamp (0.8) dominates far from the panel (0.5), less so under it.
if max(factors) - min(factors) < 0.02: fail.append("the factor does not vary with the mix")
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
PY
