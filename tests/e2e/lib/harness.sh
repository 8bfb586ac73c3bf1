# The editor end-to-end tests' shared harness (sourced, not run; the e2e glob only picks up
# tests/e2e/*.sh). E2E_OTHER_PIDS lists further processes (a second editor, a second X server)
# that the cleanup stops too. The caller sets E2E_NAME (the prefix of its messages) and TIMEOUT_S (longest
# wait for any one step), then calls e2e_setup, which makes TMP (with LAYOUT and SHOTS paths),
# checks the tools and installs the cleanup. Later, e2e_start_xvfb WxH starts an X server and
# exports DISPLAY; the caller starts the editor with --layout-file "$LAYOUT", sets EDITOR_PID and
# WID, and sets PASSED=1 at the end. CANDELA_E2E_KEEP=1 keeps TMP after a pass too. Helpers:
# layout/wait_until (the layout file), move_to, click_widget (a recorded widget, scrolled into
# its panel), window_point (a world point on screen), raised_demo_scene (the ceiling-panel view).

XVFB_PID=
EDITOR_PID=
PASSED=0
T0=$SECONDS
# Python helpers for the scripts' checks (camera.py: where a world point lands in a screenshot).
E2E_LIB=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

log() { echo "$E2E_NAME: [$((SECONDS - T0)) s] $*"; }

e2e_cleanup() {
    [ -n "$EDITOR_PID" ] && kill "$EDITOR_PID" 2>/dev/null || true
    local pid
    for pid in ${E2E_OTHER_PIDS:-}; do kill "$pid" 2>/dev/null || true; done
    [ -n "$XVFB_PID" ] && kill "$XVFB_PID" 2>/dev/null || true
    wait 2>/dev/null || true
    if [ "$PASSED" = 1 ] && [ -z "${CANDELA_E2E_KEEP:-}" ]; then
        rm -rf "$TMP"
    else
        echo "$E2E_NAME: files kept in $TMP" >&2
    fi
}

fail() {
    echo "$E2E_NAME: FAIL: $*" >&2
    if [ -f "$TMP/editor.log" ]; then
        echo "--- editor output (last 40 lines) ---" >&2
        tail -n 40 "$TMP/editor.log" >&2
    fi
    if [ -f "$LAYOUT" ]; then
        echo "--- last layout ---" >&2
        cat "$LAYOUT" >&2
    fi
    [ -n "${DISPLAY:-}" ] && import -window root "$TMP/failure.png" 2>/dev/null || true
    exit 1
}

e2e_setup() {
    TMP=$(mktemp -d "${TMPDIR:-/tmp}/candela-e2e.XXXXXX")
    LAYOUT=$TMP/layout.json
    SHOTS=$TMP/shots
    # Recent files and untitled autosaves go here, not into the user's ~/.local/state.
    export CANDELA_STATE_DIR=$TMP/state
    trap e2e_cleanup EXIT
    local tool
    for tool in Xvfb xdotool python3 convert identify import; do
        command -v "$tool" >/dev/null || fail "$tool is not installed (needs xvfb, xdotool, imagemagick)"
    done
    [ -x "$CANDELA" ] || fail "no candela binary at $CANDELA"
}

# Evaluates a Python expression over the layout file's JSON `d`; a bool becomes the exit status,
# anything else is printed. Exit 2 while the file is missing or unreadable. lum(name) is the
# layout's entry of that luminaire (None when there is none), w(name) a widget's rectangle
# (None when it was not drawn last frame).
layout() {
    python3 - "$LAYOUT" "$1" <<'PY'
import json, math, sys
try:
    with open(sys.argv[1]) as f:
        d = json.load(f)
except Exception:
    sys.exit(2)
lum = lambda name: next((l for l in d["luminaires"] if l["name"] == name), None)
w = lambda name: d.get("widgets", {}).get(name)
close = lambda a, b, tol=1e-6: all(abs(x - y) <= tol for x, y in zip(a, b))
v = eval(sys.argv[2], {"d": d, "abs": abs, "lum": lum, "w": w, "close": close, "math": math,
                       "json": json})
if isinstance(v, bool):
    sys.exit(0 if v else 1)
print(v)
PY
}

# wait_until DESCRIPTION EXPRESSION: polls the layout until the expression holds.
wait_until() {
    local deadline=$((SECONDS + TIMEOUT_S))
    until layout "$2" >/dev/null 2>&1; do
        kill -0 "$EDITOR_PID" 2>/dev/null || fail "the editor exited while waiting for $1"
        ((SECONDS < deadline)) || fail "timed out after $TIMEOUT_S s waiting for $1"
        sleep 0.1
    done
}

wait_for_file() {
    local deadline=$((SECONDS + TIMEOUT_S))
    until [ -s "$1" ]; do
        kill -0 "$EDITOR_PID" 2>/dev/null || fail "the editor exited while waiting for $1"
        ((SECONDS < deadline)) || fail "timed out after $TIMEOUT_S s waiting for $1"
        sleep 0.1
    done
}

