#!/usr/bin/env bash
# Bad input gives a clear error naming the file and the problem, exit code 1, never a crash.
set -uo pipefail
binary=$1
data="$2/data/cli"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0

source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS

expect "nothing_here.json" "cannot open" -- info "$data/nothing_here.json"
expect "malformed.json" "invalid JSON" ":4:" -- render "$data/malformed.json" --out "$out/a.png"
expect "nan_literal.json" "invalid JSON" -- probe "$data/nan_literal.json" --points "$data/nan_points.csv"
expect "nan_string.json" "size" "NaN" -- info "$data/nan_string.json"
expect "negative_size.json" "size" "positive" -- render "$data/negative_size.json" --out "$out/a.png"
expect "draco.gltf" "KHR_draco_mesh_compression" -- info "$data/draco_scene.json"
expect "draco.gltf" "KHR_draco_mesh_compression" -- info "$data/draco.gltf"
expect "does_not_exist.gltf" -- render "$data/missing_gltf.json" --out "$out/a.png"
expect "magic" "analytic" -- info "$data/unknown_technique.json"
expect "laser" "lambertian-rect" -- info "$data/unknown_kind.json"
expect "scene.txt" "unsupported" -- render "$data/scene.txt" --out "$out/a.png"
expect "scene.txt" "unsupported" -- info "$data/scene.txt"
expect "a.jpg" "unsupported" -- render "$data/ok.json" --out "$out/a.jpg"
expect "--size" "WIDTHxHEIGHT" -- render "$data/ok.json" --out "$out/a.png" --size 0x10
expect "--spp" "integer" -- render "$data/ok.json" --out "$out/a.png" --spp many
# A report's view too large for OpenGL is refused before its calculation starts, in words (no
# status code), and writes nothing.
err=$("$binary" report "$data/ok.json" --out "$out/big.pdf" --view-size 16384x16384 2>&1 >/dev/null)
rc=$?
if [ $rc -ne 1 ] || [ -e "$out/big.pdf" ] || ! grep -qF -- "--view-size 16384x16384" <<<"$err" ||
  ! grep -qF "too large" <<<"$err" || grep -q "0x\|rendering the view" <<<"$err"; then
  failures=$((failures + 1))
  echo "FAIL: report --view-size 16384x16384 (exit $rc): $err"
else
  passed=$((passed + 1))
fi
expect "nan_points.csv:3" "column 2" -- probe "$data/ok.json" --points "$data/nan_points.csv"
expect "bad_header.csv:1" "header" -- probe "$data/ok.json" --points "$data/bad_header.csv"
expect "zero_normal.csv:2" "normal" -- probe "$data/ok.json" --points "$data/zero_normal.csv"
expect "magic" "analytic" -- probe "$data/ok.json" --points "$data/ok_points.csv" --technique magic
expect "missing.csv" "cannot open" -- probe "$data/ok.json" --points "$data/missing.csv"
expect_usage "unknown option" -- render "$data/ok.json" --out "$out/a.png" --frobnicate
# A failed render leaves no output file behind.
[ ! -e "$out/a.png" ] || { echo "FAIL: a failed render left $out/a.png"; failures=$((failures + 1)); }

# An empty output name is refused, naming the flag (it used to write nothing and exit 0).
office="$2/../resources/scenes/office.json"
expect "--out" "empty" -- grid "$office" --plane y=0.8 --out ""
# A table larger than the GL's textures: the render names the luminaire and its file.
{
  echo "IESNA:LM-63-2002"; echo "TILT=NONE"; echo "1 1000 1 100000 1 1 2 0.1 0.1 0"; echo "1 1 10"
  seq 0 100000 | awk 'NR <= 100000 { printf "%.6f ", 90 * (NR - 1) / 99999 } END { print "" }'
  echo "0"
  seq 1 100000 | awk '{ printf "100 " } END { print "" }'
} >"$out/many-angles.ies"
printf '{"geometry": [{"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [4, 4]}}], "luminaires": [{"type": "photometric", "name": "Wide", "file": "many-angles.ies", "position": [0, 2, 0]}], "camera": {"position": [3, 2, 3], "target": [0, 0, 0]}}' >"$out/many-angles.json"
expect 'luminaire "Wide"' "many-angles.ies" "exceeds this GL" -- render "$out/many-angles.json" --size 32x32 --out "$out/many.png"
# A spacing that makes too many points says how many, in a few digits (not 300 of them).
expect "--spacing: the grid at a spacing of 1e-300 m over 6 x 4 m gives 6e+300 x 4e+300 points, more than the 1000000 allowed: a larger spacing or a smaller extent" -- grid "$office" --plane y=0.8 --spacing 1e-300
expect "--out" "empty" -- surfaces "$office" --out ""
expect "--out" "empty" -- glare "$office" --out ""
expect "--out" "empty" -- glare --table "$2/../resources/luminaires/photometric/prolicht-e30.ldt" --out ""
expect "--out" "empty" -- polar "$2/../resources/luminaires/photometric/prolicht-e30.ldt" --out ""
expect "--show-samples" "empty" -- probe "$data/ok.json" --points "$data/ok_points.csv" --show-samples ""

