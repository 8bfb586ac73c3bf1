#!/usr/bin/env bash
# `candela probe` on a light-field luminaire: every sampling technique agrees with the quadrature
# reference (a different code path: Gauss-Legendre over U) within 1 % or 4 standard errors at
# 20000 spp, including a grazing receiver 1 mm beyond S; `info` reports the luminaire; a missing
# light-field file is a clear error.
set -uo pipefail
binary=$1
data="$2/data/lightfield"
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }

ref=$("$binary" probe "$data/scene.json" --points "$data/points.csv" --technique reference) || failures=$((failures + 1))
for t in restricted-cdf uniform-restricted precomputed-global; do
  out=$("$binary" probe "$data/scene.json" --points "$data/points.csv" --technique "$t" --spp 20000)
  bad=$(paste -d, <(tail -n +2 <<<"$ref") <(tail -n +2 <<<"$out") | awk -F, '{
      r = $7; e = $18; se = $22; tol = 0.01 * r; if (4 * se > tol) tol = 4 * se;
      d = e - r; if (d < 0) d = -d; if (d > tol + 1e-12 || e != e) print NR ": " e " vs " r " (tol " tol ")" }')
  check "$t agrees with reference: $bad" '[ -z "$bad" ]'
done
info=$("$binary" info "$data/scene.json" 2>&1)
check "info lists the light field: $info" 'grep -q "3x3 images of 8x8 RGB" <<<"$info" && grep -q "flux" <<<"$info"'
info=$("$binary" info "$data/tiny.lf.json" 2>&1)
check "info describes the .lf.json itself: $info" 'grep -q "9 of 8x8 pixels, RGB" <<<"$info" && grep -q "3x3, spacing 20 x 20 mm" <<<"$info" && grep -q "^flux.* W$" <<<"$info" && grep -q "precomputation" <<<"$info"'
err=$("$binary" info "$data/missing_file.json" 2>&1 >/dev/null); rc=$?
check "missing light-field file (rc $rc): $err" '[ $rc -eq 1 ] && grep -q "nowhere.lf.json" <<<"$err"'
# Rendering: a floor and the light field, no occluder and no glossy material, so exactly the
# G-buffer, one restricted-CDF shading pass without SHADOWS or GLOSSY, resolve and tone mapping.
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
stats=$("$binary" render "$data/scene.json" --out "$out/lf.exr" --size 64x48 --spp 16 --stats 2>&1)
passes=$(sed -n '/^pass,/,/^variants/p' <<<"$stats" | grep -v '^pass,\|^variants' | cut -d, -f1 | tr '\n' ' ')
check "pass list [$passes]" '[ "$passes" = "gbuffer shade:Tiny:restricted-cdf resolve tonemap " ]'
check "variants: $(grep variants <<<"$stats")" 'grep -q "lightfield_restricted_cdf.frag " <<<"$stats" && ! grep -q "SHADOWS\|GLOSSY" <<<"$stats"'
check "EXR written" '[ -s "$out/lf.exr" ]'
err=$("$binary" render "$data/scene.json" --out "$out/ref.png" --technique reference 2>&1 >/dev/null); rc=$?
check "reference is CPU only (rc $rc): $err" '[ $rc -eq 1 ] && grep -q "CPU only" <<<"$err" && [ ! -e "$out/ref.png" ]'

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
