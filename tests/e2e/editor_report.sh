#!/usr/bin/env bash
# End-to-end test of File > Export report (issue 21, part 7), with real X input under Xvfb, on the
# shipped office:
#   1. Ctrl+E opens the "Export report" dialog with the PDF beside the scene; Return exports it
#      (the surfaces and the UGR on a thread while the editor keeps drawing);
#   2. the PDF, read back by poppler's pdftotext, has the report's sections, the desk's summary
#      as `candela surfaces` prints it and the observers' UGR as `candela glare` does, and its
#      first page shows the viewport's image in colour (pdftoppm).
# Usage: bash tests/e2e/editor_report.sh /path/to/candela /path/to/tests
set -euo pipefail

CANDELA=${1:?usage: editor_report.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_report.sh /path/to/candela /path/to/tests}
SOURCE=$(cd "$TESTS/.." && pwd)
TIMEOUT_S=240

E2E_NAME=editor_report
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
"$CANDELA" surfaces "$TMP/office.json" >"$TMP/surfaces.txt" 2>&1 || fail "candela surfaces: $(cat "$TMP/surfaces.txt")"
"$CANDELA" glare "$TMP/office.json" --spp 1024 >"$TMP/glare.txt" 2>&1 || fail "candela glare: $(cat "$TMP/glare.txt")"

e2e_start_editor "$TMP/office.json" 1280x800 "len(d['luminaires']) == 6 and d['frame'] >= 2"
xdotool key ctrl+e
wait_until "the Export report dialog's path field" "d['typing']"
sleep 0.3
xdotool key Return
wait_until "the report to be written" "d['reports'] >= 1 and not d['report_running']"
PDF="$TMP/office-report.pdf"
[ -s "$PDF" ] || fail "no report at $PDF"
layout "d['error'] == ''" || fail "the editor reported an error: $(layout "d['error']")"
pdftotext -layout "$PDF" "$TMP/report.txt"
for section in "Lighting report" "Luminaire schedule" "Polar diagram" "Desk (task area)" \
               "Calculation points" "Glare: UGR (CIE 117)" "the editor's viewport"; do
  grep -qF "$section" "$TMP/report.txt" || fail "the report has no \"$section\""
done
desk=$(grep -m1 -E "^  Em " "$TMP/surfaces.txt" | sed 's/^ *//')
grep -qF "$desk" "$TMP/report.txt" || fail "the report's desk differs from candela surfaces' \"$desk\""
for ugr in $(sed -n 's/^  UGR \([0-9.]*\),.*/\1/p' "$TMP/glare.txt"); do
  grep -qE " $ugr +19 +(PASS|FAIL)" "$TMP/report.txt" || fail "the report has not candela glare's UGR $ugr"
done
pdftoppm -r 40 -f 1 -l 1 -png "$PDF" "$TMP/page"
saturation=$(convert "$TMP"/page-*1.png -colorspace HSL -channel G -separate -format "%[fx:maxima]" info:)
awk -v s="$saturation" 'BEGIN { exit !(s > 0.1) }' || fail "the first page shows no coloured view (saturation $saturation)"
log "report: $(pdfinfo "$PDF" | sed -n 's/^Pages: */pages /p'), desk \"$desk\""
PASSED=1
log "passed"
