#!/usr/bin/env bash
# End-to-end test of the editor with real X input events under Xvfb (llvmpipe, no GPU needed):
#   1. press the Screenshot button                         -> shot-000.{png,exr,json}
#   2. press on the ceiling panel and drag it 150 px right  -> the panel follows the mouse
#   3. let the image refine, press Screenshot again         -> shot-001.{png,exr,json}
#   4. check the images: the panel's old spot got darker, its new spot brighter; the sidecars
#      parse and the luminaire moved in its horizontal plane to where the mouse was released.
# Usage: bash tests/e2e/editor_drag.sh /path/to/candela /path/to/tests
# The editor writes its layout (viewport, button and luminaire positions in window pixels) with
# --layout-file; the test polls it instead of sleeping for fixed times. CANDELA_E2E_KEEP=1 keeps
# the temporary folder (screenshots, layout, editor log, window.png) after a pass too.
set -euo pipefail

CANDELA=${1:?usage: editor_drag.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_drag.sh /path/to/candela /path/to/tests}
SOURCE=$(cd "$TESTS/.." && pwd)
DRAG_PX=150        # horizontal drag, window pixels
BOX=20             # side of the boxes whose mean brightness is compared, image pixels
TIMEOUT_S=240       # longest wait for any one step

E2E_NAME=editor_drag
source "$(dirname "$0")/lib/harness.sh"
e2e_setup

# --- X server ------------------------------------------------------------------------------------
e2e_start_xvfb 1280x800

# --- Scene: the demo with the camera raised to see the ceiling panel, and the panel turned so ---
# its short side runs across the image (a 150 px drag then clears its old footprint).
raised_demo_scene "$SOURCE" "$TMP/scene.json"

# --- Editor ---------------------------------------------------------------------------------------
e2e_start_editor "$TMP/scene.json" 1280x800 "len(d['luminaires']) > 0 and d['frame'] >= 2"
wait_until "a visible luminaire" "d['luminaires'][0]['screen'] is not None"

read -r BX BY < <(layout "'%d %d' % tuple(round(c) for c in d['screenshot_button'])")
read -r LX LY < <(layout "'%d %d' % tuple(round(c) for c in d['luminaires'][0]['screen'])")
NAME=$(layout "d['luminaires'][0]['name']")
read -r VX VY VW VH < <(layout "'%d %d %d %d' % tuple(d['viewport'])")
echo "editor_drag: viewport $VX,$VY ${VW}x$VH; Screenshot button at ($BX, $BY); \"$NAME\" at ($LX, $LY)"
((LX > VX + BOX && LX + DRAG_PX < VX + VW - BOX && LY > VY + BOX && LY < VY + VH - BOX)) ||
    fail "the luminaire at ($LX, $LY) is too close to the viewport's edge for the drag"

# --- 1. Screenshot before the drag ---------------------------------------------------------------
move_to "$BX" "$BY"
xdotool click 1
wait_for_file "$SHOTS/shot-000.json"
[ -s "$SHOTS/shot-000.png" ] && [ -s "$SHOTS/shot-000.exr" ] || fail "shot-000.png/.exr missing"
echo "editor_drag: shot-000 written"

# --- 2. Drag the luminaire by DRAG_PX to the right ----------------------------------------------
# On the placement grid (0.1 m, about 24 px across in this view): within a cell of the mouse.
E2E_DRAG_GRID=20 e2e_drag "$NAME" "$LX" "$LY" "$DRAG_PX"
wait_until "the end of the drag" "not d['dragging']"
read -r NX NY < <(layout "'%.2f %.2f' % tuple(d['luminaires'][0]['screen'])")
echo "editor_drag: \"$NAME\" now at ($NX, $NY)"

# --- 3. Let the image refine (a soft wait: the checks do not need convergence), screenshot ------
deadline=$((SECONDS + 20))
until layout "d['converged'] or d['samples_per_pixel'] >= 16" >/dev/null 2>&1 ||
    ((SECONDS >= deadline)); do
    sleep 0.2
