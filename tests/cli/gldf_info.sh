#!/usr/bin/env bash
# `candela info` on GLDF containers: the complete gldf.net container's product, variants, emitter
# ratings and maintenance, and its photometry's flux equal to `info` on the same .ldt extracted
# alone (Python's zipfile, not Candela's reader) within 0.1 %, and probed illuminance equal to the
# ldt's on CPU and GPU; a container without product.xml and a scene placing a variant; `grid` refuses to write onto the container.
set -uo pipefail
binary=$1
data="$2/data/gldf"
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
source "$2/cli/lib/expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

complete="$data/GldfWithFilesComplete.gldf"
info=$("$binary" info "$complete" 2>&1)
check "info on the complete container exits 0: $info" '[ $? -eq 0 ]'
check "manufacturer and product: $info" 'grep -qx "manufacturer: DIAL" <<<"$info" && grep -q "^product: Product name (product number Product number" <<<"$info"'
check "both variants listed: $info" '[ $(grep -c "^variant \"variant-[12]\"" <<<"$info") -eq 2 ]'
check "emitter with its photometry member: $info" 'grep -q "changeable light emitter, photometry \"photometry\": ldc/photometry.ldt" <<<"$info"'
check "rated flux, power and efficacy with units: $info" 'grep -q "rated luminous flux: 800 lm" <<<"$info" && grep -q "rated input power: 110 W" <<<"$info" && grep -q "luminous efficacy (rated flux / rated power): 7.273 lm/W" <<<"$info"'
check "light source maintenance: $info" 'grep -q "LLMF after 125 h: 0.9 (90.0 %)" <<<"$info" && grep -q "LSF after 150 h: 0.82 (82.0 %)" <<<"$info"'
check "photometry named inside the container: $info" 'grep -q "photometry: .*GldfWithFilesComplete.gldf:ldc/photometry.ldt" <<<"$info"'

python3 - "$complete" "$tmp/photometry.ldt" <<'PY'
import sys, zipfile
open(sys.argv[2], "wb").write(zipfile.ZipFile(sys.argv[1]).read("ldc/photometry.ldt"))
PY
alone=$("$binary" info "$tmp/photometry.ldt" 2>&1)
flux_alone=$(sed -n 's/^luminaire flux (exact quadrature of the table): \([0-9.e+]*\) lm$/\1/p' <<<"$alone")
flux_inside=$(sed -n 's/^luminaire flux (exact quadrature of the table): \([0-9.e+]*\) lm$/\1/p' <<<"$info" | head -1)
# 0.1 %: both figures are printed to 6 significant digits, so equal photometry prints equal
# numbers; the bound only absorbs the printing, not a difference in how the bytes were read.
check "flux inside ($flux_inside lm) equals the extracted ldt's ($flux_alone lm) within 0.1 %" \
  'python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); sys.exit(0 if a > 0 and abs(a - b) <= 1e-3 * a else 1)" "$flux_alone" "$flux_inside"'

expect "GldfWithMissingProduct.gldf: product.xml: missing" -- info "$data/GldfWithMissingProduct.gldf"
info=$("$binary" info "$data/GldfWithMissingFiles.gldf" 2>&1)
check "a missing member is reported per variant: $info" 'grep -qF "cannot be placed: $data/GldfWithMissingFiles.gldf: ldc/file.ldt (file \"eulumdat\", referenced by emitter \"emitter\"): not in the container" <<<"$info"'

# The same light from the container and from its ldt extracted alone: every technique probes the
# same illuminance, on the CPU and on the GPU (the same table through the same photometric code,
# so the printed figures are identical; the reference's fixed seed makes it repeatable too).
cat > "$tmp/ldt_scene.json" <<'JSON'
{"luminaires": [{"type": "photometric", "file": "photometry.ldt", "position": [0, 3, 0], "aim": [0, -1, 0]}]}
JSON
cp "$complete" "$tmp/lamp.gldf"
cat > "$tmp/gldf_scene.json" <<'JSON'
{"luminaires": [{"type": "gldf", "file": "lamp.gldf", "position": [0, 3, 0], "aim": [0, -1, 0]}]}
JSON
for device in cpu gpu; do
  for t in hybrid point reference; do
    a=$("$binary" probe "$tmp/ldt_scene.json" --points "$2/data/photometric/far_points.csv" --technique $t --spp 256 --device $device 2>/dev/null)
    b=$("$binary" probe "$tmp/gldf_scene.json" --points "$2/data/photometric/far_points.csv" --technique $t --spp 256 --device $device 2>/dev/null)
    check "probe $t on $device: the GLDF variant lights like its ldt ($b vs $a)" '[ "$a" = "$b" ] && [ $(wc -l <<<"$b") -eq 5 ]'
  done
done

cat > "$tmp/scene.json" <<'JSON'
{"luminaires": [{"type": "gldf", "file": "lamp.gldf", "variant": "variant-2", "position": [0, 3, 0]}]}
JSON
info=$("$binary" info "$tmp/scene.json" 2>&1)
check "a scene places a GLDF variant: $info" 'grep -q "GLDF lamp.gldf variant \"variant-2\" (DIAL Product name): EULUMDAT" <<<"$info"'
expect "lamp.gldf: " "would overwrite this input of the command" -- \
  grid "$tmp/scene.json" --plane y=0 --spacing 1 --csv "$tmp/lamp.gldf"
check "the container is untouched" 'cmp -s "$complete" "$tmp/lamp.gldf"'

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
