#!/usr/bin/env bash
# Runs on the lent GPU machine (tools `device`, as root, in a copy of the working tree), times
# every technique's shading pass and the drag bench for this build and a baseline on the GPU's
# own driver through EGL, then runs the GL tests there. Everything it reports goes to $OUT.
#
# Prepared here first, by scripts/device/prepare.sh BASELINE_BINARY (the bundle in .gpu/, the
# GL loaders in .gl/); the call carries .gpu, .gl and resources/luminaires/generated:
#   run(command="bash scripts/device/gpu_bench.sh", carry=[".gpu", ".gl",
#       "resources/luminaires/generated"], timeout_s=560)
# Environment: SIZE, SPP, REPEATS (as scripts/bench_side_by_side.sh; defaults 1920x1080, 16, 3),
# PASS_LIMIT, DRAG_LIMIT, TEST_LIMIT, SHADOW_LIMIT, PROST_LIMIT (seconds for each stage, defaults 270,
# 70 per build, 100, 60 per scene, 90),
# STAGES (which to run, in that order; default "passes drag info tests"; also "shadows" and "prost"; the bundle may then lack the baseline),
# CASES (bench_side_by_side.sh's filter on case labels).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-/tmp/gpu-out}
mkdir -p "$out"
exec > >(tee -a "$out/log.txt") 2>&1
work=/tmp/gpu-bench
rm -rf "$work" && mkdir -p "$work/bundle"
started=$(date +%s)
stamp() { echo "== $(( $(date +%s) - started )) s: $*"; }

stamp "setup"
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
  [ -d "$d" ] && export LD_LIBRARY_PATH=${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}$d
done
vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f "$vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
tar -xJf .gpu/bundle.tar.xz -C "$work/bundle"
export LD_LIBRARY_PATH=$work/bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
# The binaries find shaders and resources under the folder they were built from.
if [ "$(pwd -P)" != /work/main ]; then
  [ -e /work/main ] && { stamp "/work/main exists and is not this tree: stopping"; exit 1; }
  mkdir -p /work && ln -s "$(pwd -P)" /work/main
fi
baseDir=$(cat .gpu/baseline-dir 2>/dev/null || echo build-baseline/src)
if [ ! -d "$baseDir/shaders" ]; then
  mkdir -p "$baseDir"
  tar -xf .gpu/baseline-shaders.tar -C "$baseDir"
  ln -sfn "$(pwd -P)/resources" "$baseDir/resources"
fi
# A baseline built in this tree (prepare.sh --same-tree) reads the shaders of its own commit,
# packed beside it, instead of this tree's.
if [ -f .gpu/baseline-same-tree ]; then
  mv "$work/bundle/bin/candela-baseline" "$work/bundle/bin/candela-baseline.bin"
  printf '#!/bin/sh\nCANDELA_SHADER_DIR=%s exec %s "$@"\n' "$(pwd -P)/$baseDir/shaders" \
    "$work/bundle/bin/candela-baseline.bin" >"$work/bundle/bin/candela-baseline"
  chmod +x "$work/bundle/bin/candela-baseline"
fi
export CANDELA_GL=egl __GL_SHADER_DISK_CACHE_PATH=$work/glcache
mkdir -p "$__GL_SHADER_DISK_CACHE_PATH"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem,temperature.gpu --format=csv
current=$work/bundle/bin/candela base=$work/bundle/bin/candela-baseline
"$current" render resources/scenes/editor-room.json --out "$work/probe.png" --size 480x270 --spp 4 \
  --stats 2>&1 | grep -E 'context|shade|error' || { stamp "no EGL context: stopping"; exit 1; }

stage_passes() {
stamp "shading passes, side by side"
CASES=${CASES:-} SIZE=${SIZE:-1920x1080} SPP=${SPP:-16} REPEATS=${REPEATS:-3} DRAG=0 CURRENT=$current \
  CURRENT_LABEL="$(cat .gpu/current-label)" BASELINE_LABEL="$(cat .gpu/baseline-label)" \
  timeout "${PASS_LIMIT:-270}" bash scripts/bench_side_by_side.sh "$base" "$work/sbs"
cp "$work/sbs/passes.csv" "$work/sbs/raw.tsv" "$work/sbs/machine.txt" "$out/" 2>/dev/null
}