done
move_to "$BX" "$BY"
xdotool click 1
wait_for_file "$SHOTS/shot-001.json"
[ -s "$SHOTS/shot-001.png" ] && [ -s "$SHOTS/shot-001.exr" ] || fail "shot-001.png/.exr missing"
echo "editor_drag: shot-001 written"
kill -0 "$EDITOR_PID" 2>/dev/null || fail "the editor exited"
grep -q "shot-001.png" "$TMP/editor.log" || fail "the editor did not print the screenshot paths"
import -window root "$TMP/window.png" 2>/dev/null || true  # the whole editor, for a look

# --- 4. Compare the screenshots ------------------------------------------------------------------
# Window pixels -> image pixels through the viewport rectangle and the image size.
read -r IW IH < <(identify -format '%w %h\n' "$SHOTS/shot-001.png")
read -r OX OY < <(python3 -c "print(round(($LX-$VX)*$IW/$VW), round(($LY-$VY)*$IH/$VH))")
read -r PX PY < <(python3 -c "print(round(($NX-$VX)*$IW/$VW), round(($NY-$VY)*$IH/$VH))")
# The panel is an emitter far brighter than the frame mean, so tone mapping shows it near white;
# the ceiling around it is lit only indirectly (not at all here). 20 grey levels is well above
# the noise of a few-spp image in 400-pixel means.
e2e_spot_moved "$SHOTS/shot-000.png" "$SHOTS/shot-001.png" "$OX" "$OY" "$PX" "$PY" 20

# Sidecars: parse, the luminaire moved in its horizontal plane onto the placement grid, in the
# grid cell where the mouse was released (the renderer's camera model: lookAt + perspective,
# Y-up).
PYTHONPATH="$E2E_LIB" python3 - "$SHOTS/shot-000.json" "$SHOTS/shot-001.json" "$NAME" "$PX" "$PY" <<'EOF' ||
import json, math, sys
from camera import project
before, after = (json.load(open(p)) for p in sys.argv[1:3])
name, px, py = sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
for s in (before, after):
    for key in ("camera", "luminaires", "render_size", "samples_per_pixel", "passes",
                "total_gpu_ms", "timestamp", "scene"):
        assert key in s, f"sidecar lacks {key}"
    assert all("technique" in l for l in s["luminaires"]), "a luminaire lacks its technique"
lum = lambda s: next(l for l in s["luminaires"] if l["name"] == name)
p0, p1 = lum(before)["position"], lum(after)["position"]
d = [b - a for a, b in zip(p0, p1)]
print(f"editor_drag: sidecar position {p0} -> {p1}")
assert abs(d[1]) < 1e-6, f"the drag changed the height by {d[1]} m"
assert math.hypot(d[0], d[2]) > 0.2, f"the luminaire moved only {math.hypot(d[0], d[2]):.3f} m"
assert d[0] > 0, "dragging right should move the luminaire towards +x in this view"

# It lands on the placement grid (0.1 m by default): x and z are multiples of the step...
step = 0.1
for c in (p1[0], p1[2]):
    assert abs(c / step - round(c / step)) < 1e-6, f"{p1} is not on the {step} m grid"
# ...in the grid cell where the mouse was released: the mouse within (4 px of) the cell's
# projection.
corners = [project([p1[0] + dx, p1[1], p1[2] + dz], after)
           for dx in (-step / 2, step / 2) for dz in (-step / 2, step / 2)]
xs, ys = [c[0] for c in corners], [c[1] for c in corners]
sx, sy = project(p1, after)
print(f"editor_drag: new position projects to ({sx:.1f}, {sy:.1f}), its cell to x {min(xs):.1f}..{max(xs):.1f}, y {min(ys):.1f}..{max(ys):.1f}; mouse released at ({px}, {py})")
assert min(xs) - 4 <= px <= max(xs) + 4 and min(ys) - 4 <= py <= max(ys) + 4, \
    "the luminaire is not in the grid cell where it was dropped"
EOF
    fail "sidecar check"

PASSED=1
echo "editor_drag: PASS"
