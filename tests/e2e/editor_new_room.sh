#!/usr/bin/env bash
# End-to-end test of a designer's project made in the editor without writing JSON, with real X
# input under Xvfb:
#   1. Ctrl+N opens the room dialog; the room's name and width are typed, three windows and a door
#      added with the dialog's buttons; Create makes an untitled scene of that room with its task
#      area (500 lx, U0 0.6);
#   2. Ctrl+L opens the layout dialog; the luminaire is picked from its list, Propose computes the
#      layout on a worker while the editor draws on, and Accept places the grid as one undo step;
#   3. Ctrl+S asks where the untitled scene goes and saves it; the file holds the room, its four
#      openings, the task area and the layout, and `candela surfaces` on it meets the target.
# Usage: bash tests/e2e/editor_new_room.sh /path/to/candela /path/to/tests
set -euo pipefail

CANDELA=${1:?usage: editor_new_room.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_new_room.sh /path/to/candela /path/to/tests}
SOURCE=$(cd "$TESTS/.." && pwd)
TIMEOUT_S=300

E2E_NAME=editor_new_room
source "$(dirname "$0")/lib/harness.sh"
e2e_setup
e2e_start_xvfb 1280x800

# Started on a bare floor (no light to refine): the frames stay quick while the dialogs work.
echo '{"geometry": [{"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [4, 4]}}],
 "camera": {"position": [0, 2, 4], "target": [0, 0, 0]}}' >"$TMP/start.json"
e2e_start_editor "$TMP/start.json" 1280x800 "d['frame'] >= 2"

# --- 1. File > New: the room dialog ------------------------------------------------------------
xdotool key --window "$WID" ctrl+n
wait_until "the room dialog, its name field focused" "w('room.create') is not None and d['typing']"
xdotool key --window "$WID" ctrl+a
xdotool type --window "$WID" --delay 20 "Classroom"
wait_frames 2
# A number typed into the width: Ctrl+click makes the field take text.
point_to room.width 30
xdotool keydown ctrl
xdotool mousedown 1
wait_until "the press on the width" "d['mouse_down']"
xdotool mouseup 1
xdotool keyup ctrl
wait_until "the width field taking text" "d['typing']"
xdotool key --window "$WID" ctrl+a
xdotool type --window "$WID" --delay 20 "10"
xdotool key --window "$WID" Return
wait_frames 2
for button in room.add_window room.add_window room.add_window room.add_door; do
    click_widget "$button"
    wait_frames 2
done
click_widget room.create
wait_until "the new room" \
    "d['scene_path'] == '' and d['geometry'] == ['Classroom (room) #0'] and len(d['luminaires']) == 0 and len(d['task_areas']) == 1"
log "new scene: $(layout "d['geometry']"), task area $(layout "d['task_areas'][0]")"
layout "d['task_areas'][0]['lo'] == [-5.0, -4.0] and d['task_areas'][0]['hi'] == [5.0, 4.0]" ||
    fail "the task area is not the 10 x 8 m floor"

# --- 2. The layout dialog ----------------------------------------------------------------------
xdotool key --window "$WID" ctrl+l
wait_until "the layout dialog" "w('layout.propose') is not None"
click_widget layout.luminaire
click_widget layout.file:prolicht-e30.ldt
wait_frames 2
click_widget layout.propose
wait_until "the proposal to be computed (on a worker: the editor draws on)" \
    "d['layout_job'] is not None and d['layout_job']['done']"
layout "d['layout_job']['error'] == '' and d['layout_job']['count'] > 0" ||
    fail "no layout: $(layout "d['layout_job']")"
COUNT=$(layout "d['layout_job']['count']")
click_widget layout.accept
wait_until "the layout's $COUNT luminaires" \
    "len(d['luminaires']) == $COUNT and d['undo'].startswith('Layout of $COUNT') and d['undo_steps'] == 1"
log "accepted: $COUNT luminaires in one undo step"
xdotool key --window "$WID" F12  # the window, for a person to look at (CANDELA_E2E_KEEP=1)
wait_until "the window image" "d['window_images'] >= 1"

# --- 3. Save the untitled scene ------------------------------------------------------------------
xdotool key --window "$WID" ctrl+s
wait_until "the Save scene as dialog's path field" "d['typing']"
xdotool key --window "$WID" ctrl+a
xdotool type --window "$WID" --delay 10 "$TMP/classroom.json"
xdotool key --window "$WID" Return
wait_for_file "$TMP/classroom.json"
wait_until "the scene saved" "d['scene_path'] != '' and not d['dirty']"
layout "d['error'] == ''" || fail "the editor reported an error: $(layout "d['error']")"
kill "$EDITOR_PID" 2>/dev/null || true  # done with it: its frames would slow the check below
wait "$EDITOR_PID" 2>/dev/null || true
EDITOR_PID=

python3 - "$TMP/classroom.json" "$COUNT" <<'PY' || fail "the saved scene is not the room made in the dialog"
import json, sys
doc = json.load(open(sys.argv[1]))
room = doc["geometry"][0]["room"]
assert room["name"] == "Classroom", room
assert room["floor"] == [[-5, -4], [5, -4], [5, 4], [-5, 4]], room["floor"]
assert room["height"] == 3, room["height"]
types = [o["type"] for o in room["openings"]]
assert types == ["window"] * 3 + ["door"], types
assert doc["task_areas"][0]["required"] == {"em_lx": 500, "u0": 0.6}, doc["task_areas"]
(layout,) = doc["layouts"]
assert layout["grid"][0] * layout["grid"][1] >= int(sys.argv[2]), layout
assert "luminaires" not in doc or not doc["luminaires"], "the layout's luminaires were written one by one"
print(f"editor_new_room: saved {len(open(sys.argv[1]).read().splitlines())} lines, layout {layout['grid']}")
PY
"$CANDELA" surfaces "$TMP/classroom.json" >"$TMP/surfaces.txt" 2>&1 || fail "candela surfaces: $(cat "$TMP/surfaces.txt")"
grep -A4 "^Classroom (task area)" "$TMP/surfaces.txt" | grep -q "required: Em >= 500 lx, U0 >= 0.60: PASS" ||
    fail "the layout does not meet 500 lx / 0.6: $(grep -A4 '^Classroom (task area)' "$TMP/surfaces.txt")"
log "candela surfaces: $(grep -A3 '^Classroom (task area)' "$TMP/surfaces.txt" | grep ' Em ' | sed 's/^ *//')"
PASSED=1
log "passed"
