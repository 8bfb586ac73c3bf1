#!/usr/bin/env bash
# Crash test of the autosave (issue 7, "Projects"), with real X input under Xvfb:
#   1. open a copy of the demo scene with the autosave every 2 s, drag the ceiling panel (an
#      unsaved edit), wait until the editor's autosave beside the scene holds the new position;
#   2. kill the editor with SIGKILL (no chance to save or clean up): the scene file is untouched;
#   3. start the editor again on the same file: it offers the autosave (nothing applied unasked);
#      Restore brings the edit back, shows the scene unsaved and says so;
#   4. Ctrl+S: the scene file now holds the edit and no autosave is left.
# Usage: bash tests/e2e/editor_autosave.sh /path/to/candela /path/to/tests
set -euo pipefail

CANDELA=${1:?usage: editor_autosave.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_autosave.sh /path/to/candela /path/to/tests}
SOURCE=$(cd "$TESTS/.." && pwd)
DRAG_PX=150
TIMEOUT_S=240

E2E_NAME=editor_autosave
source "$(dirname "$0")/lib/harness.sh"
e2e_setup
e2e_start_xvfb 1280x800

raised_demo_scene "$SOURCE" "$TMP/scene.json"
ORIGINAL=$(sha256sum "$TMP/scene.json")
# Each editor's own: $TMP/.scene.autosave-HOST-PID-START.json.
autosave_files() { compgen -G "$TMP/.scene.autosave*.json" || true; }

# --- 1. An unsaved edit, autosaved ---------------------------------------------------------------
export E2E_EDITOR_ARGS="--autosave-seconds 2"
e2e_start_editor "$TMP/scene.json" 1280x800 "len(d['luminaires']) > 0 and d['frame'] >= 2"
wait_until "a visible luminaire" "d['luminaires'][0]['screen'] is not None"
read -r LX LY < <(layout "'%d %d' % tuple(round(c) for c in d['luminaires'][0]['screen'])")
NAME=$(layout "d['luminaires'][0]['name']")
e2e_drag "$NAME" "$LX" "$LY" "$DRAG_PX"
wait_until "the end of the drag" "not d['dragging'] and d['dirty']"
MOVED=$(layout "json.dumps(d['luminaires'][0]['position'])")
log "\"$NAME\" moved to $MOVED, unsaved"
deadline=$((SECONDS + TIMEOUT_S))
until AUTOSAVE=$(autosave_files) && [ -n "$AUTOSAVE" ] && python3 -c "
import json, sys
a = json.load(open('$AUTOSAVE'))
sys.exit(0 if a['luminaires'][0]['position'] == json.loads('$MOVED') else 1)" 2>/dev/null; do
    ((SECONDS < deadline)) || fail "no autosave with the moved position beside $TMP/scene.json"
    sleep 0.2
done
log "autosave written: $AUTOSAVE"

# --- 2. SIGKILL ----------------------------------------------------------------------------------
# EDITOR_PID is the `timeout` wrapper: kill the editor itself, then the wrapper.
CHILD=$(pgrep -P "$EDITOR_PID" || true)
[ -n "$CHILD" ] || fail "no editor process under $EDITOR_PID"
kill -KILL "$CHILD"
wait "$EDITOR_PID" 2>/dev/null || true
kill -0 "$CHILD" 2>/dev/null && fail "the editor survived SIGKILL"
EDITOR_PID=
[ "$(sha256sum "$TMP/scene.json")" = "$ORIGINAL" ] || fail "the scene file changed without a save"
[ -s "$AUTOSAVE" ] || fail "the autosave did not survive the kill"
rm -f "$LAYOUT"

# --- 3. Restart: the autosave is offered, and restored on request ---------------------------------
e2e_start_editor "$TMP/scene.json" 1280x800 "len(d['luminaires']) > 0 and d['frame'] >= 2"
wait_until "the autosave offered" "d['autosave_offers'] == 1"
layout "json.dumps(d['luminaires'][0]['position']) != '$MOVED' and not d['dirty']" ||
    fail "the autosave was applied before the user chose it"
click_widget autosave.restore0
wait_until "the restored position" "json.dumps(d['luminaires'][0]['position']) == '$MOVED'"
layout "d['dirty']" || fail "the restored scene should show as unsaved"
layout "'Restored' in d['status']" || fail "the status bar does not say the edits were restored"
log "restored after the crash: $(layout "d['status']")"

# --- 4. Save: the file holds the edit, the autosave is gone --------------------------------------
xdotool key --window "$WID" ctrl+s
wait_until "the save" "not d['dirty']"
python3 -c "
import json, sys
s = json.load(open('$TMP/scene.json'))
sys.exit(0 if s['luminaires'][0]['position'] == json.loads('$MOVED') else 1)" ||
    fail "the saved scene does not hold the restored position"
[ -z "$(autosave_files)" ] || fail "an autosave is still there after saving: $(autosave_files)"

PASSED=1
echo "editor_autosave: PASS"
