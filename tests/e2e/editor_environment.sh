#!/usr/bin/env bash
# End-to-end test of the editor's Environment section with real X input events under Xvfb:
#   1. click the solar-time slider near its right end   -> the time of day changes, and the sky's
#      sun sits where an independent solar-position formula (below, in Python) puts it
#   2. press Play, then Pause                            -> the time advances and the sun moves
#      while playing; both stand still after Pause
#   3. open "Samples for a pixel", tick "Pick a pixel", click the box's front face in the viewport
#                                                        -> the chart's normal is +Z and its
#      point lies on that face; pick again on the floor -> normal +Y, point at y = 0
#   4. the chart's selection for the +Z normal puts no sample on the -Z face (its table).
# Usage: bash tests/e2e/editor_environment.sh /path/to/candela /path/to/tests
# Like the other e2e tests it polls the editor's --layout-file; CANDELA_E2E_KEEP=1 keeps the
# temporary folder (layout, editor log, window.png).
set -euo pipefail

CANDELA=${1:?usage: editor_environment.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_environment.sh /path/to/candela /path/to/tests}
TIMEOUT_S=240

E2E_NAME=editor_environment
source "$(dirname "$0")/lib/harness.sh"
e2e_setup
e2e_start_xvfb 1400x900

# A floor, a unit box on it and a small clear sky (fast to remake every frame while playing).
cat >"$TMP/scene.json" <<'EOF'
{"geometry": [{"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [6, 6]}, "albedo": [0.5, 0.5, 0.5]},
              {"box": {"center": [0, 0.5, 0], "size": [1, 1, 1]}, "albedo": [0.5, 0.5, 0.5]}],
 "environment": {"sky": {"sun_elevation_deg": 30, "sun_azimuth_deg": 120, "turbidity": 3, "resolution": 128}},
 "camera": {"position": [0, 4, 5], "target": [0, 0, 0], "fov_deg": 50}}
EOF

e2e_start_editor "$TMP/scene.json" 1400x900 "d['frame'] >= 2 and w('environment.time') is not None"

# click_along NAME [FX]: clicks the centre of the named widget, or the point a fraction FX of the
# way along it (a slider at a value), scrolled into the Render panel first.
click_along() {
    local name=$1 fx=${2:-0.5} x y
    scroll_into_view "$name" render
    read -r x y < <(layout "'%d %d' % ((w('$name')[0] + $fx * (w('$name')[2] - w('$name')[0])), (w('$name')[1] + w('$name')[3]) / 2)")
    move_to "$x" "$y"
    xdotool click 1
}

# The solar position in the textbook form (altitude from the declination and hour angle, then
# the azimuth from north by the spherical law of cosines, east of north in the afternoon), not
# the editor's east-north-up vector: prints elevation and the scene's azimuth (phi from +X
# towards +Z, with north = -Z and east = +X) in degrees.
SUN_PY='
import math
def sun(lat, day, hours):
    dec = math.radians(23.45 * math.sin(math.radians(360 * (284 + day) / 365)))
    h = math.radians(15 * (hours - 12))
    lat = math.radians(lat)
    alt = math.asin(math.sin(lat) * math.sin(dec) + math.cos(lat) * math.cos(dec) * math.cos(h))
    c = (math.sin(dec) - math.sin(alt) * math.sin(lat)) / (math.cos(alt) * math.cos(lat))
    az_north = math.acos(max(-1.0, min(1.0, c)))
    if h > 0:
        az_north = 2 * math.pi - az_north  # afternoon: the sun is west of the meridian
    # Direction east = sin(az), north = cos(az); x = east, z = -north.
    return math.degrees(alt), math.degrees(math.atan2(-math.cos(az_north), math.sin(az_north)))
'

# --- 1. The solar-time slider ------------------------------------------------------------------
h0=$(layout "d['environment_ui']['solar_hours']")
click_along environment.time 0.8
wait_until "the time of day to change" "abs(d['environment_ui']['solar_hours'] - $h0) > 1"
sleep 0.5
layout "d['environment_ui']" >"$TMP/time.txt"
log "after the click: $(cat "$TMP/time.txt"); sky $(layout "d['environment']['sky']")"
python3 - "$LAYOUT" <<EOF || fail "the sun is not where the time of day puts it"
import json, sys
$SUN_PY
d = json.load(open(sys.argv[1]))
ui, sky = d["environment_ui"], d["environment"]["sky"]
assert 17.0 < ui["solar_hours"] < 21.0, f"clicked at 80 % of 0-24 h, got {ui['solar_hours']}"
el, az = sun(ui["latitude_deg"], ui["day_of_year"], ui["solar_hours"])
print(f"expected elevation {el:.2f} azimuth {az:.2f}; sky has {sky['sun_elevation_deg']:.2f} {sky['sun_azimuth_deg']:.2f}")
# Both come from the same declination (Cooper) and hour angle; 0.1 deg covers rounding.
assert abs(max(el, 0.0) - sky["sun_elevation_deg"]) < 0.1
assert abs((az - sky["sun_azimuth_deg"] + 180) % 360 - 180) < 0.1
EOF

# --- 2. Play, then Pause -----------------------------------------------------------------------
click_along environment.play
wait_until "playback to start" "d['environment_ui']['playing']"
h1=$(layout "d['environment_ui']['solar_hours']")
a1=$(layout "d['environment']['sky']['sun_azimuth_deg']")
wait_until "the time to advance while playing" "abs(d['environment_ui']['solar_hours'] - $h1) > 0.1"
wait_until "the sun to move while playing" "abs(d['environment']['sky']['sun_azimuth_deg'] - $a1) > 0.5"
click_along environment.play
wait_until "playback to stop" "not d['environment_ui']['playing']"
h2=$(layout "d['environment_ui']['solar_hours']")
sleep 1.5
h3=$(layout "d['environment_ui']['solar_hours']")
log "played from $h1 h to $h2 h; one and a half seconds after Pause: $h3 h"
[ "$h2" = "$h3" ] || fail "the time of day still moves after Pause ($h2 -> $h3)"

# --- 3. Pick pixels for the sample chart -------------------------------------------------------
click_along environment.chart 0.3
wait_until "the chart to open" "d['environment_ui']['chart']['open'] and w('environment.pick_pixel') is not None"

# Window pixel of a world point, through the layout's viewport and the renderer's camera.
to_window() {
    PYTHONPATH="$E2E_LIB" python3 - "$LAYOUT" "$TMP/scene.json" "$1" <<'EOF'
import json, sys
from camera import project
d, scene = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
p = json.loads(sys.argv[3])
vx, vy, vw, vh = d["viewport"]
x, y = project(p, {"camera": scene["camera"], "render_size": d["render_size"]})
print(round(vx + x * vw / d["render_size"][0]), round(vy + y * vh / d["render_size"][1]))
EOF
}

pick() {  # pick WORLD_POINT_JSON: arms the picker and clicks where that point shows
    local x y
    click_along environment.pick_pixel
    wait_until "the picker to arm" "d['environment_ui']['chart']['picking']"
    read -r x y < <(to_window "$1")
    move_to "$x" "$y"
    xdotool click 1
    wait_until "the pixel at ($x, $y) to be picked" \
        "not d['environment_ui']['chart']['picking'] and d['environment_ui']['chart']['picked'] and abs(d['environment_ui']['chart']['pixel'][0] - $x) < 1.5"
}

pick "[0.1, 0.6, 0.5]"   # on the box's front face (z = 0.5)
layout "d['environment_ui']['chart']" >"$TMP/chart_box.txt"
log "box face: $(cat "$TMP/chart_box.txt")"
layout "close(d['environment_ui']['chart']['normal'], [0, 0, 1], 1e-3) and abs(d['environment_ui']['chart']['point'][2] - 0.5) < 1e-3 and abs(d['environment_ui']['chart']['point'][1] - 0.6) < 0.05" ||
    fail "the pick on the box's front face gave $(cat "$TMP/chart_box.txt")"
# The chart's table for a +Z normal: the share of -Z is 0, so nothing is selected there.
wait_until "the chart's counts for the picked normal" "'-Z 0.00' in d['environment_ui']['chart']['counts']"
import -window root "$TMP/window.png" 2>/dev/null || true

pick "[1.2, 0.0, 1.4]"   # on the floor in front of the box
layout "d['environment_ui']['chart']" >"$TMP/chart_floor.txt"
log "floor: $(cat "$TMP/chart_floor.txt")"
layout "close(d['environment_ui']['chart']['normal'], [0, 1, 0], 1e-3) and abs(d['environment_ui']['chart']['point'][1]) < 1e-4" ||
    fail "the pick on the floor gave $(cat "$TMP/chart_floor.txt")"
kill -0 "$EDITOR_PID" 2>/dev/null || fail "the editor exited"

PASSED=1
echo "editor_environment: PASS"
