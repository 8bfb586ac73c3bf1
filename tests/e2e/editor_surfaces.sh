#!/usr/bin/env bash
# End-to-end test of the editor's EN 12464-1 calculation surfaces (issue 21, part 5) and its UGR
# (part 6), with real X
# input under Xvfb, on the shipped office (a desk task area, a cylindrical and a vertical point):
#   1. the Measure panel opens on the task areas: its grid on the desk's plane and extent, and
#      "Compute surfaces" in view without scrolling at the editor's default size (1280x800);
#      click it;
#   2. the panel's results (the layout file's "surfaces") list the desk, its immediate
#      surrounding and background and the two points, each Em, U0, Emin and Emax equal to
#      `candela surfaces`'s to its printed digits (the total light with shadows in both, by
#      default), each verdict the CLI's word, and the desk fails its 500 lx as the CLI says; the
#      UGR equal to `candela glare`'s;
#   3. the surfaces' false colour, then their isolux lines: one at each of the legend's levels
#      within a surface's range, none outside it, each where the CLI's values interpolate to
#      its level;
#   4. save the window images (F12) for a person to look at (CANDELA_E2E_KEEP=1 keeps them).
# Usage: bash tests/e2e/editor_surfaces.sh /path/to/candela /path/to/tests
set -euo pipefail

CANDELA=${1:?usage: editor_surfaces.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_surfaces.sh /path/to/candela /path/to/tests}
SOURCE=$(cd "$TESTS/.." && pwd)
TIMEOUT_S=240

E2E_NAME=editor_surfaces
source "$(dirname "$0")/lib/harness.sh"
e2e_setup
e2e_start_xvfb 1280x800

python3 - "$SOURCE/resources/scenes/office.json" "$TMP/office.json" <<'PY'
import json, os, sys
scene = json.load(open(sys.argv[1]))
base = os.path.dirname(os.path.abspath(sys.argv[1]))
for l in scene["luminaires"]:
    l["file"] = os.path.normpath(os.path.join(base, l["file"]))
json.dump(scene, open(sys.argv[2], "w"), indent=1)
PY
"$CANDELA" surfaces "$TMP/office.json" >"$TMP/cli.txt" 2>&1 || fail "candela surfaces: $(cat "$TMP/cli.txt")"

e2e_start_editor "$TMP/office.json" 1280x800 "len(d['luminaires']) == 6 and d['frame'] >= 2"
# The panel starts on the desk (y=0.75, x -0.4..1.2 m, z -0.7..0.1 m), not on plane 0 with no
# extent, and shows "Compute surfaces" without scrolling.
wait_until "the Measure panel" "w('measure.compute_surfaces') is not None and w('panel.measure') is not None"
log "grid: $(layout "d['grid']"); Compute surfaces at $(layout "w('measure.compute_surfaces')") in $(layout "w('panel.measure')")"
layout "d['grid']['plane'] == 'y=0.75' and d['grid']['extent_set'] and close(d['grid']['lo'], [-0.4, -0.7]) and close(d['grid']['hi'], [1.2, 0.1])" ||
  fail "the Measure panel's grid does not start on the desk: $(layout "d['grid']")"
layout "w('measure.compute_surfaces')[1] >= w('panel.measure')[1] and w('measure.compute_surfaces')[3] <= w('panel.measure')[3]" ||
  fail "Compute surfaces is not in view at the default size: $(layout "w('measure.compute_surfaces')") in $(layout "w('panel.measure')")"
click_widget measure.compute_surfaces
wait_until "the surfaces' results" "d['surfaces'] is not None and len(d['surfaces']) == 5"
log "surfaces: $(layout "d['surfaces']")"

python3 - "$LAYOUT" "$TMP/cli.txt" <<'PY' || fail "the editor's surfaces differ from candela surfaces (above)"
import json, re, sys
d = json.load(open(sys.argv[1]))["surfaces"]
cli = open(sys.argv[2]).read()
# One number everywhere: Em, U0, Emin and Emax of each surface, and each point's E, as the CLI
# prints them (4 significant digits, U0 3 decimals: the editor's value rounds to the CLI's).
rows = re.findall(r"  E(?:z)?m ([\d.e+]+) lx, U0 ([\d.]+), E(?:z)?min ([\d.e+]+) lx, E(?:z)?max ([\d.e+]+) lx", cli)
points = [float(x) for x in re.findall(r"(?:cylindrical Ez|: E) ([\d.e+]+) lx", cli)]
fail = []
if len(rows) + len(points) != 5: fail.append("the CLI printed %d values, want 5" % (len(rows) + len(points)))
for s, (em, u0, emin, emax) in zip(d, rows):
    for key, text in (("em", em), ("emin", emin), ("emax", emax)):
        if "%.4g" % s[key] != "%.4g" % float(text): fail.append("%s %s: editor %.6g, CLI %s" % (s["name"], key, s[key], text))
    if "%.3f" % s["u0"] != u0: fail.append("%s U0: editor %.5f, CLI %s" % (s["name"], s["u0"], u0))
