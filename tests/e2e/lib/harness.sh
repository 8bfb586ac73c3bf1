# The editor end-to-end tests' shared harness (sourced, not run; the e2e glob only picks up
# tests/e2e/*.sh). The caller sets E2E_NAME (the prefix of its messages) and TIMEOUT_S (longest
# wait for any one step), then calls e2e_setup, which makes TMP (with LAYOUT and SHOTS paths),
# checks the tools and installs the cleanup. Later, e2e_start_xvfb WxH starts an X server and
# exports DISPLAY; the caller starts the editor with --layout-file "$LAYOUT", sets EDITOR_PID and
# WID, and sets PASSED=1 at the end. CANDELA_E2E_KEEP=1 keeps TMP after a pass too.

XVFB_PID=
EDITOR_PID=
PASSED=0
T0=$SECONDS

log() { echo "$E2E_NAME: [$((SECONDS - T0)) s] $*"; }

e2e_cleanup() {
    [ -n "$EDITOR_PID" ] && kill "$EDITOR_PID" 2>/dev/null || true
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

# e2e_start_xvfb WxH: an X server that picks a free display number itself and reports it once
# it is ready.
e2e_start_xvfb() {
    Xvfb -displayfd 5 -screen 0 "${1}x24" -nolisten tcp 5>"$TMP/display" >/dev/null 2>"$TMP/xvfb.log" &
    XVFB_PID=$!
    local deadline=$((SECONDS + 30))
    until [ -s "$TMP/display" ]; do
        kill -0 "$XVFB_PID" 2>/dev/null || fail "Xvfb did not start: $(cat "$TMP/xvfb.log")"
        ((SECONDS < deadline)) || fail "Xvfb did not report a display within 30 s"
        sleep 0.1
    done
    export DISPLAY=":$(head -n 1 "$TMP/display")"
    unset WAYLAND_DISPLAY  # GLFW must use the X server above
    log "Xvfb on $DISPLAY"
}