# Moves the pointer to window pixel (x, y) and waits until the editor has seen it there, so a
# following press lands where intended even when frames are slow.
move_to() {
    xdotool mousemove --window "$WID" "$1" "$2"
    wait_until "the pointer at ($1, $2)" \
        "d['mouse'] is not None and abs(d['mouse'][0] - $1) < 1 and abs(d['mouse'][1] - $2) < 1"
}

# wait_frames N: until the editor has drawn N more frames, so the layout file shows the effect of
# the input sent before (under load a frame can take longer than any fixed sleep).
wait_frames() {
    local f
    f=$(layout "d['frame']")
    wait_until "$1 more frames" "d['frame'] >= $f + $1"
}

# scroll_into_view WIDGET PANEL: scrolls the panel (its rectangle recorded as panel.PANEL) with
# the mouse wheel until the recorded widget lies inside it, with a margin of 4 pixels.
scroll_into_view() {
    local widget=$1 panel=panel.$2 x y i where
    for ((i = 0; i < 60; i++)); do
        where=$(layout "'in' if w('$widget')[1] >= w('$panel')[1] + 24 and w('$widget')[3] <= w('$panel')[3] - 4 else ('down' if w('$widget')[3] > w('$panel')[3] - 4 else 'up')") ||
            fail "no $widget or $panel in the layout"
        [ "$where" = in ] && return 0
        read -r x y < <(layout "'%d %d' % ((w('$panel')[0] + w('$panel')[2]) / 2, (w('$panel')[1] + w('$panel')[3]) / 2)")
        move_to "$x" "$y"
        if [ "$where" = down ]; then xdotool click 5; else xdotool click 4; fi
        wait_frames 2
    done
    fail "could not scroll $widget into $panel"
}

# widget_point NAME [DX]: a point inside the named widget's frame, DX pixels from its left edge
# (the rectangles include the label on the right), vertically centred. Waits for the widget.
widget_point() {
    wait_until "the widget $1" "w('$1') is not None"
    layout "'%d %d' % (w('$1')[0] + ${2:-12}, round((w('$1')[1] + w('$1')[3]) / 2))"
}

# point_to NAME [DX]: moves the pointer into the named widget and makes sure the frame that saw
# the pointer there drew the widget under it (a popup is placed only a frame after it appears).
point_to() {
    local x y attempt
    # Widgets of the inspector and the library may lie below their panel's fold (the left column
    # holds three panels): scroll them in first.
    case "$1" in
        inspector.* | library.* | measure.*) wait_until "the widget $1" "w('$1') is not None"; scroll_into_view "$1" "${1%%.*}" ;;
    esac
    for attempt in 1 2 3 4 5; do
        read -r x y < <(widget_point "$1" "${2:-12}")
        move_to "$x" "$y"
        layout "w('$1') is not None and w('$1')[0] <= $x < w('$1')[2] and w('$1')[1] <= $y < w('$1')[3]" &&
            return 0
    done
    fail "the widget $1 does not stay under the pointer"
}

# click_widget NAME [DX]: a left click inside the named widget.
click_widget() {
    point_to "$1" "${2:-12}"
    xdotool mousedown 1
    wait_until "the press on $1" "d['mouse_down']"
    xdotool mouseup 1
    wait_until "the release on $1" "not d['mouse_down']"
}

# window_point "[X, Y, Z]" SCENE: the window pixel (rounded) where a world point (metres) shows,
# through SCENE's camera and the viewport and render size of the layout file.
window_point() {
    python3 - "$LAYOUT" "$2" "$1" "$E2E_LIB" <<'PY'
import json, sys
sys.path.insert(0, sys.argv[4])
from camera import project
d = json.load(open(sys.argv[1]))
cam = json.load(open(sys.argv[2]))["camera"]
x, y = project(json.loads(sys.argv[3]), {"camera": cam, "render_size": d["render_size"]})
vx, vy, vw, vh = d["viewport"]
print(round(vx + x * vw / d["render_size"][0]), round(vy + y * vh / d["render_size"][1]))
PY
}

# raised_demo_scene SOURCE OUT: the demo scene with the camera raised to see the ceiling panel,
# and the panel turned so its short side runs across the image.
raised_demo_scene() {
    python3 - "$1/resources/scenes/demo.json" "$2" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["camera"] = {"position": [0.0, 1.3, 2.6], "target": [0.0, 1.9, -1.0], "fov_deg": 60}
scene["luminaires"][0]["c0"] = [0, 0, 1]
json.dump(scene, open(sys.argv[2], "w"), indent=1)
PY
}

