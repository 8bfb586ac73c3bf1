#!/usr/bin/env bash
# Prepares a call of scripts/device/gpu_bench.sh on the lent GPU machine: packs build/candela,
# build/tests/candela_gltests and a baseline binary with their libraries into .gpu/bundle.tar.xz
# (scripts/device/make_bundle.py), the baseline's shaders into .gpu/baseline-shaders.tar, and
# downloads the GL loaders (glvnd's libEGL and friends) into .gl/. Both folders are kept out of
# git by .git/info/exclude.
# Usage: scripts/device/prepare.sh BASELINE_SOURCE   (a built checkout, e.g. build-baseline/src)
#    or: scripts/device/prepare.sh --same-tree BASELINE_BINARY COMMIT
#        (a binary built in this tree at COMMIT, kept before rebuilding, e.g. to A/B a change that
#        is not committed yet: the baseline then reads COMMIT's shaders, packed into build-baseline/
#        COMMIT, through CANDELA_SHADER_DIR)
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ "${1:-}" = --same-tree ]; then
  binary=${2:?usage: prepare.sh --same-tree BASELINE_BINARY COMMIT} commit=${3:?missing COMMIT}
  src=build-baseline/$commit
  rm -rf "$src" && mkdir -p "$src/build"
  git archive "$commit" shaders | tar -x -C "$src"
  cp "$binary" "$src/build/candela"
  mkdir -p .gpu && touch .gpu/baseline-same-tree
  BASELINE_LABEL=${BASELINE_LABEL:-$(git log -1 --format="%h %s" "$commit" | cut -c1-80)}
else
  src=${1:?usage: scripts/device/prepare.sh BASELINE_SOURCE}
  rm -f .gpu/baseline-same-tree
fi
for folder in /.gpu/ /.gl/; do
  grep -qx "$folder" .git/info/exclude 2>/dev/null || echo "$folder" >>.git/info/exclude
done
mkdir -p .gpu .gl
python3 scripts/device/make_bundle.py .gpu/bundle.tar.xz candela=build/candela \
  candela-baseline="$src/build/candela" gltests=build/tests/candela_gltests
tar -cf .gpu/baseline-shaders.tar -C "$src" shaders
# The baseline binary reads its shaders from the folder it was built in, relative to this tree.
realpath --relative-to=. "$src" >.gpu/baseline-dir
echo "${CURRENT_LABEL:-$(git log -1 --format='%h %s' | cut -c1-80)}" >.gpu/current-label
echo "${BASELINE_LABEL:-$(git -C "$src" log -1 --format="%h %s" | cut -c1-80)}" >.gpu/baseline-label
if ! ls .gl/libegl1_*.deb >/dev/null 2>&1; then
  mkdir -p /tmp/amd64/partial
  o=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
  apt-get "${o[@]}" update >/dev/null
  (cd .gl && apt-get "${o[@]}" download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
fi
du -sh .gpu .gl
