#!/usr/bin/env bash
# `candela edit` without a display renders the scene's screenshot offscreen with what the window
# would show: direct and interreflected light. A panel in the middle of a closed white room
# faces +x; the camera looks the other way, at the wall behind it, which no light reaches
# directly: the image is black with direct light alone and lit with the interreflection.
set -uo pipefail
binary=$1
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cat >"$tmp/room.json" <<'JSON'
{"geometry": [{"name": "Room", "box": {"center": [0, 1.5, 0], "size": [4, 3, 4], "inside": true},
               "albedo": [0.7, 0.7, 0.7]}],
 "luminaires": [{"type": "lambertian-rect", "name": "Panel", "size": [0.6, 0.6],
                 "radiance": [100, 100, 100], "position": [0, 1.5, 0], "aim": [1, 0, 0],
                 "technique": "analytic"}],
 "camera": {"position": [0.5, 1.5, 0], "target": [-2, 1.5, 0], "fov_deg": 60}}
JSON
out=$(cd "$tmp" && env -u DISPLAY -u WAYLAND_DISPLAY "$binary" edit room.json 2>&1)
check "edit without a display exits 0: $out" '[ $? -eq 0 ]'
check "it says the light includes the interreflection: $out" 'grep -q "offscreen (960x540, .*), direct and interreflected light ([0-9]* patches)" <<<"$out"'
mean=$(oiiotool --stats "$tmp/candela-screenshots/shot-000.exr" 2>/dev/null | sed -n 's/^ *Stats Avg: \([0-9.e+-]*\) .*/\1/p' | head -1)
# The wall behind the panel gets only reflected light: about rho / (1 - rho) of the room's mean
# direct irradiance over pi, tens of W/m2 sr here; any of it shows the interreflection, none of
# it (0) is direct light alone.
check "the wall behind the panel is lit (mean radiance ${mean:-none} W/m2 sr)" 'python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) > 1.0 else 1)" "${mean:-0}"'

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
