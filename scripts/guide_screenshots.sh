#!/usr/bin/env bash
# Takes the user guide's images (docs/editor.md) with the editor itself (View > Save window image, F12),
# driven by real X input under Xvfb: docs/guide/{editor,preview,place,compare,wipe}.png; and the
# comparison sheet `candela render --pane ... --sheet` writes headless: docs/guide/sheet.png; and two
# pages of the classroom project's report (`candela report`): docs/guide/report.png.
# Usage: bash scripts/guide_screenshots.sh [build/candela]   (needs xvfb, xdotool, imagemagick)
set -euo pipefail
cd "$(dirname "$0")/.."
CANDELA=${1:-build/candela}
CANDELA=$(cd "$(dirname "$CANDELA")" && pwd)/$(basename "$CANDELA")
OUT=docs/guide
TIMEOUT_S=120
E2E_NAME=guide
source tests/e2e/lib/harness.sh
e2e_setup
e2e_start_xvfb 1280x720
mkdir -p "$OUT"

# The demo room with one luminaire of each kind, seen from the door. No autosave: it would be
# written beside the scene in resources/ and restored by the next run.
rm -f resources/scenes/.editor-room.autosave.json
E2E_EDITOR_ARGS="--autosave-seconds 1000000"
e2e_start_editor "$PWD/resources/scenes/editor-room.json" 1280x720 "len(d['luminaires']) == 3 and d['frame'] >= 2"
shot() {  # shot NAME: F12, then move the newest window image to docs/guide/NAME.png
    local n
    n=$(layout "d['window_images']")
    xdotool key --window "$WID" F12
    wait_until "window image $n" "d['window_images'] > $n"
    mv "$SHOTS/window-$(printf %03d "$n").png" "$OUT/$1.png"
    log "wrote $OUT/$1.png"
}

# 1. The editor after a few refinement passes.
wait_until "some refinement" "d['samples_per_pixel'] >= 32"
shot editor

# 2. The live preview, mid-orbit (the mouse held down on empty floor).
read -r VX VY VW VH < <(layout "'%d %d %d %d' % tuple(d['viewport'])")
CX=$((VX + VW / 2)); CY=$((VY + VH * 4 / 5))
move_to "$CX" "$CY"
xdotool mousedown 1
for i in 1 2 3 4 5 6; do xdotool mousemove --window "$WID" $((CX + 4 * i)) "$CY"; sleep 0.1; done
wait_until "the preview" "d['preview']['active']"
wait_frames 3
shot preview
xdotool mouseup 1
xdotool key --window "$WID" ctrl+z 2>/dev/null || true  # orbits are not undone; harmless

# 3. The pendant placed on the back wall ("Place on a surface", then a click on the wall).
click_widget "outline.luminaire:Linear pendant"
wait_until "the pendant selected" "d['selected'] == 'Linear pendant'"
click_widget outline.place
wait_frames 2
move_to $((VX + VW / 2)) $((VY + VH / 3))
xdotool click 1
wait_until "the placement" "d['undo'] is not None and d['undo'].startswith('Place')"
wait_until "refinement after the placement" "d['samples_per_pixel'] >= 32"
shot place
xdotool key --window "$WID" ctrl+z  # the pendant back above the table for the comparison
wait_until "the placement undone" "d['undo_steps'] == 0"

# 4. Two panes: the scene's techniques (A) against the drag preview's (B), the accuracy plot open.
click_widget viewport.two
wait_until "both panes measured" "d['compare']['layout'] == 'two' and all(p['measured'] for p in d['compare']['panes'])"
click_widget viewport.plot
wait_until "the plot" "d['compare']['plot_open']"
wait_until "a second measurement of each pane" "all(len(p['series']) >= 2 for p in d['compare']['panes'])"
shot compare

# 5. The wipe with error maps.
click_widget viewport.plot
click_widget viewport.wipe
click_widget viewport.error_map
wait_until "the wipe's panes measured" "d['compare']['layout'] == 'wipe' and d['compare']['error_map'] and all(p['measured'] for p in d['compare']['panes'])"
move_to $((VX + VW / 3)) $((VY + VH / 2))  # no tooltip in the picture
wait_frames 3
shot wipe

# 6. The same comparison headless, four panes, as a labelled sheet (the editor closed first: its
# reference would share the two cores and inflate the sheet's times, which are wall times on
# llvmpipe).
kill "$EDITOR_PID" 2>/dev/null || true
wait "$EDITOR_PID" 2>/dev/null || true
EDITOR_PID=""
"$CANDELA" render "$PWD/resources/scenes/editor-room.json" --sheet "$TMP/sheet" --pane "" \
    --pane "precomputed-global,scattered" --pane "granier2003,point" --pane "uniform-restricted,mc-poisson-24" \
    --size 320x180 --spp 64 --reference-spp 256
cp "$TMP/sheet/sheet-000.png" "$OUT/sheet.png"
log "wrote $OUT/sheet.png"

# 7. Two pages of the classroom project's report, side by side: its cover and its task area.
"$CANDELA" report "$PWD/resources/scenes/classroom-project.json" --out "$TMP/report.pdf" \
    --view-size 640x360 --view-spp 8
# The task area's page: where the contents (page 2) say the calculation surfaces start.
surfaces=$(pdftotext -f 2 -l 2 -layout "$TMP/report.pdf" - |
    sed -n 's/^ *Calculation surfaces.* \([0-9][0-9]*\)$/\1/p')
pdftoppm -r 60 -f 1 -l 1 -singlefile -png "$TMP/report.pdf" "$TMP/report-cover"
pdftoppm -r 60 -f "$surfaces" -l "$surfaces" -singlefile -png "$TMP/report.pdf" "$TMP/report-surface"
convert "$TMP/report-cover.png" "$TMP/report-surface.png" -bordercolor gray70 -border 1 +append \
    "$OUT/report.png"
log "wrote $OUT/report.png"
PASSED=1