for s, w in zip(d[len(rows):], points):
    if "%.4g" % s["em"] != "%.4g" % w: fail.append("%s: editor %.6g, CLI %g" % (s["name"], s["em"], w))
if d[0]["name"] != "Desk" or d[0]["passes"] or d[0]["points"] != 50:
    fail.append("desk: %s (want 50 points, failing 500 lx as the CLI says)" % d[0])
# Each verdict in the CLI's words (PASS, FAIL, no requirement; "no points" for a surface the
# room leaves none of), surfaces in order, then the points that have a requirement.
words = re.findall(r"(?:required: .*: |  )(PASS|FAIL|no requirement|no points)(?: \(|\n)", cli)
words += re.findall(r", required [\d.]+ lx: (PASS|FAIL)", cli)
want = [s["verdict"] for s in d[:len(rows)]] + [s["verdict"] for s in d[len(rows):] if s["verdict"] != "no requirement"]
if words != want: fail.append("verdicts: editor %s, CLI %s" % (want, words))
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
PY

# The UGR at the office's two observers: the editor computes it as the CLI does (the same light,
# patches, method and seeds), so the two agree to the CLI's printed 0.1 (0.05 and rounding).
"$CANDELA" glare "$TMP/office.json" >"$TMP/glare.txt" 2>&1 || fail "candela glare: $(cat "$TMP/glare.txt")"
click_widget measure.compute_glare
wait_until "the UGR results" "d['glare'] is not None and len(d['glare']) == 2"
log "glare: $(layout "d['glare']")"
python3 - "$LAYOUT" "$TMP/glare.txt" <<'PY' || fail "the editor's UGR differs from candela glare's (above)"
import json, re, sys
d = json.load(open(sys.argv[1]))["glare"]
cli = [float(x) for x in re.findall(r"^  UGR ([\d.]+)", open(sys.argv[2]).read(), re.M)]
fail = [] if len(cli) == 2 else ["the CLI printed %d UGR values, want 2" % len(cli)]
for g, want in zip(d, cli):
    if abs(g["ugr"] - want) > 0.0501: fail.append("%s: editor %.2f, CLI %.1f" % (g["name"], g["ugr"], want))
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
PY

# False colour on the surfaces: each point's cell in the colour of its value on the legend (0 to
# 500 lx, linear: the default), against the scale worked out here from the stops of
# shaders/shared/FalseColour.h and the CLI's value at that point. Each cell is sampled a quarter
# of its spacing from its point, on the side that shows highest on screen (its label hangs below
# the point); cells under 5 pixels from point to sample, and samples a label or dot of another
# point may cover, are left out. Of the rest (at least 10; 15 here), 90 % must match.
"$CANDELA" surfaces "$TMP/office.json" --out "$TMP/surfaces.csv" >/dev/null 2>&1 || fail "candela surfaces --out"
# The colours alone first: the isolux lines (on by default) would cross some of the samples.
wait_until "the surfaces' isolux lines" "len(d['isolines']) > 0"
click_widget measure.isolines
wait_until "no isolux lines" "len(d['isolines']) == 0"
click_widget measure.colour_surfaces
wait_frames 3
xdotool key F12
wait_until "the window image" "d['window_images'] >= 1"
shot=$(ls "$SHOTS"/window-*.png | head -1)
python3 - "$TMP/surfaces.csv" "$LAYOUT" "$TMP/office.json" "$shot" "$E2E_LIB" "$TMP/cli.txt" <<'PY' || fail "the surfaces' false colours differ from the legend's (above)"
import csv, json, re, subprocess, sys
sys.path.insert(0, sys.argv[5])
from camera import project
stops = [(0.08, 0.04, 0.28), (0.24, 0.10, 0.52), (0.16, 0.28, 0.70), (0.05, 0.47, 0.72),
         (0.08, 0.62, 0.58), (0.32, 0.74, 0.36), (0.66, 0.82, 0.18), (0.96, 0.86, 0.16),
         (1.00, 0.97, 0.66)]
def colour(e, lo=0.0, hi=500.0):
    x = min(max((e - lo) / (hi - lo), 0.0), 1.0) * 8
    i = min(int(x), 7)
    return [round(255 * (a + (b - a) * (x - i))) for a, b in zip(stops[i], stops[i + 1])]
