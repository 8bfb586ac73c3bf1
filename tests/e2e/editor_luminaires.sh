#!/usr/bin/env bash
# End-to-end test of light-field and photometric luminaires in the editor, with real X input
# events under Xvfb (llvmpipe, no GPU needed). On a floor strip with the bundled OSRAM LED light
# field 8 cm above it (and a small ceiling, out of view, so that Add places luminaires above the
# floor):
#   1. click the LED in the viewport and drag it sideways     -> selected, moved; shot-000/001
#      show its lit spot gone from the old place and arrived at the new one; the sidecars and the
#      scene saved with Ctrl+S hold the new position
#   2. type another light field's path (candela convert --procedural bike-headlight) into the
#      inspector's `file` field, Enter, Ctrl+S                -> the file changed, the pose and the
#                                                                technique did not
#   3. outline: kind combo -> photometric, Add; inspector: Technique -> scattered, Spin
#      ctrl+click -> 30, Enter; Ctrl+S and a screenshot       -> linear-pendant.ies, technique
#      scattered, C0 turned 30 deg about the aim, in the saved scene and in the sidecar
# About 50 s with the default LED technique (granier2003); CANDELA_E2E_LF_TECHNIQUE=restricted-cdf
# runs the same steps with the progressive technique (about 3.5 min).
# Usage: bash tests/e2e/editor_luminaires.sh /path/to/candela /path/to/tests
# The editor writes its layout (viewport, luminaires with their scene-file entries and screen
# positions, named widgets' rectangles, mouse, typing, dirty, status) with --layout-file; the test
# polls it instead of sleeping for fixed times. Dear ImGui 1.86 may miss a click whose press and
# release fall within one frame (frames take seconds here), so every click holds the button down
# until the layout shows that a frame saw it down. Widgets are found through the rectangles the
# panels record for the layout file ("inspector.spin", "outline.add", ...). CANDELA_E2E_KEEP=1
# keeps the temporary folder (screenshots, saved scenes, layout, editor log) after a pass too.
set -euo pipefail

CANDELA=${1:?usage: editor_luminaires.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_luminaires.sh /path/to/candela /path/to/tests}
SOURCE=$(cd "$TESTS/.." && pwd)
DRAG_PX=280        # horizontal drag of the LED, window pixels
# The LED's technique. granier2003 is exact (one frame per change, then the editor idles), which
# keeps the test short on llvmpipe; the progressive restricted-cdf (1.4 s a frame here, for 64
# frames after each change) works too but takes about twice as long.
LF_TECHNIQUE=${CANDELA_E2E_LF_TECHNIQUE:-granier2003}
BOX=10             # side of the boxes whose mean brightness is compared, image pixels
TIMEOUT_S=240       # longest wait for any one step
SPIN_DEG=30        # Spin typed for the photometric luminaire

E2E_NAME=editor_luminaires
source "$(dirname "$0")/lib/harness.sh"
e2e_setup
SCENE=$TMP/scene.json
BIKE=$TMP/bike.lf.json
LED_FILE=$SOURCE/resources/luminaires/osram-lertduw.lf.json
IES_NAME=linear-pendant.ies
[ -f "$LED_FILE" ] || fail "no $LED_FILE"

# click X Y WHAT: a left click at window pixel (x, y) whose press a frame has seen before the
# release (buttons, combos and selectables act on the release).
click() {
    move_to "$1" "$2"
    xdotool mousedown 1
    wait_until "the press on $3" "d['mouse_down']"
    xdotool mouseup 1
    wait_until "the release on $3" "not d['mouse_down']"
}

# Ctrl+S, then waits until the scene is saved (no unsaved edits, status "Saved ...").
save_scene() {
    wait_until "no text field active before Ctrl+S" "not d['typing']"
    xdotool key ctrl+s
    wait_until "the scene to be saved" "not d['dirty'] and d['status'].startswith('Saved')"
    cp "$SCENE" "$TMP/saved-$1.json"
}

