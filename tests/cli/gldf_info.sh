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
# The product rates its light source at 800 lm; its photometry was measured with 6300 lm of lamps.
check "the rated flux against the photometry's, with the one used: $info" 'grep -qF "GldfWithFilesComplete.gldf:ldc/photometry.ldt: the product rates its light source at 800 lm, but the photometry was measured with 6300 lm of lamps (-87.3 %); Candela uses the table'"'"'s 4048.7 lm" <<<"$info"'

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
# same illuminance, on the CPU and on the GPU (the same table through the same photometric code;
# the reference's fixed seed makes it repeatable too). The container's emitter has a <Rotation>
# of X 1, Y 2, Z 3, G0 4 degrees: the ldt is aimed as Candela reads it (docs/luminaire-files.md, "GLDF luminaires"), worked
# out here with rotation matrices: G0 about the aim, then Rz Rx Ry in the luminaire frame (z up;
# at this pose its x is world x, y world -z, z world y).
python3 - "$tmp/ldt_scene.json" <<'PY'
import json, math, sys
d = math.radians
def rx(a): c, s = math.cos(d(a)), math.sin(d(a)); return [[1, 0, 0], [0, c, -s], [0, s, c]]
def ry(a): c, s = math.cos(d(a)), math.sin(d(a)); return [[c, 0, s], [0, 1, 0], [-s, 0, c]]
def rz(a): c, s = math.cos(d(a)), math.sin(d(a)); return [[c, -s, 0], [s, c, 0], [0, 0, 1]]
def mul(a, b): return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def apply(m, v): return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]
r = mul(rz(3), mul(rx(1), ry(2)))
aim = apply(r, [0, 0, -1])
c0 = apply(r, [math.cos(d(4)), math.sin(d(4)), 0])  # G0 4: C0 towards C90 (+y)
world = lambda v: [v[0], v[2], -v[1]]
json.dump({"luminaires": [{"type": "photometric", "file": "photometry.ldt", "position": [0, 3, 0],
                           "aim": world(aim), "c0": world(c0)}]}, open(sys.argv[1], "w"))
PY
cp "$complete" "$tmp/lamp.gldf"
cat > "$tmp/gldf_scene.json" <<'JSON'
{"luminaires": [{"type": "gldf", "file": "lamp.gldf", "position": [0, 3, 0], "aim": [0, -1, 0]}]}
JSON
same() {  # same A B: the probes' E columns agree within 1e-9 (the two frames differ by rounding)
  python3 - "$1" "$2" <<'PY'
import sys
a, b = [l.split(",") for l in sys.argv[1].split()], [l.split(",") for l in sys.argv[2].split()]
sys.exit(0 if len(a) == len(b) == 5 and a[0] == b[0] and
         all(abs(float(x[6]) - float(y[6])) <= 1e-9 * abs(float(x[6])) + 1e-12 for x, y in zip(a[1:], b[1:])) else 1)
PY
}
for device in cpu gpu; do
  for t in adaptive point reference; do
    a=$("$binary" probe "$tmp/ldt_scene.json" --points "$2/data/photometric/far_points.csv" --technique $t --spp 256 --device $device 2>/dev/null)
    b=$("$binary" probe "$tmp/gldf_scene.json" --points "$2/data/photometric/far_points.csv" --technique $t --spp 256 --device $device 2>/dev/null)
    check "probe $t on $device: the GLDF variant lights like its ldt ($b vs $a)" 'same "$a" "$b"'
  done
done
# And the rotation matters: the ldt aimed straight down lights the points otherwise.
straight=$("$binary" probe "$tmp/gldf_scene.json" --points "$2/data/photometric/far_points.csv" --technique point 2>/dev/null)
cat > "$tmp/down.json" <<'JSON'
{"luminaires": [{"type": "photometric", "file": "photometry.ldt", "position": [0, 3, 0], "aim": [0, -1, 0]}]}
JSON
down=$("$binary" probe "$tmp/down.json" --points "$2/data/photometric/far_points.csv" --technique point 2>/dev/null)
check "the emitter's rotation changes the light ($straight vs $down)" '! same "$straight" "$down"'
info=$("$binary" info "$complete" 2>&1)
check "info states the rotation and how it is read: $info" 'grep -q "rotation: X 1 deg, Y 2 deg, Z 3 deg, G0 4 deg (applied" <<<"$info" && grep -q "rotation: X 5 deg, Y 6 deg, Z 7 deg, G0 8 deg (not placed)" <<<"$info"'

cat > "$tmp/scene.json" <<'JSON'
{"luminaires": [{"type": "gldf", "file": "lamp.gldf", "variant": "variant-2", "position": [0, 3, 0]}]}
JSON
info=$("$binary" info "$tmp/scene.json" 2>&1)
check "a scene places a GLDF variant: $info" 'grep -q "GLDF lamp.gldf variant \"variant-2\" (DIAL Product name): EULUMDAT" <<<"$info"'
"$binary" report "$tmp/scene.json" --out "$tmp/report.pdf" --no-view >/dev/null 2>&1
report=$(pdftotext "$tmp/report.pdf" - 2>&1 | tr '\n' ' ')
check "the report states the product's disagreeing figures, without the file: $report" 'grep -qF "Data check: the product rates its light source at 800 lm, but the photometry was measured with 6300 lm of lamps (-87.3 %); Candela uses the table'"'"'s 4048.7 lm." <<<"$report"'
expect "lamp.gldf: " "would overwrite this input of the command" -- \
  grid "$tmp/scene.json" --plane y=0 --spacing 1 --out "$tmp/lamp.gldf"
check "the container is untouched" 'cmp -s "$complete" "$tmp/lamp.gldf"'

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