d = json.load(open(sys.argv[2]))
cam = json.load(open(sys.argv[3]))["camera"]
# The window image as binary PPM through oiiotool (OpenImageIO's tool, installed by setup.sh).
ppm = sys.argv[4][:-4] + ".ppm"
subprocess.run(["oiiotool", sys.argv[4], "--ch", "R,G,B", "-d", "uint8", "-o", ppm], check=True)
data = open(ppm, "rb").read()
fields, at = [], 0
while len(fields) < 4:  # P6, width, height, maxval, then one whitespace byte
    while data[at:at + 1].isspace(): at += 1
    start = at
    while not data[at:at + 1].isspace(): at += 1
    fields.append(data[start:at])
w, h = int(fields[1]), int(fields[2])
pixels = data[at + 1:]
pixel = lambda x, y: tuple(pixels[3 * (y * w + x): 3 * (y * w + x) + 3])
vx, vy, vw, vh = d["viewport"]
rw, rh = d["render_size"]
rows = list(csv.DictReader(open(sys.argv[1])))
# Each surface's cell size (u, v in m) as the CLI prints it; these are horizontal: u = x, v = z.
spacing = {m[0]: (float(m[1]), float(m[2])) for m in re.findall(
    r"\n(.+?) \((?:task area|immediate surrounding|background)\).*\n.*\n\s+grid \d+ x \d+ cells of ([\d.]+) x ([\d.]+) m",
    open(sys.argv[6]).read())}
def window(p):
    x, y = project(p, {"camera": cam, "render_size": [rw, rh]})
    return vx + x * vw / rw, vy + y * vh / rh
at = [window([float(r["x"]), float(r["y"]), float(r["z"])]) for r in rows]
good = total = 0
for r, (x, y) in zip(rows, at):
    if r["surface"] not in spacing: continue  # the calculation points
    su, sv = spacing[r["surface"]]
    p = [float(r["x"]), float(r["y"]), float(r["z"])]
    sx, sy = min((window([p[0] + du, p[1], p[2] + dv]) for du, dv in
                  [(su / 4, 0), (-su / 4, 0), (0, sv / 4), (0, -sv / 4)]), key=lambda q: q[1])
    if y - sy < 5: continue  # the cell is too small on screen
    px, py = round(sx), round(sy)
    if not (vx <= px < vx + vw and vy <= py < vy + vh): continue  # outside the view
    if any(abs(qx - sx) < 18 and -3 <= sy - qy <= 17 for qx, qy in at): continue  # a label
    want, got = colour(float(r["E_lx"])), pixel(px, py)
    total += 1
    if max(abs(a - b) for a, b in zip(want, got)) <= 6: good += 1
    elif total <= 60: print("  (%d, %d): %s, want %s for %.1f lx" % (px, py, got, want, float(r["E_lx"])))
print("%d of %d cells clear of labels in their legend colour" % (good, total))
sys.exit(0 if total >= 10 and good >= 0.9 * total else 1)
PY
# The isolux lines on the surfaces, at the legend's levels (0 to 500 lx: 100, 200, 300, 400 lx),
# against the CLI's points (the CSV): each surface has a line at every level that some complete
# cell of its points (four neighbours, none in its hole) spans, and at no other (an immediate
# surrounding one point wide has no complete cell, hence no line); and each line's first point
# lies on an edge between two neighbouring points whose values, interpolated linearly, give its
# level. The editor's values agree with the CLI's to 4 digits (above): 0.05 % of 300 lx is
# 0.15 lx, so within 0.5 lx.
click_widget measure.isolines
wait_until "the isolux lines" "len(d['isolines']) > 0"
xdotool key F12
wait_until "the window image with isolux lines" "d['window_images'] >= 2"
log "isolines: $(layout "[(l['surface'], l['level'], l['labelled']) for l in d['isolines']]")"
python3 - "$TMP/surfaces.csv" "$LAYOUT" <<'PY' || fail "the isolux lines are not where the CLI's values put them (above)"
import csv, json, sys
d = json.load(open(sys.argv[2]))
lines = d["isolines"]
values = {}  # surface -> {(x, z) to 0.1 mm: E}; the office's surfaces are horizontal: u = x, v = z
for r in csv.DictReader(open(sys.argv[1])):
    if r["role"] in ("task area", "immediate surrounding", "background"):
        values.setdefault(r["surface"], {})[(round(float(r["x"]), 4), round(float(r["z"]), 4))] = float(r["E_lx"])
