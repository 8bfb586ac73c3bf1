#!/usr/bin/env bash
# No command destroys an input: an output that resolves to a file the command reads (the scene,
# its luminaire file, its environment map, a points CSV, a TM-25 ray file, the photometric file
# of polar), directly or through a symbolic or hard link, is refused with exit code 1 and a
# message naming both, the input unchanged. And no failed write leaves half a file: on a "full
# disk" (ulimit -f with SIGXFSZ ignored, so write() fails with EFBIG) each command writing over an
# existing, larger output exits 1 naming it, the old file unchanged and no temporary file left.
# Everything runs on copies in a temporary folder: nothing in the repository is ever at risk.
set -uo pipefail
binary=$(realpath "$1")  # absolute: one case runs from another folder
data="$2/data"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passed=0

source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS

# Renders under the limit must not leave half-written entries in the user's shader cache.
export MESA_SHADER_CACHE_DIR="$work/mesa-cache"

checksum() { sha256sum "$1" | cut -d' ' -f1; }
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# Copies of the inputs.
mkdir -p "$work/grid" "$work/photo" "$work/env" "$work/rays"
cp "$data/measure/plane.json" "$work/grid/"
cp "$data/photometric/scene.json" "$data/photometric/spot.ies" "$work/photo/"
cp "$data/environment/constant.json" "$data/environment/constant_2.exr" "$data/environment/points.csv" "$work/env/"
cp "$data/measure/quadrant.ies" "$work/photo/"
cp "$data/nearfield/Cyl10k.1.tm25ray" "$work/rays/"
cp "$data/hdr/noon_grass_256.hdr" "$work/env/"
echo '{"environment": {"file": "noon_grass_256.hdr"}}' >"$work/env/grass.json"

# refuses INPUT OUTPUT -- ARGS: candela ARGS exits 1 saying OUTPUT would overwrite INPUT (named by
# its file name, as the command resolved it), and INPUT keeps its checksum.
refuses() {
  local input=$1 output=$2
  shift 3
  local before
  before=$(checksum "$input")
  expect "$(basename "$input"): " "$output would overwrite this input of the command" -- "$@"
  if [ "$(checksum "$input")" = "$before" ]; then
    passed=$((passed + 1))
  else
    fail "candela $* changed $input"
  fi
}

# Outputs onto inputs.
refuses "$work/grid/plane.json" "--out $work/grid/plane.json" -- \
  grid "$work/grid/plane.json" --plane y=0 --spacing 1 --out "$work/grid/plane.json"
refuses "$work/photo/spot.ies" "--out $work/photo/spot.ies" -- \
  grid "$work/photo/scene.json" --plane y=0 --spacing 1 --out "$work/photo/spot.ies"
# Relative and ".." spellings of the same file, run from the copy's folder.
cd "$work/photo"
refuses "$work/photo/spot.ies" "--out ../photo/./spot.ies" -- \
  grid scene.json --plane y=0 --spacing 1 --out ../photo/./spot.ies
cd - >/dev/null
refuses "$work/env/constant_2.exr" "--out $work/env/constant_2.exr" -- \
  render "$work/env/constant.json" --out "$work/env/constant_2.exr" --size 32x16
ln -s constant.json "$work/env/scene-link.png"
refuses "$work/env/constant.json" "--out $work/env/scene-link.png" -- \
  render "$work/env/constant.json" --out "$work/env/scene-link.png" --size 32x16
ln "$work/env/constant_2.exr" "$work/env/hard-link.exr"
refuses "$work/env/constant_2.exr" "--out $work/env/hard-link.exr" -- \
  render "$work/env/constant.json" --out "$work/env/hard-link.exr" --size 32x16
refuses "$work/env/constant.json" "--show-samples $work/env/constant.json" -- \
  probe "$work/env/constant.json" --points "$work/env/points.csv" --spp 16 --show-samples "$work/env/constant.json"
refuses "$work/env/points.csv" "--show-samples $work/env/points.csv" -- \
  probe "$work/env/constant.json" --points "$work/env/points.csv" --spp 16 --show-samples "$work/env/points.csv"
ln -s quadrant.ies "$work/photo/polar-link.png"
refuses "$work/photo/quadrant.ies" "--out $work/photo/polar-link.png" -- \
  polar "$work/photo/quadrant.ies" --out "$work/photo/polar-link.png"
# Named directly, the .ies is refused by its extension first: still exit 1, still untouched.
before=$(checksum "$work/photo/quadrant.ies")
expect "quadrant.ies" "unsupported output extension" -- polar "$work/photo/quadrant.ies" --out "$work/photo/quadrant.ies"
[ "$(checksum "$work/photo/quadrant.ies")" = "$before" ] || fail "polar --out changed quadrant.ies"
ln -s Cyl10k.1.tm25ray "$work/rays/rays.lf.json"
refuses "$work/rays/Cyl10k.1.tm25ray" "--out $work/rays/rays.lf.json" -- \
  convert "$work/rays/Cyl10k.1.tm25ray" --out "$work/rays/rays.lf.json" --grid 3x3 --res 8
