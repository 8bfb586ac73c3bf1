#!/usr/bin/env bash
# Every technique's shading pass, and the editor's drag and release, timed side by side against an
# earlier build on the same machine in one run (issue 20, part 4). Speed-ups are ratios of medians
# measured alternately (baseline, this build, baseline, ...), so drift in the machine's load
# touches both alike. Only commands both builds have are used (`candela render --stats`,
# `candela bench --drag`; interreflection off, which its indirect pass would add alike), so any
# commit since `render --indirect off` can be the baseline.
#
# Usage: scripts/bench_side_by_side.sh BASELINE [OUT]
#   BASELINE: a commit (checked out into build-baseline/src and built there, Release) or the path
#             of a candela binary.
#   OUT:      folder for the results (default docs/bench/side-by-side): passes.csv (median pass
#             times and speed-ups), raw.tsv (every run), drag.csv and the two drag benches'
#             folders, machine.txt, summary.txt.
# Environment: REPEATS (timed runs per build and case after one warm-up, default 3), SIZE
# (default 480x270), SPP (default 16), DRAG=0 to skip the drag and release bench (about 5 min per
# build), DRAG_ARGS (default "--reference-spp 512"), BASELINE_LABEL (what machine.txt calls a
# baseline binary), CURRENT (the binary timed against it, default build/candela) and
# CURRENT_LABEL (what machine.txt calls it, default this checkout's commit), CANDELA_GL (which
# offscreen context both run on: osmesa or egl, see renderer/context/GlContext.h), CASES (an
# extended regular expression: only the cases whose label matches, e.g. '^(room|headlight)$').
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: scripts/bench_side_by_side.sh BASELINE [OUT]"; exit 2; }
baseline=$1
out=${2:-docs/bench/side-by-side}
repeats=${REPEATS:-3} size=${SIZE:-480x270} spp=${SPP:-16}
current=${CURRENT:-build/candela}
[ -x "$current" ] || { echo "bench: $current is missing (scripts/build.sh builds it)"; exit 1; }

if [ -x "$baseline" ] && [ -f "$baseline" ]; then
  base=$baseline
  baseLabel=${BASELINE_LABEL:-$baseline}
else
  commit=$(git rev-parse --verify "$baseline^{commit}") || { echo "bench: $baseline is neither a binary nor a commit"; exit 1; }
  src=build-baseline/src
  if [ ! -d "$src" ]; then git worktree add --detach "$src" "$commit" >/dev/null; fi
  git -C "$src" checkout --detach -q "$commit"
  echo "bench: building $commit into $src/build (log build-baseline/build.log)"
  { cmake -S "$src" -B "$src/build" -DCMAKE_BUILD_TYPE=Release && cmake --build "$src/build" -j"$(nproc)" --target candela; } \
    >build-baseline/build.log 2>&1 || { tail -20 build-baseline/build.log; exit 1; }
  base=$src/build/candela
  baseLabel="$(git log -1 --format='%h %s' "$commit" | cut -c1-80)"
fi

mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A scene under a sky for the environment techniques (the repository's scenes have none).
cat >"$tmp/sky.json" <<'EOF'
{"geometry": [{"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [10,10]}},
              {"box": {"center": [0,0.5,0], "size": [1,1,1]}}],
 "luminaires": [], "camera": {"position": [3,2.5,4], "target": [0,0.4,0]},
 "environment": {"sky": {"sun_elevation_deg": 30, "sun_azimuth_deg": 120, "turbidity": 3,
                         "ground_albedo": 0.2, "resolution": 256}}}
EOF
# The demo room as older builds read it: without the camera's exposure (newer than some
# baselines, and no part of any pass), its files made absolute so the copy can live in $tmp.
python3 - resources/scenes/editor-room.json "$tmp/room.json" <<'PY'
import json, os, sys
src, dst = sys.argv[1:3]
scene = json.load(open(src))
scene.get("camera", {}).pop("exposure", None)
base = os.path.dirname(os.path.abspath(src))
for item in scene.get("luminaires", []) + scene.get("geometry", []):
    for key in ("file", "gltf"):
        if isinstance(item.get(key), str):
            item[key] = os.path.join(base, item[key])
json.dump(scene, open(dst, "w"), indent=1)
PY
room=$tmp/room.json
# case label | scene | extra render arguments
cases=(
  "room|$room|"
  "room scattered|$room|--technique scattered"
  "room structured|$room|--technique structured"
  "room mrp|$room|--technique mrp"
  "room mc-poisson-24|$room|--technique mc-poisson-24"
  "room mc-poisson-40|$room|--technique mc-poisson-40"
  "room point|$room|--technique point"
  "room uniform-area|$room|--technique uniform-area"
  "room uniform-restricted|$room|--technique uniform-restricted"
  "room precomputed-global|$room|--technique precomputed-global"
  "room precomputed-shared|$room|--technique precomputed-shared"
  "room granier2003|$room|--technique granier2003"
  "room restricted-cdf-raytraced|$room|--technique restricted-cdf-raytraced"
  "headlight|resources/scenes/headlight-room.json|"
  "sky balanced|$tmp/sky.json|--env-technique balanced"
  "sky uniform-faces|$tmp/sky.json|--env-technique uniform-faces"
  "sky global-cdf|$tmp/sky.json|--env-technique global-cdf"
  "sky balanced-mis|$tmp/sky.json|--env-technique balanced-mis"
  "sky balanced-integer|$tmp/sky.json|--env-technique balanced-integer"
  "sky havran2005|$tmp/sky.json|--env-technique havran2005"
)

# One render's pass times: "pass<TAB>ms" for the shading and environment passes.
passes() {
  local binary=$1 scene=$2
  shift 2
  "$binary" render "$scene" --out "$tmp/frame.png" --size "$size" --spp "$spp" --indirect off --stats "$@" 2>&1 |
    awk -F, '/^(shade|env):/ {print $1 "\t" $2}'
}

printf "case\tbuild\trun\tpass\tms\n" >"$out/raw.tsv"
for c in "${cases[@]}"; do
  IFS='|' read -r label scene extra <<<"$c"
  [[ -n ${CASES:-} && ! $label =~ $CASES ]] && continue
  read -r -a args <<<"$extra"
  echo "bench: $label"
  passes "$base" "$scene" "${args[@]}" >/dev/null  # warm-up: compiles and caches the shaders
  passes "$current" "$scene" "${args[@]}" >/dev/null
  for r in $(seq 1 "$repeats"); do
    for build in baseline current; do
      binary=$base
      [ "$build" = current ] && binary=$current
      passes "$binary" "$scene" "${args[@]}" | while IFS=$'\t' read -r pass ms; do
        printf "%s\t%s\t%s\t%s\t%s\n" "$label" "$build" "$r" "$pass" "$ms"
      done >>"$out/raw.tsv"
    done
  done
done

# Medians per case, pass and build; the speed-up is baseline / current.
awk -F'\t' 'NR > 1 { key = $1 "\t" $4; v[key, $2, ++n[key, $2]] = $5; keys[key] = 1 }
  function median(k, b,   m, i, j, t, a) {
    m = n[k, b]; if (m == 0) return -1
    for (i = 1; i <= m; ++i) a[i] = v[k, b, i]
    for (i = 1; i <= m; ++i) for (j = i + 1; j <= m; ++j) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
    return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
  }
  END {
    print "case,pass,baseline_ms,current_ms,speedup"
    for (k in keys) {
      b = median(k, "baseline"); c = median(k, "current"); split(k, p, "\t")
      bs = b < 0 ? "" : sprintf("%.1f", b)
      cs = c < 0 ? "" : sprintf("%.1f", c)
      ratio = (b > 0 && c > 0) ? sprintf("%.2f", b / c) : ""
      printf "%s,%s,%s,%s,%s\n", p[1], p[2], bs, cs, ratio
    }
  }' "$out/raw.tsv" | { read -r header; echo "$header"; sort; } >"$out/passes.csv"

if [ "${DRAG:-1}" != 0 ]; then
  read -r -a dragArgs <<<"${DRAG_ARGS:---reference-spp 512}"
  for build in baseline current; do
    binary=$base
    [ "$build" = current ] && binary=$current
    echo "bench: drag and release, $build"
    "$binary" bench --drag --out "$out/drag-$build" "${dragArgs[@]}" >"$tmp/drag-$build.log" 2>&1 ||
      { tail -5 "$tmp/drag-$build.log"; exit 1; }
  done
  # summary.txt: "NAME  dragging  F fps (...); after release Delta E < 1 in T s refining it alone"
  extract() {
    sed -n 's/^\(.*[^ ]\) *dragging *\([0-9.]*\) fps.*Delta E < 1 in \([0-9.]*\) s refining it alone.*/\1,\2,\3/p' "$1"
  }
  echo "luminaire,baseline_fps,current_fps,fps_ratio,baseline_release_s,current_release_s,release_speedup" >"$out/drag.csv"
  join -t, <(extract "$out/drag-baseline/summary.txt" | sort) <(extract "$out/drag-current/summary.txt" | sort) |
    awk -F, '{ printf "%s,%s,%s,%.2f,%s,%s,%.2f\n", $1, $2, $4, $4 / $2, $3, $5, $3 / $5 }' >>"$out/drag.csv"
fi

{
  echo "baseline: $baseLabel"
  echo "current: ${CURRENT_LABEL:-$(git log -1 --format='%h %s' | cut -c1-80)$(git diff --quiet -- . ":(exclude)$out" || echo ' (with uncommitted changes)')}"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
  "$current" render resources/scenes/demo.json --out "$tmp/frame.png" --size 64x36 --spp 1 --stats 2>&1 | grep '^context:' || true
  echo "settings: $size, $spp spp per pass, median of $repeats runs per build after one warm-up"
} >"$out/machine.txt"
{
  cat "$out/machine.txt"
  echo
  cat "$out/passes.csv"
  if [ -f "$out/drag.csv" ]; then echo; cat "$out/drag.csv"; fi
} >"$out/summary.txt"
cat "$out/summary.txt"