fail = []
for name, pts in values.items():
    us, vs = sorted(set(u for u, v in pts)), sorted(set(v for u, v in pts))  # the grid's columns, rows
    spans = set()
    for i in range(len(us) - 1):
        for j in range(len(vs) - 1):
            corners = [(us[i], vs[j]), (us[i + 1], vs[j]), (us[i + 1], vs[j + 1]), (us[i], vs[j + 1])]
            if all(c in pts for c in corners):
                e = [pts[c] for c in corners]
                spans |= {l for l in (100.0, 200.0, 300.0, 400.0) if min(e) < l <= max(e)}
    got = sorted(set(l["level"] for l in lines if l["surface"] == name))
    if got != sorted(spans): fail.append("%s: lines at %s lx, want %s" % (name, got, sorted(spans)))
    for l in (l for l in lines if l["surface"] == name):
        u, v = l["first"]
        found = []
        for k in range(len(us) - 1):  # along u, on a row
            for row in vs:
                a, b = (us[k], row), (us[k + 1], row)
                if abs(v - row) < 1e-4 and a[0] - 1e-4 <= u <= b[0] + 1e-4 and a in pts and b in pts:
                    found.append(pts[a] + (u - a[0]) / (b[0] - a[0]) * (pts[b] - pts[a]))
        for k in range(len(vs) - 1):  # along v, on a column
            for col in us:
                a, b = (col, vs[k]), (col, vs[k + 1])
                if abs(u - col) < 1e-4 and a[1] - 1e-4 <= v <= b[1] + 1e-4 and a in pts and b in pts:
                    found.append(pts[a] + (v - a[1]) / (b[1] - a[1]) * (pts[b] - pts[a]))
        if not any(abs(e - l["level"]) <= 0.5 for e in found):
            fail.append("%s %g lx at (%.4f, %.4f) m: the CLI's points there give %s lx" % (name, l["level"], u, v, ["%.2f" % e for e in found]))
if not any(l["labelled"] for l in lines): fail.append("no isolux line has its value written")
for f in fail: print("FAIL:", f)
print("%d isolux lines on %d surfaces where the CLI's values put them" % (len(lines), len(set(l["surface"] for l in lines))))
sys.exit(1 if fail else 0)
PY
# Drawing a task area with the mouse (part 5): arm "Draw a task area", then drag in the viewport
# from where one world point on the grid's plane shows to where another does (projected through
# the camera by tests/e2e/lib/camera.py, not by the editor). The new task area's corners are those
# points within 3 cm (the 1 cm rounding, and a pixel of rounding at about 4 m).
plane=$(layout "d['grid_plane']")
[[ "$plane" =~ ^y=([-0-9.e]+)$ ]] || fail "the grid's plane is $plane, expected a horizontal one"
height=${BASH_REMATCH[1]}
areas=$(layout "len(d['task_areas'])")
click_widget measure.draw_task
wait_until "drawing armed" "d['drawing_area']"
read -r x0 y0 <<<"$(window_point "[-0.9, $height, -0.6]" "$TMP/office.json")"
read -r x1 y1 <<<"$(window_point "[0.7, $height, 0.5]" "$TMP/office.json")"
log "drawing from ($x0, $y0) to ($x1, $y1) on $plane"
xdotool mousemove "$x0" "$y0"
wait_frames 2
xdotool mousedown 1
wait_until "the press in the viewport" "d['mouse_down']"
for k in 1 2 3 4; do
  xdotool mousemove $((x0 + (x1 - x0) * k / 4)) $((y0 + (y1 - y0) * k / 4))
  wait_frames 1
done
xdotool mouseup 1
wait_until "the drawn task area" "len(d['task_areas']) == $areas + 1 and not d['drawing_area']"
log "drawn: $(layout "d['task_areas'][-1]") ($(layout "d['status']"))"
layout "d['undo'] == 'Draw task area Task area'" || fail "the drawing is not one undo step: $(layout "d['undo']")"
python3 - "$LAYOUT" "$plane" <<'PY' || fail "the drawn task area is not where the drag was (above)"
import json, sys
a = json.load(open(sys.argv[1]))["task_areas"][-1]
fail = [] if a["plane"] == sys.argv[2] else ["plane %s, want %s" % (a["plane"], sys.argv[2])]
for got, want in zip(a["lo"] + a["hi"], [-0.9, -0.6, 0.7, 0.5]):
    if abs(got - want) > 0.03: fail.append("corner coordinate %.3f m, want %.3f m" % (got, want))
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
PY

log "window image: $(ls "$SHOTS" | tr '\n' ' ')"
PASSED=1
log "passed"