# e2e_start_xvfb WxH: an X server that picks a free display number itself and reports it once
# it is ready.
e2e_start_xvfb() {
    # A file of its own per server: a second server must not be read from the first's file.
    local file
    file=$(mktemp "$TMP/display.XXXXXX")
    Xvfb -displayfd 5 -screen 0 "${1}x24" -nolisten tcp 5>"$file" >/dev/null 2>>"$TMP/xvfb.log" &
    XVFB_PID=$!
    local deadline=$((SECONDS + 30))
    until [ -s "$file" ]; do
        kill -0 "$XVFB_PID" 2>/dev/null || fail "Xvfb did not start: $(cat "$TMP/xvfb.log")"
        ((SECONDS < deadline)) || fail "Xvfb did not report a display within 30 s"
        sleep 0.1
    done
    export DISPLAY=":$(head -n 1 "$file")"
    unset WAYLAND_DISPLAY  # GLFW must use the X server above
    log "Xvfb on $DISPLAY"
}

# e2e_mean IMAGE X Y: mean grey level (0-255) of the BOX x BOX square centred on (X, Y).
e2e_mean() {
    convert "$1" -crop "${BOX}x${BOX}+$(($2 - BOX / 2))+$(($3 - BOX / 2))" +repage \
        -colorspace Gray -format '%[fx:mean*255]' info:
}

# e2e_spot_moved BEFORE.png AFTER.png OX OY PX PY LEVELS: between the two images the square at
# the old place (OX, OY) got darker and the one at the new place (PX, PY) brighter, each by more
# than LEVELS grey levels.
e2e_spot_moved() {
    local ob oa nb na
    ob=$(e2e_mean "$1" "$3" "$4")
    oa=$(e2e_mean "$2" "$3" "$4")
    nb=$(e2e_mean "$1" "$5" "$6")
    na=$(e2e_mean "$2" "$5" "$6")
    log "old place ($3, $4): $ob -> $oa; new place ($5, $6): $nb -> $na"
    python3 - "$ob" "$oa" "$nb" "$na" "$7" <<'PY' || fail "the lit spot did not move"
import sys
ob, oa, nb, na, levels = map(float, sys.argv[1:])
ok = True
if not ob - oa > levels:
    print(f"the old place did not get darker by > {levels:g} levels ({ob:.1f} -> {oa:.1f})"); ok = False
if not na - nb > levels:
    print(f"the new place did not get brighter by > {levels:g} levels ({nb:.1f} -> {na:.1f})"); ok = False
sys.exit(0 if ok else 1)
PY
}

# e2e_start_editor SCENE WxH FIRST_LAYOUT_CONDITION: starts the editor on SCENE (screenshots into
# SHOTS, layout into LAYOUT), waits until the layout satisfies the condition, and finds and
# focuses its window (WID). E2E_EDITOR_ARGS adds options (e.g. --autosave-seconds 2).
e2e_start_editor() {
    # The editor's own limit (a hung editor ends); each step waits on the layout file's state.
    LIBGL_ALWAYS_SOFTWARE=1 timeout 840 "$CANDELA" edit "$1" --size "$2" \
        --screenshot-dir "$SHOTS" --layout-file "$LAYOUT" --quit-after-frames 1000000 \
        ${E2E_EDITOR_ARGS:-} >>"$TMP/editor.log" 2>&1 &
    EDITOR_PID=$!
    wait_until "the editor's first layout" "$3"
    # This editor's window (GLFW sets _NET_WM_PID): the X server may show another's too.
    local child
    child=$(pgrep -P "$EDITOR_PID" | head -n 1)
    WID=$(timeout 30 xdotool search --sync --onlyvisible --pid "${child:-$EDITOR_PID}" --name Candela | head -n 1) ||
        fail "no window named Candela"
    [ -n "$WID" ] || fail "no window named Candela"
    xdotool windowfocus "$WID" 2>/dev/null || true
}

# e2e_drag NAME X Y DX: presses on luminaire NAME at window pixel (X, Y), drags it DX pixels to
# the right in ten steps, waits until it follows the mouse there, and releases. Sets NX.
e2e_drag() {
    local name=$1 x=$2 y=$3 dx=$4 i
    move_to "$x" "$y"
    xdotool mousedown 1
    wait_until "\"$name\" to be picked and dragged" "d['dragging'] and d['selected'] == '$name'"
    # Ctrl held once the drag is under way (pressed with the click it would add to the selection):
    # the luminaire moves freely, off the placement grid, and follows the mouse to the pixel.
    # E2E_DRAG_GRID=PX leaves it on the grid: it follows to within PX pixels (a grid cell's size).
    local tolerance=${E2E_DRAG_GRID:-3}
    [ -z "${E2E_DRAG_GRID:-}" ] && xdotool keydown ctrl
    for ((i = 1; i <= 10; i++)); do
        xdotool mousemove --window "$WID" $((x + dx * i / 10)) "$y"
        sleep 0.05
    done
    NX=$((x + dx))
    move_to "$NX" "$y"
    wait_until "\"$name\" to follow the mouse to ($NX, $y)" \
        "abs(lum('$name')['screen'][0] - $NX) < $tolerance and abs(lum('$name')['screen'][1] - $y) < $tolerance"
    xdotool mouseup 1
    [ -z "${E2E_DRAG_GRID:-}" ] && xdotool keyup ctrl
    return 0
}