# Waits (softly: the checks do not need convergence) for the image to refine, then screenshots.
screenshot() {
    local n=$1
    local deadline=$((SECONDS + 25))
    until layout "d['converged'] or d['samples_per_pixel'] >= 16" >/dev/null 2>&1 ||
        ((SECONDS >= deadline)); do
        sleep 0.2
    done
    local before
    before=$(layout "d['screenshots']")
    click "$BX" "$BY" "the Screenshot button"
    wait_until "screenshot $n" "d['screenshots'] > $before"
    wait_for_file "$SHOTS/shot-$n.json"
    [ -s "$SHOTS/shot-$n.png" ] && [ -s "$SHOTS/shot-$n.exr" ] || fail "shot-$n.png/.exr missing"
    log "shot-$n written at $(layout "d['samples_per_pixel']") spp"
}

# --- A second light field, made while Xvfb and the editor start -----------------------------------
"$CANDELA" convert --procedural bike-headlight --out "$BIKE" --rays 20000 \
    >"$TMP/convert.log" 2>&1 &
CONVERT_PID=$!

# --- X server: Xvfb picks a free display number itself and reports it once it is ready. --------
e2e_start_xvfb 1024x720

# --- Scene: a floor strip (1 x 0.4 m: most of the image is background, which shades quickly on
# llvmpipe) seen from above, the LED 0.08 m over it aimed down, left of the middle (low, so its
# spot is small next to the drag). A small ceiling out of view raises the scene's bounds, so Add
# puts a luminaire at 1.5 m instead of under the floor; being behind every luminaire, it casts no
# shadow (no shadow rays are traced).
python3 - "$LED_FILE" "$SCENE" "$LF_TECHNIQUE" <<'EOF'
import json, sys
scene = {
    "geometry": [
        {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [1.0, 0.4]},
         "albedo": [0.6, 0.6, 0.6]},
        {"plane": {"center": [0, 2, 0], "normal": [0, -1, 0], "size": [0.2, 0.2]},
         "albedo": [0.6, 0.6, 0.6]},
    ],
    "luminaires": [
        {"type": "lightfield", "name": "LED", "file": sys.argv[1], "position": [-0.22, 0.08, 0],
         "aim": [0, -1, 0], "c0": [1, 0, 0], "technique": sys.argv[3]},
    ],
    "environment": None,
    "camera": {"position": [0, 1.1, 0.5], "target": [0, 0, 0], "fov_deg": 50},
}
json.dump(scene, open(sys.argv[2], "w"), indent=1)
EOF

# --- Editor ---------------------------------------------------------------------------------------
e2e_start_editor "$SCENE" 1024x720 "len(d['luminaires']) == 1 and d['frame'] >= 2"
wait_until "the LED on screen" "lum('LED')['screen'] is not None"
layout "d['selected'] is None" || fail "a luminaire is selected before any click"

read -r BX BY < <(layout "'%d %d' % tuple(round(c) for c in d['screenshot_button'])")
read -r LX LY < <(layout "'%d %d' % tuple(round(c) for c in lum('LED')['screen'])")
read -r VX VY VW VH < <(layout "'%d %d %d %d' % tuple(d['viewport'])")
log "viewport $VX,$VY ${VW}x$VH; LED at ($LX, $LY)"
((LX > VX + 30 && LX + DRAG_PX < VX + VW - 30 && LY > VY + 30 && LY < VY + VH - 30)) ||
    fail "the LED at ($LX, $LY) is too close to the viewport's edge for the drag"

# === 1. Select the LED by clicking it and drag it ==================================================
screenshot 000
e2e_drag "LED" "$LX" "$LY" "$DRAG_PX"
wait_until "the end of the drag" "not d['dragging']"
layout "d['selected'] == 'LED'" || fail "the LED is not selected after the drag"
LED_POSE=$(layout "json.dumps([lum('LED')[k] for k in ('position', 'aim', 'c0')])")
log "LED dragged; pose (position, aim, c0) $LED_POSE"
screenshot 001
save_scene drag

# The lit spot on the floor below the LED moved with it (checked in the images), and the sidecars
# and the saved scene hold the new position.
read -r IW IH < <(identify -format '%w %h\n' "$SHOTS/shot-001.png")
PYTHONPATH="$E2E_LIB" python3 - "$SHOTS/shot-000.json" "$SHOTS/shot-001.json" "$TMP/saved-drag.json" <<'EOF' \
    >"$TMP/spots.txt" || fail "sidecar / saved scene check after the drag"