# The editor: its layout file (written every frame) may not be the scene or a file it reads; it
# is refused before any window opens, with or without a display. Its screenshots (headless here)
# take new names beside, never an input's.
# refuses_edit INPUT LAYOUT: `edit` with that layout file exits 1 naming both, INPUT unchanged.
refuses_edit() {
  local before
  before=$(checksum "$1")
  expect "$(basename "$1"): --layout-file $2 would overwrite this input of the editor" -- \
    edit "$work/photo/scene.json" --layout-file "$2"
  [ "$(checksum "$1")" = "$before" ] || fail "candela edit --layout-file $2 changed $1"
}
refuses_edit "$work/photo/scene.json" "$work/photo/scene.json"
refuses_edit "$work/photo/spot.ies" "$work/photo/spot.ies"
ln -s scene.json "$work/photo/layout-link.json"
refuses_edit "$work/photo/scene.json" "$work/photo/layout-link.json"
before=$(checksum "$work/photo/scene.json")
ln -s scene.json "$work/photo/shot-000.png"
if env -u DISPLAY -u WAYLAND_DISPLAY "$binary" edit "$work/photo/scene.json" \
    --screenshot-dir "$work/photo" >/dev/null 2>&1 &&
  [ "$(checksum "$work/photo/scene.json")" = "$before" ] && [ -s "$work/photo/shot-001.png" ]; then
  passed=$((passed + 1))
else
  fail "edit's headless screenshots into the scene's folder changed scene.json or wrote no shot-001.png"
fi

# full_disk TARGET [NAMED] -- ARGS: candela ARGS, with files limited to 2 blocks of 1024 bytes,
# writes over TARGET (8 KiB of random bytes, more than the limit, so any replacement would have to
# write past it): exit 1, an error naming NAMED (default TARGET's file name: the file whose write
# failed), TARGET unchanged, the folder's listing unchanged (no temporary file left).
full_disk() {
  local target=$1 named
  named=$(basename "$target")
  shift
  if [ "$1" != "--" ]; then
    named=$1
    shift
  fi
  shift
  local dir before listing err rc
  dir=$(dirname "$target")
  head -c 8192 /dev/urandom >"$target"
  before=$(checksum "$target")
  listing=$(ls -A "$dir")
  # bash: an ignored signal stays ignored across exec; ulimit -f counts 1024-byte blocks.
  err=$( (trap '' XFSZ; ulimit -f 2; "$binary" "$@") 2>&1 >/dev/null)
  rc=$?
  local ok=1
  [ $rc -eq 1 ] || ok=0
  grep -qF -- "$named" <<<"$err" || ok=0
  grep -qF -- "File too large" <<<"$err" || ok=0
  [ "$(checksum "$target")" = "$before" ] || ok=0
  [ "$(ls -A "$dir")" = "$listing" ] || ok=0
  if [ $ok -eq 1 ]; then
    passed=$((passed + 1))
  else
    fail "full disk: candela $* (exit $rc): $err; folder now: $(ls -A "$dir" | tr '\n' ' ')"
  fi
}

mkdir -p "$work/out"
# 16 x 16 points of about 40 bytes: some 10 kB of CSV.
full_disk "$work/out/grid.csv" -- grid "$work/grid/plane.json" --plane y=0 --extent -2,-2,2,2 --spacing 0.25 \
  --out "$work/out/grid.csv"
# The panel's light on the floor at 128 x 96: a PNG and an EXR of several kilobytes.
full_disk "$work/out/render.png" -- render "$work/grid/plane.json" --out "$work/out/render.png" --size 128x96
full_disk "$work/out/render.exr" -- render "$work/grid/plane.json" --out "$work/out/render.exr" --size 128x96
full_disk "$work/out/polar.png" -- polar "$work/photo/quadrant.ies" --out "$work/out/polar.png"
# A real map's chart (a constant map's compresses below the limit): some 50 kB of PNG.
full_disk "$work/out/chart.png" -- probe "$work/env/grass.json" --points "$work/env/points.csv" --spp 16 \
  --show-samples "$work/out/chart.png"
# A light field's first image (rays_0_0.exr, 32 x 32 floats) is the first file over the limit;
# the old manifest stays as it was.
head -c 8192 /dev/urandom >"$work/out/rays_0_0.exr"
before=$(checksum "$work/out/rays_0_0.exr")
full_disk "$work/out/rays.lf.json" rays_0_0.exr -- convert "$work/rays/Cyl10k.1.tm25ray" \
  --out "$work/out/rays.lf.json" --grid 3x3 --res 32
[ "$(checksum "$work/out/rays_0_0.exr")" = "$before" ] || fail "convert on a full disk changed rays_0_0.exr"

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