# Numbers out of their physical range are refused at load, naming the field (each used to give an
# infinite or NaN result, or a silent 0, with exit 0).
ies="$(cd "$2/.." && pwd)/resources/validation/isotropic.ies"
lamp() {  # lamp EXTRA: a scene of one floor and one lamp with EXTRA fields
  printf '{"geometry": [{"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [4, 4]}}],
 "luminaires": [{"type": "photometric", "file": "%s", "position": [0, 2, 0]%s}]%s}' "$ies" "$1" "${2:-}"
}
lamp ', "colour": [1e308, 1, 1]' >"$out/colour.json"
expect "luminaires[0].colour" "at most 1000" -- grid "$out/colour.json" --plane y=0
lamp ', "scale": 1e308' >"$out/scale.json"
expect "luminaires[0].scale" "at most 1000000" -- grid "$out/scale.json" --plane y=0
lamp ', "opening": [1e308, 0.1]' >"$out/opening.json"
expect "luminaires[0].opening" "at most 1000 m" -- grid "$out/opening.json" --plane y=0
lamp ', "opening": [1e6, 0.1]' >"$out/opening6.json"
expect "luminaires[0].opening" "at most 1000 m" -- grid "$out/opening6.json" --plane y=0
lamp '' ', "environment": {"sky": {"sun_elevation_deg": 30, "sun_azimuth_deg": 0, "turbidity": 3, "resolution": 64}, "rotation_deg": 1e308}' >"$out/rotation.json"
expect "environment.rotation_deg" "angle in degrees from -3600 to 3600" -- grid "$out/rotation.json" --plane y=0
lamp '' ', "glare_observers": [{"name": "Eye", "position": [0, 1.2, 1.5], "view": [0, 0, -1], "background_cd_m2": 5e-324}]' >"$out/background.json"
expect "glare_observers[0].background_cd_m2" "luminance in cd/m2 from 0.001" -- glare "$out/background.json"
# Coordinates and lengths: within 1000 km (1e308 used to make areas and distances infinite).
printf '{"geometry": [{"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [1e308, 4]}}]}' >"$out/huge-plane.json"
expect "geometry[0].plane.size[0]" "a positive size in metres of at most 1e+06" -- info "$out/huge-plane.json"
printf '{"geometry": [{"box": {"center": [0, -1e308, 0], "size": [1, 1, 1]}}]}' >"$out/far-box.json"
expect "geometry[0].box.center[1]" "a coordinate in metres from -1e+06 to 1e+06" -- info "$out/far-box.json"
lamp '' ', "calculation_points": [{"position": [1e300, 1, 0]}]' >"$out/far-point.json"
expect "calculation_points[0].position[0]" "a coordinate in metres" -- surfaces "$out/far-point.json"
printf '{"luminaires": [{"type": "photometric", "file": "%s", "position": [0, 1e7, 0]}]}' "$ies" >"$out/far-lamp.json"
expect "luminaires[0].position[1]" "a coordinate in metres" -- info "$out/far-lamp.json"

# A bench whose output folder holds its environment map under a name the bench writes: refused
# before any rendering, leaving nothing behind (it used to render first, then refuse, leaving
# bench_scene.json).
mkdir -p "$out/benchdir"
cp "$2/data/environment/constant_2.exr" "$out/benchdir/reference.exr"
expect "reference.exr" "--out" -- bench --environment "$out/benchdir/reference.exr" --out "$out/benchdir"
[ "$(ls "$out/benchdir")" = "reference.exr" ] || { echo "FAIL: the refused bench left $(ls "$out/benchdir")"; failures=$((failures + 1)); }

# An empty list entry count over a limit: refused by the count, naming the list.
python3 -c 'import json; print(json.dumps({"glare_observers": [{}] * 10001}))' >"$out/observers.json"
expect "glare_observers: expected at most 10000 observers, found 10001" -- info "$out/observers.json"

# Out of memory: a scene with a model of a million triangles (24 MB) under falling limits on the
# address space. Each run must end with exit 0, or exit 1 and a message saying what it was
# doing ("out of memory while reading ..."), never a crash (a worker thread's bad_alloc, or a
# thread that could not start, used to end in std::terminate); one at least must be refused
# that way. A limit under which the program cannot even print its help is skipped: its libraries
# do not load, or one of them (log4cplus, under OpenImageIO) cannot start its thread before main.
python3 "$2/../scripts/fine_gltf.py" "$out/million" 1000000 >/dev/null
refused=0
for limit in 1200000 1000000 900000 800000 750000 700000 650000 600000 550000 500000 450000; do
  (ulimit -v $limit; exec "$binary" --help) >/dev/null 2>&1 || continue
  (ulimit -v $limit; exec "$binary" info "$out/million.json") >"$out/oom.txt" 2>&1
  code=$?
  if [ $code -eq 1 ] && grep -q "error: out of memory while " "$out/oom.txt"; then
    refused=$((refused + 1))
  elif [ $code -ne 0 ] && [ $code -ne 1 ]; then
    echo "FAIL: info under ulimit -v $limit ended with $code: $(tail -2 "$out/oom.txt")"
    failures=$((failures + 1))
  fi
done
if [ $refused -gt 0 ]; then passed=$((passed + 1)); else
  echo "FAIL: no run under a memory limit said what it was doing"; failures=$((failures + 1))
fi

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