import json, math, sys
from camera import project
before, after, saved = (json.load(open(p)) for p in sys.argv[1:4])
for s in (before, after):
    for key in ("camera", "luminaires", "render_size", "samples_per_pixel", "scene"):
        assert key in s, f"sidecar lacks {key}"
led = lambda doc: next(l for l in doc["luminaires"] if l["name"] == "LED")
p0, p1, ps = led(before)["position"], led(after)["position"], led(saved)["position"]
print(f"# sidecar position {p0} -> {p1}; saved {ps}", file=sys.stderr)
d = [b - a for a, b in zip(p0, p1)]
assert abs(d[1]) < 1e-9, f"the drag changed the height by {d[1]} m"
assert d[0] > 0.2, f"the LED moved only {d[0]:.3f} m towards +x"
assert all(abs(a - b) < 1e-9 for a, b in zip(p1, ps)), "the saved position differs from the sidecar's"
assert led(saved)["type"] == "lightfield" and led(saved)["file"].endswith("osram-lertduw.lf.json")

def pixel(p, s): return tuple(round(c) for c in project(p, s))
# Floor points below the old and the new position, 6 cm towards the camera so that the box is
# clear of the LED's own silhouette (the spot there is still near its peak).
print(*pixel([p0[0], 0.0, p0[2] + 0.06], after), *pixel([p1[0], 0.0, p1[2] + 0.06], after))
EOF
read -r OX OY PX PY <"$TMP/spots.txt"
for c in "$OX $OY" "$PX $PY"; do
    read -r x y <<<"$c"
    ((x >= BOX && x < IW - BOX && y >= BOX && y < IH - BOX)) ||
        fail "the floor spot ($x, $y) is outside the ${IW}x$IH image"
done
# The floor is lit only by the LED (no indirect light), so away from its spot it is black.
e2e_spot_moved "$SHOTS/shot-000.png" "$SHOTS/shot-001.png" "$OX" "$OY" "$PX" "$PY" 30
log "1. drag: passed"

# === 2. Swap the LED's light field through the inspector's file field ==============================
wait "$CONVERT_PID" || { cat "$TMP/convert.log" >&2; fail "candela convert --procedural failed"; }
[ -s "$BIKE" ] || fail "candela convert wrote no $BIKE"
log "$(grep -m1 converted "$TMP/convert.log" || true)"
point_to "inspector.field:file" 20
xdotool mousedown 1
wait_until "the file field to take the keyboard" "d['typing']"
xdotool mouseup 1
wait_until "the release in the file field" "not d['mouse_down']"
xdotool key ctrl+a
# Select-all and the typed text must reach different frames (Dear ImGui inserts a frame's
# characters before it handles its shortcuts); no rendering while typing, so frames are quick.
sleep 0.3
xdotool type --delay 20 "$BIKE"
xdotool key Return
wait_until "the LED's file to become $BIKE" "lum('LED')['file'] == '$BIKE' and not d['typing']"
layout "d['error'] == ''" || fail "the editor reported an error: $(layout "d['error']")"
log "the LED now shows $(layout "lum('LED')['file']")"
save_scene swap
python3 - "$TMP/saved-swap.json" "$BIKE" "$LED_POSE" "$LF_TECHNIQUE" <<'EOF' ||
import json, sys
saved, bike, technique = json.load(open(sys.argv[1])), sys.argv[2], sys.argv[4]
pose = json.loads(sys.argv[3])
leds = [l for l in saved["luminaires"] if l["name"] == "LED"]
assert len(saved["luminaires"]) == 1 and len(leds) == 1, "expected exactly the LED in the scene"
led = leds[0]
print(f"editor_luminaires: saved LED {led}")
assert led["type"] == "lightfield", f"type {led['type']}"
assert led["file"] == bike, f"file {led['file']}, expected {bike}"
assert led["technique"] == technique, f"technique {led['technique']}, expected {technique}"
for key, want in zip(("position", "aim", "c0"), pose):
    assert all(abs(a - b) < 1e-9 for a, b in zip(led[key], want)), f"{key} {led[key]} != {want}"
EOF
    fail "saved scene after the swap"
