#!/usr/bin/env bash
# `candela info` on L3D geometry: an unpacked example folder and the same example packed as an
# .l3d archive by Python's zipfile (not Candela's code) describe the same parts and openings; the
# two-opening pendant (example_004) emits up from one object and down from the other; GLDF's
# complete container shows its variant's geometry and the object its emitter is placed at; a
# broken archive is a one-line error naming it.
set -uo pipefail
binary=$1
data="$2/data"
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
source "$2/cli/lib/expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

folder=$("$binary" info "$data/l3d/examples/example_000" 2>&1)
check "info on an L3D folder exits 0: $folder" '[ $? -eq 0 ]'
check "the cube's size in metres (README: 0.5 x 0.25 x 0.1 m): $folder" 'grep -q "size 0.5 x 0.25 x 0.1 m" <<<"$folder"'
check "its opening: $folder" 'grep -q "light-emitting object \"leo\" (part \"luminaire\"): rectangle 0.5 x 0.25 m, 0.125 m2" <<<"$folder"'

python3 - "$data/l3d/examples/example_000" "$tmp/cube.l3d" <<'PY'
import os, sys, zipfile
root, out = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
    for folder, _, files in os.walk(root):
        for f in files:
            path = os.path.join(folder, f)
            z.write(path, os.path.relpath(path, root))
PY
packed=$("$binary" info "$tmp/cube.l3d" 2>&1)
check "the packed archive describes the same geometry: $packed" '[ "$(tail -n +2 <<<"$packed")" = "$(tail -n +2 <<<"$folder")" ]'

pendant=$("$binary" info "$data/l3d/examples/example_004" 2>&1)
check "the pendant's upper object emits up: $pendant" 'grep -q "object \"leo_top\".*emitting towards (-\?0.000, -\?0.000, 1.000)" <<<"$pendant"'
check "the pendant's lower object emits down: $pendant" 'grep -q "object \"leo_bottom\".*emitting towards (-\?0.000, -\?0.000, -1.000)" <<<"$pendant"'

gldf=$("$binary" info "$data/gldf/GldfWithFilesComplete.gldf" 2>&1)
check "the complete container's geometry: $gldf" 'grep -q "geometry: .*GldfWithFilesComplete.gldf:geo/geometry.l3d, New Luminaire" <<<"$gldf" && grep -q "1 part(s), 0 joint(s) (shown at their default rotation), 92 triangles" <<<"$gldf"'
check "its emitter placed at the object LEO: $gldf" 'grep -q "the emitter is placed at light-emitting object \"LEO\"" <<<"$gldf"'

two="$data/gldf/PendantTwoEmitters.gldf"
pendant=$("$binary" info "$two" 2>&1)
check "the two-emitter pendant places each emitter at its object: $pendant" 'grep -q "placement 0 of 2: emitter \"down\"" <<<"$pendant" && grep -q "placed at light-emitting object \"leo_bottom\"" <<<"$pendant" && grep -q "placement 1 of 2: emitter \"up\"" <<<"$pendant" && grep -q "placed at light-emitting object \"leo_top\"" <<<"$pendant"'
cp "$two" "$tmp/pendant.gldf"
cat > "$tmp/pendant.json" <<'JSON'
{"luminaires": [{"type": "gldf", "file": "pendant.gldf", "name": "pendant", "position": [0, 3, 0]}]}
JSON
scene=$("$binary" info "$tmp/pendant.json" 2>&1)
check "a scene entry is one luminaire per emitter: $scene" 'grep -q "^luminaires: 2$" <<<"$scene" && grep -q "\"pendant #0\": GLDF pendant.gldf variant \"pendant\" emitter 0 of 2" <<<"$scene" && grep -q "\"pendant #1\": GLDF pendant.gldf variant \"pendant\" emitter 1 of 2" <<<"$scene"'

printf 'not a zip' > "$tmp/broken.l3d"
expect "broken.l3d: not an L3D archive (a ZIP archive)" -- info "$tmp/broken.l3d"
expect "structure.xml: missing" -- info "$tmp"

echo "l3d_info: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