stage_drag() {
for build in baseline current; do
  binary=$base
  [ $build = current ] && binary=$current
  stamp "drag and release, $build"
  timeout "${DRAG_LIMIT:-70}" "$binary" bench --drag --out "$work/drag-$build" --reference-spp 512 \
    >"$work/drag-$build.log" 2>&1
  echo "rc $?"; tail -4 "$work/drag-$build.log"
  [ -f "$work/drag-$build/summary.txt" ] && cat "$work/drag-$build/summary.txt"
done
tar -czf "$out/drag.tgz" -C "$work" drag-baseline drag-current drag-baseline.log drag-current.log
}

stage_info() {
stamp "light-field precomputation on a newly started machine (issue 20, part 6), five runs"
for i in 1 2 3 4 5; do
  "$current" info resources/luminaires/generated/car-headlight.lf.json 2>&1 | grep -i precomputation
done
}

stage_shadows() {
# The shadow-map bench (docs/performance.md, "Shadow-map bench") on the GPU: maps against a shadow ray per sample.
for scene in headlight-room headlight-grille; do
  stamp "shadow maps against shadow rays, $scene"
  timeout "${SHADOW_LIMIT:-60}" "$current" bench --shadows "resources/scenes/$scene.json" \
    --out "$work/shadows-$scene" --spp 256 >"$work/shadows-$scene.log" 2>&1
  echo "rc $?"; head -4 "$work/shadows-$scene/summary.txt" 2>/dev/null
  cat "$work/shadows-$scene/shadows.csv" 2>/dev/null
done
tar -czf "$out/shadows.tgz" -C "$work" --exclude='*.png' shadows-headlight-room shadows-headlight-grille \
  shadows-headlight-room.log shadows-headlight-grille.log 2>/dev/null
}

stage_prost() {
# Prost's evaluation (docs/performance.md, "Photometric bench") on the 14 files of the committed llvmpipe run.
stamp "photometric bench (Prost's Sec. 6.2)"
d=tests/data/photometry/ies
timeout "${PROST_LIMIT:-90}" "$current" bench --prost tests/data/photometric/lambert.ies \
  tests/data/photometric/side.ies $d/RenderPipeline/{area_light,comet,jelly_fish,medium_scatter}.ies \
  $d/RenderPipeline/{parallel_beam,three_lobe_umbrella,x_arrow}.ies "$d/ies_rescale/Type B - 01.ies" \
  "$d/ies_rescale/Type C - 03.ies" "$d/ies_rescale/Type C - 06.ies" $d/photometric-viewer/dummy.ies \
  tests/data/photometry/ldt/lidrs/example.ldt --size 64 --reference-spp 1024 --out "$work/prost" \
  >"$work/prost.log" 2>&1
echo "rc $?"; grep -A12 "^over 56" "$work/prost/summary.txt" 2>/dev/null
tar -czf "$out/prost.tgz" -C "$work" --exclude='*.png' prost prost.log 2>/dev/null
}

stage_tests() {
stamp "GL tests on the GPU"
timeout "${TEST_LIMIT:-100}" "$work/bundle/bin/gltests" --gtest_brief=1 >"$out/gltests.log" 2>&1
echo "gltests rc $?"
grep -E '^\[  (FAILED|PASSED) |tests ran' "$out/gltests.log" | tail -30
grep 'on the GPU: expected' "$out/gltests.log" | cut -c1-300
}

# The stages run in the order STAGES names them, so the ones that matter most can go first.
for stage in ${STAGES:-passes drag info tests}; do
  if declare -F "stage_$stage" >/dev/null; then "stage_$stage"; else stamp "unknown stage $stage"; fi
done
stamp "done"