log "2. file swap: passed"

# === 3. A photometric luminaire: Add, technique scattered, Spin typed =============================
click_widget "outline.add_kind"
click_widget "outline.add_kind:photometric"
wait_until "the kind combo to close" "w('outline.add_kind:photometric') is None"
click_widget "outline.add"
wait_until "a photometric luminaire to be added and selected" \
    "(len(d['luminaires']) == 2 and d['luminaires'][1]['type'] == 'photometric' and
      d['selected'] == d['luminaires'][1]['name'])"
PNAME=$(layout "d['selected']")
log "added \"$PNAME\": $(layout "lum('$PNAME')")"
layout "(lum('$PNAME')['file'].endswith('$IES_NAME') and
         close(lum('$PNAME')['aim'], [0, -1, 0]) and close(lum('$PNAME')['c0'], [1, 0, 0]))" ||
    fail "the added photometric luminaire is not $IES_NAME aimed down with C0 along +x"
layout "lum('$PNAME')['technique'] != 'scattered'" || fail "the new luminaire is already scattered"

click_widget "inspector.technique"
click_widget "inspector.technique:scattered"
wait_until "the technique scattered" "lum('$PNAME')['technique'] == 'scattered'"

point_to "inspector.spin"
xdotool keydown ctrl
xdotool mousedown 1
wait_until "ctrl+click to turn Spin into a text field" "d['typing']"
xdotool mouseup 1
xdotool keyup ctrl
wait_until "the release on Spin" "not d['mouse_down']"
xdotool key ctrl+a  # the text field of a ctrl+clicked drag starts all selected; to be sure
sleep 0.3
xdotool type --delay 20 "$SPIN_DEG"
xdotool key Return
# Aim (0, -1, 0): Spin turns C0 from +X towards +Z (aim x +X), so C0 = (cos s, 0, sin s).
C0_WANT="[math.cos(math.radians($SPIN_DEG)), 0.0, math.sin(math.radians($SPIN_DEG))]"
wait_until "C0 turned by $SPIN_DEG deg" \
    "not d['typing'] and close(lum('$PNAME')['c0'], $C0_WANT, 1e-6)"
log "$PNAME: c0 $(layout "lum('$PNAME')['c0']")"
save_scene photometric
screenshot 002
python3 - "$TMP/saved-photometric.json" "$SHOTS/shot-002.json" "$PNAME" "$IES_NAME" "$SPIN_DEG" \
    "$BIKE" "$LED_POSE" <<'EOF' || fail "saved scene / sidecar after the photometric edits"
import json, math, sys
saved, sidecar = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
name, ies, spin, bike = sys.argv[3], sys.argv[4], float(sys.argv[5]), sys.argv[6]
pose = json.loads(sys.argv[7])
want = [math.cos(math.radians(spin)), 0.0, math.sin(math.radians(spin))]
for what, doc in (("saved scene", saved), ("sidecar", sidecar)):
    lums = {l["name"]: l for l in doc["luminaires"]}
    assert set(lums) == {"LED", name}, f"{what}: luminaires {sorted(lums)}"
    p = lums[name]
    print(f"editor_luminaires: {what}: {p}")
    assert p["type"] == "photometric" and p["file"].endswith(ies), f"{what}: {p['type']} {p['file']}"
    assert p["technique"] == "scattered", f"{what}: technique {p['technique']}"
    assert all(abs(a - b) < 1e-6 for a, b in zip(p["aim"], [0, -1, 0])), f"{what}: aim {p['aim']}"
    assert all(abs(a - b) < 1e-6 for a, b in zip(p["c0"], want)), f"{what}: c0 {p['c0']} != {want}"
    led = lums["LED"]
    assert led["file"] == bike, f"{what}: LED file {led['file']}"
    for key, w in zip(("position", "aim", "c0"), pose):
        assert all(abs(a - b) < 1e-9 for a, b in zip(led[key], w)), f"{what}: LED {key} {led[key]}"
EOF
log "3. photometric: passed"

kill -0 "$EDITOR_PID" 2>/dev/null || fail "the editor exited"
import -window root "$TMP/window.png" 2>/dev/null || true  # the whole editor, for a look
PASSED=1
log "PASS"
