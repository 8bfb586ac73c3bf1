#!/usr/bin/env bash
# `candela probe` with an environment map: a constant map of radiance 2 gives E = 2 pi for every
# normal, exactly with the default (reference) and within 4 standard errors + 0.5 % with each
# stochastic environment technique; --technique T picks the environment's technique when T is
# one, luminaires keep theirs and add their closed form; the GPU probe gives 2 pi with each GPU
# technique; bad names and the CPU-only reference on the GPU fail clearly.
set -uo pipefail
binary=$1
data="$2/data/environment"
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
source "$2/cli/lib/expect.sh"

pts="$data/points.csv"
out=$("$binary" probe "$data/constant.json" --points "$pts" 2>/dev/null)
bad=$(tail -n +2 <<<"$out" | awk -F, '{ d = $7 - 6.283185307; if (d < 0) d = -d; if (d > 1e-5 || $11 != 0) print NR ": " $0 }')
check "reference gives 2 pi exactly: $out" '[ -z "$bad" ] && [ $(wc -l <<<"$out") -eq 5 ]'
for t in balanced uniform-faces global-cdf balanced-mis reference havran2005; do
  for flag in --technique --env-technique; do
    out=$("$binary" probe "$data/constant.json" --points "$pts" $flag $t --spp 20000 2>/dev/null)
    # havran2005 is a deterministic approximation (256 lights): within 1 %.
    bad=$(tail -n +2 <<<"$out" | awk -F, -v t=$t '{ e = $7; se = $11; tol = (t == "havran2005" ? 0.01 : 0.005) * 6.283185307 + 4 * se;
        d = e - 6.283185307; if (d < 0) d = -d; if (d > tol || e != e) print NR ": " e " (tol " tol ")" }')
    check "$t via $flag gives 2 pi: $bad" '[ -z "$bad" ] && [ $(wc -l <<<"$out") -eq 5 ]'
  done
done
# With a panel: the environment's 2 pi plus the panel's closed form; an environment technique
# name leaves the panel on its own technique (analytic, exact).
ref=$("$binary" probe "$data/constant_with_panel.json" --points "$pts" 2>/dev/null)
check "panel + environment: up-facing gets more than 2 pi, down-facing exactly 2 pi: $ref" \
  'awk -F, "NR==2 && \$7 > 8.5 {ok++} NR==4 && \$7 > 6.283185 && \$7 < 6.283186 {ok++} END {exit ok != 2}" <<<"$ref"'
out=$("$binary" probe "$data/constant_with_panel.json" --points "$pts" --technique balanced --spp 50000 2>/dev/null)
bad=$(paste -d, <(tail -n +2 <<<"$out") <(tail -n +2 <<<"$ref") | awk -F, '{ d = $7 - $18; if (d < 0) d = -d; if (d > 4 * $11 + 0.005 * $18) print NR ": " $7 " vs " $18 }')
check "--technique balanced with a panel agrees with the reference: $bad" '[ -z "$bad" ]'
out=$("$binary" probe "$data/sky.json" --points "$pts" 2>/dev/null)
check "a sky gives daylight illuminance upwards: $out" 'awk -F, "NR==2 && \$7 > 40000 && \$7 < 110000 {ok=1} END {exit !ok}" <<<"$out"'

expect "--env-technique" "not-a-technique" "balanced" -- probe "$data/constant.json" --points "$pts" --env-technique not-a-technique
expect "--env-technique" "runs on the CPU only" -- probe "$data/constant.json" --points "$pts" --device gpu --env-technique reference
# The GPU probe runs the production passes: 2 pi within 1 % (its noise at 16384 spp is below
# 0.3 %, the CPU twin's standard error at that count) for each GPU technique.
for t in balanced uniform-faces balanced-mis global-cdf havran2005; do
  out=$("$binary" probe "$data/constant.json" --points "$pts" --device gpu --env-technique $t --spp 16384 2>/dev/null)
  bad=$(tail -n +2 <<<"$out" | awk -F, '{ d = $7 - 6.283185307; if (d < 0) d = -d; if (d > 0.01 * 6.283185307 || $7 != $7) print NR ": " $7 }')
  check "GPU $t gives 2 pi: $out" '[ -z "$bad" ] && [ $(wc -l <<<"$out") -eq 5 ]'
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed 's/constant_2.exr/nowhere.exr/' "$data/constant.json" > "$tmp/missing.json"
expect "missing.json: environment.file: " "nowhere.exr" -- probe "$tmp/missing.json" --points "$pts"
echo '{"environment": {"sky": {"turbidity": 50}}}' > "$tmp/badsky.json"
expect "badsky.json: environment.sky.turbidity: expected a turbidity in [1.7, 10]" -- probe "$tmp/badsky.json" --points "$pts"

# --show-samples: the Fig. 1-2 chart of the first point's normal; its per-face table (stderr)
# adds up, every sample of a constant map counts once, and no more are effective than selected.
"$binary" probe "$data/sky.json" --points "$pts" --show-samples "$tmp/chart.png" --chart-spp 60 \
  >/dev/null 2>"$tmp/chart.txt"
check "chart written: $(cat "$tmp/chart.txt")" '[ -s "$tmp/chart.png" ]'
sums=$(awk '$1 ~ /^[+-][XYZ]$/ {d += $3; e += $4; if ($4 > $3) bad++} $1 == "all" {D = $3; E = $4}
            END {print (d == D && e == E && !bad && D >= 60 && D <= 66) ? "ok" : "bad " d " " D " " e " " E}' "$tmp/chart.txt")
check "chart counts add up: $sums" '[ "$sums" = ok ]'
# --pixel X,Y: the surface a pixel of the render sees. The camera (0,4,5) looks at the origin;
# the centre pixel of 960x540 sees the front face of the unit box (z = 0.5, normal +Z) and a
# pixel lower down the floor in front of it (y = 0, normal +Y); a pixel of sky is an error.
"$binary" probe "$data/pixel.json" --pixel 480,270 --size 960x540 --technique balanced --spp 256 \
  --show-samples "$tmp/pixel.png" >"$tmp/pixel.csv" 2>"$tmp/pixel.txt"
face=$(awk -F, 'NR == 2 { z = $3 - 0.5; if (z < 0) z = -z; print (z < 1e-6 && $4 == 0 && $5 == 0 && $6 == 1) ? "ok" : $0 }' "$tmp/pixel.csv")
check "centre pixel sees the box's front face: $face $(cat "$tmp/pixel.txt")" '[ "$face" = ok ]'
behind=$(awk '$1 == "-Z" {print $3}' "$tmp/pixel.txt")
check "nothing selected on the face behind the picked normal: $behind" '[ "$behind" = 0 ]'
floor=$("$binary" probe "$data/pixel.json" --pixel 480,330 2>/dev/null | awk -F, 'NR == 2 { y = $2; if (y < 0) y = -y; print (y < 1e-6 && $5 == 1) ? "ok" : $0 }')
check "a lower pixel sees the floor: $floor" '[ "$floor" = ok ]'
expect "--pixel: pixel (10, 10) of 960x540 sees no surface" -- probe "$data/pixel.json" --pixel 10,10
expect "--pixel: expected X,Y inside the 64x48 image" -- probe "$data/pixel.json" --pixel 64,0 --size 64x48
expect_usage "usage" -- probe "$data/pixel.json" --pixel 1,1 --points "$pts"
echo '{"geometry": []}' > "$tmp/noenv.json"
expect "--show-samples: the scene has no environment" -- probe "$tmp/noenv.json" --points "$pts" --show-samples "$tmp/x.png"

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
