#!/usr/bin/env bash
# `candela glare`: the UGR of one uniform-luminance luminaire (lambert.ies: 1000 cd cos g on
# 0.6 x 0.3 m, so L = 5555.6 cd/m2 in every direction) against the closed form worked in Python
# from the geometry and the published coefficients of Guth's position index (within 0.05, the
# printed digit); the office scene's observers with their limits and a CSV; clear refusals.
set -uo pipefail
binary=$1
data="$2/data"
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
source "$2/cli/lib/expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cp "$data/photometric/lambert.ies" "$tmp/"
cat > "$tmp/one.json" <<'JSON'
{"luminaires": [{"type": "photometric", "file": "lambert.ies", "position": [0.5, 2.8, 0], "aim": [0, -1, 0], "c0": [1, 0, 0]}]}
JSON
want=$(python3 - <<'PY'
import math
eye, lum, view = (0.0, 1.2, 4.0), (0.5, 2.8, 0.0), (0.0, 0.0, -1.0)
d = [l - e for l, e in zip(lum, eye)]; r = math.sqrt(sum(c * c for c in d)); u = [c / r for c in d]
cos_g = (lum[1] - eye[1]) / r
area = 0.18 * cos_g; omega = area / r ** 2; L = 1000 * cos_g / area
sigma = math.degrees(math.acos(sum(a * b for a, b in zip(u, view))))
tau = math.degrees(math.acos(abs(u[1]) / math.sqrt(1 - math.cos(math.radians(sigma)) ** 2)))
p = math.exp(sigma * (35.2 - 0.31889 * tau - 1.22 * math.exp(-2 * tau / 9)) * 1e-3
             + sigma ** 2 * (21 + 0.26667 * tau - 0.002963 * tau ** 2) * 1e-5)
print("%.3f" % (8 * math.log10(0.25 / 20 * L * L * omega / p ** 2)))
PY
)
out=$("$binary" glare "$tmp/one.json" --observer 0,1.2,4 --view 0,0,-1 --background 20 --limit 19 2>&1)
got=$(sed -n 's/^  UGR \([0-9.]*\).*/\1/p' <<<"$out")
check "UGR $got against the closed form $want: $out" 'awk -v a="$got" -v b="$want" "BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 0.05) }"'
check "the background is the one given: $out" 'grep -q "background luminance Lb 20 cd/m2 (given)" <<<"$out"'
check "a uniform luminance of 5556 cd/m2: $out" 'grep -q "5556 " <<<"$out"'

office=$("$binary" glare "$2/../resources/scenes/office.json" --spp 128 --out "$tmp/ugr.csv" 2>/dev/null)
check "the office's two observers, each with its limit: $office" '[ $(grep -c "limit UGR_L 19: \(PASS\|FAIL\)" <<<"$office") -eq 2 ]'
check "their background from the interreflected light: $office" '[ $(grep -c "interreflected light at the eye" <<<"$office") -eq 2 ]'
check "the CSV has a row per observer" '[ $(wc -l <"$tmp/ugr.csv") -eq 3 ] && head -1 "$tmp/ugr.csv" | grep -q "^observer,x_m,y_m,z_m,view_x,view_y,view_z,Lb_cd_m2,UGR,limit,passes$"'
# --csv, the old name of --out, still writes the CSV, with a line saying what replaces it.
err=$("$binary" glare "$tmp/one.json" --observer 0,1.2,4 --view 0,0,-1 --background 20 --csv "$tmp/old.csv" 2>&1 >/dev/null); rc=$?
check "--csv still works with its deprecation line (exit $rc): $err" \
    '[ $rc -eq 0 ] && [ $(wc -l <"$tmp/old.csv") -eq 2 ] && grep -qF -- "--csv is now called --out" <<<"$err"'

expect "no glare observers" -- glare "$tmp/one.json"
expect "needs the background luminance" "has no surfaces" -- glare "$tmp/one.json" --observer 0,1.2,4 --view 0,0,-1
expect "a line of sight with a horizontal part" -- glare "$tmp/one.json" --observer 0,1.2,4 --view 0,1,0 --background 10
expect "--observer: expected X,Y,Z" -- glare "$tmp/one.json" --observer 0,1.2 --view 0,0,-1
expect_usage "missing --view" -- glare "$tmp/one.json" --observer 0,1.2,4
expect_usage "missing --observer" -- glare "$tmp/one.json" --view 0,0,-1
expect_usage "--limit goes with --observer and --view" -- glare "$tmp/one.json" --limit 19
expect_usage "missing scene.json" -- glare
expect_usage "unknown option --spacing" -- glare "$tmp/one.json" --spacing 1
expect_usage "--spacing-ratio goes with --table" -- glare "$tmp/one.json" --spacing-ratio 1

echo "glare: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
