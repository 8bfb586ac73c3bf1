#!/usr/bin/env bash
# Two editors on one scene lose nothing (real X input; each editor on an X server of its own):
#   1. editors A and B open the same scene (autosave every 2 s) and move its ceiling panel by
#      different amounts: each autosaves to its own file;
#   2. A saves: the scene holds A's edit, B's autosave is still there;
#   3. B saves: the scene changed on disk since B opened it, so B asks instead of overwriting;
#   4. B is killed (SIGKILL) with the question open: its autosave survives;
#   5. B starts again: its autosave is offered and restored; saving asks again (the scene changed
#      after B's edits began) and "Save mine as..." writes B's edit to a new file.
# In the end the scene holds A's edit, the new file B's, and no autosave is left.
# Usage: bash tests/e2e/editor_two_editors.sh /path/to/candela /path/to/tests
set -euo pipefail

CANDELA=${1:?usage: editor_two_editors.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_two_editors.sh /path/to/candela /path/to/tests}
SOURCE=$(cd "$TESTS/.." && pwd)
TIMEOUT_S=240

E2E_NAME=editor_two_editors
source "$(dirname "$0")/lib/harness.sh"
e2e_setup
raised_demo_scene "$SOURCE" "$TMP/scene.json"
SCENE=$TMP/scene.json
MINE=$TMP/scene-b.json
export E2E_EDITOR_ARGS="--autosave-seconds 2"

e2e_start_xvfb 1280x800
DISPLAY_A=$DISPLAY
E2E_OTHER_PIDS=$XVFB_PID
e2e_start_xvfb 1280x800
DISPLAY_B=$DISPLAY
E2E_OTHER_PIDS="$E2E_OTHER_PIDS $XVFB_PID"

# use A|B: the harness's helpers act on that editor (its X server, layout file and window).
use() {
    eval "DISPLAY=\$DISPLAY_$1 LAYOUT=\$TMP/layout-$1.json EDITOR_PID=\${PID_$1:-} WID=\${WID_$1:-}"
    export DISPLAY
}
start() {
    use "$1"
    rm -f "$LAYOUT"
    e2e_start_editor "$SCENE" 1280x800 "len(d['luminaires']) > 0 and d['frame'] >= 2"
    eval "PID_$1=\$EDITOR_PID WID_$1=\$WID"
    E2E_OTHER_PIDS="$E2E_OTHER_PIDS $EDITOR_PID"
}
# move_panel DX: drags the ceiling panel DX pixels and prints its new position.
move_panel() {
    local x y name
    wait_until "a visible luminaire" "d['luminaires'][0]['screen'] is not None"
    read -r x y < <(layout "'%d %d' % tuple(round(c) for c in d['luminaires'][0]['screen'])")
    name=$(layout "d['luminaires'][0]['name']")
    e2e_drag "$name" "$x" "$y" "$1" >&2
    wait_until "the end of the drag" "not d['dragging'] and d['dirty']"
    layout "json.dumps(d['luminaires'][0]['position'])"
}
# position_in FILE: the ceiling panel's position in a scene file.
position_in() {
    python3 -c "import json, sys; print(json.dumps(json.load(open(sys.argv[1]))['luminaires'][0]['position']))" "$1"
}
autosave_files() { compgen -G "$TMP/.scene.autosave*.json" || true; }
# autosave_holding POSITION: waits until some autosave beside the scene holds it.
autosave_holding() {
    local deadline=$((SECONDS + TIMEOUT_S)) f
    while ((SECONDS < deadline)); do
        for f in $(autosave_files); do
            [ "$(position_in "$f" 2>/dev/null)" = "$1" ] && return 0
        done
        sleep 0.2
    done
    fail "no autosave holds $1 (autosaves: $(autosave_files))"
}

# --- 1. Two editors, two edits, two autosaves ----------------------------------------------------
start A
start B
use A
MOVED_A=$(move_panel 150)
use B
MOVED_B=$(move_panel -120)
[ "$MOVED_A" != "$MOVED_B" ] || fail "the two edits should differ"
autosave_holding "$MOVED_A"
autosave_holding "$MOVED_B"
log "A moved the panel to $MOVED_A, B to $MOVED_B; autosaves: $(autosave_files | wc -l)"

# --- 2. A saves ----------------------------------------------------------------------------------
use A
xdotool key --window "$WID" ctrl+s
wait_until "A's save" "not d['dirty']"
[ "$(position_in "$SCENE")" = "$MOVED_A" ] || fail "the scene does not hold A's edit"
autosave_holding "$MOVED_B"  # A's save left B's autosave alone
log "A saved; B's autosave is still there"

# --- 3. B saves: it asks -------------------------------------------------------------------------
use B
xdotool key --window "$WID" ctrl+s
wait_until "B's question about the changed file" "d['conflict'] and w('conflict.save_as') is not None"
[ "$(position_in "$SCENE")" = "$MOVED_A" ] || fail "B's save replaced A's edit without asking"
log "B asks: $(layout "d['status']")"

# --- 4. B crashes --------------------------------------------------------------------------------
CHILD=$(pgrep -P "$EDITOR_PID" || true)
[ -n "$CHILD" ] || fail "no editor process under $EDITOR_PID"
kill -KILL "$CHILD"
wait "$EDITOR_PID" 2>/dev/null || true
PID_B=
autosave_holding "$MOVED_B"
[ "$(position_in "$SCENE")" = "$MOVED_A" ] || fail "the scene changed when B was killed"

# --- 5. B again: restore, save as ----------------------------------------------------------------
start B
wait_until "B's autosave offered" "d['autosave_offers'] == 1"
click_widget autosave.restore0
wait_until "B's restored edit" "json.dumps(d['luminaires'][0]['position']) == '$MOVED_B' and d['dirty']"
xdotool key --window "$WID" ctrl+s
wait_until "B's question again" "d['conflict'] and w('conflict.save_as') is not None"
click_widget conflict.save_as
wait_until "the Save As field" "d['typing']"
xdotool key --window "$WID" ctrl+a
wait_frames 2
xdotool type --window "$WID" --delay 30 "$MINE"
wait_frames 2
xdotool key --window "$WID" Return
wait_until "B's save as" "not d['dirty']"
[ "$(position_in "$MINE")" = "$MOVED_B" ] || fail "$MINE does not hold B's edit"
[ "$(position_in "$SCENE")" = "$MOVED_A" ] || fail "the scene lost A's edit"
[ -z "$(autosave_files)" ] || fail "autosaves left after both saved: $(autosave_files)"
# A's editor is still running and clean.
use A
layout "not d['dirty']" || fail "A shows unsaved edits"

PASSED=1
echo "editor_two_editors: PASS"
