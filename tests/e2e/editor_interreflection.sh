#!/usr/bin/env bash
# End-to-end test of interreflected light in the editor (issue 17, part 3), with real X input
# under Xvfb, on the shipped office (six downlights, reflectances 0.7 / 0.5 / 0.2, a desk), the
# camera looking up at the ceiling, which the downlights do not light directly:
#   1. wait until the interreflection has converged; Screenshot (shot-000.exr);
#   2. check that nothing refines once converged: over 20 frames no pass runs, the solution's
#      version and the worker stay as they were;
#   3. drag one downlight 150 px to the right; wait for the interreflection to converge again
#      (a newer solution) and the image; Screenshot (shot-001.exr);
#   4. the ceiling above the moved downlight's new place got brighter (its light now reflects from
#      the floor below it), by more than the run-to-run noise; the ceiling far from it is nearly
#      unchanged; and every ceiling pixel is lit (a black ceiling is what direct light alone gives).
# Usage: bash tests/e2e/editor_interreflection.sh /path/to/candela /path/to/tests
set -euo pipefail

CANDELA=${1:?usage: editor_interreflection.sh /path/to/candela /path/to/tests}
TESTS=${2:?usage: editor_interreflection.sh /path/to/candela /path/to/tests}
SOURCE=$(cd "$TESTS/.." && pwd)
DRAG_PX=150        # horizontal drag, window pixels
TIMEOUT_S=240      # longest wait for any one step (form factors and a refinement on 2 shared cores)

E2E_NAME=editor_interreflection
source "$(dirname "$0")/lib/harness.sh"
e2e_setup
e2e_start_xvfb 1280x800

# The office seen from below its ceiling (luminaire paths made absolute for the copy in TMP).
python3 - "$SOURCE/resources/scenes/office.json" "$TMP/office.json" <<'PY'
import json, os, sys
scene = json.load(open(sys.argv[1]))
base = os.path.dirname(os.path.abspath(sys.argv[1]))
for l in scene["luminaires"]:
    l["file"] = os.path.normpath(os.path.join(base, l["file"]))
scene["camera"] = {"position": [0.0, 0.6, 1.7], "target": [0.0, 2.8, -0.6], "fov_deg": 75}
json.dump(scene, open(sys.argv[2], "w"), indent=1)
PY

e2e_start_editor "$TMP/office.json" 1280x800 "len(d['luminaires']) == 6 and d['frame'] >= 2"
converged="d['interreflection']['converged'] and not d['interreflection']['busy'] and d['converged']"
wait_until "the interreflection to converge" "$converged and d['interreflection']['present']"
log "converged: $(layout "d['interreflection']")"

# --- 1. Screenshot --------------------------------------------------------------------------------
read -r BX BY < <(layout "'%d %d' % tuple(round(c) for c in d['screenshot_button'])")
move_to "$BX" "$BY"
xdotool click 1
wait_for_file "$SHOTS/shot-000.json"
read -r VERSION UPDATES < <(layout "'%d %d' % (d['interreflection']['version'], d['interreflection']['updates'])")

# --- 2. Nothing refines once converged ------------------------------------------------------------
# (The pointer parks over the Screenshot button: no hover over the viewport changes anything.)
f0=$(layout "d['frame']")
for ((i = 0; i < 20; i++)); do
    wait_frames 1
    layout "len(d['passes']) == 0 and not d['interreflection']['busy'] and d['interreflection']['version'] == $VERSION" ||
        fail "frame $(layout "d['frame']") (converged since $f0) ran $(layout "d['passes']") or the interreflection worked: $(layout "d['interreflection']")"
done
log "20 frames after convergence: no pass, no interreflection work (version $VERSION)"

# --- 3. Drag a downlight --------------------------------------------------------------------------
NAME="Downlight 2"  # the middle one of the back row, over the desk
read -r LX LY < <(layout "'%d %d' % tuple(round(c) for c in lum('$NAME')['screen'])")
log "\"$NAME\" at ($LX, $LY)"
e2e_drag "$NAME" "$LX" "$LY" "$DRAG_PX"
wait_until "the end of the drag" "not d['dragging']"
wait_until "a newer converged interreflection" "$converged and d['interreflection']['version'] > $VERSION"
log "converged again: $(layout "d['interreflection']")"
move_to "$BX" "$BY"
xdotool click 1
wait_for_file "$SHOTS/shot-001.json"

# --- 4. The ceiling changed above the moved downlight, little far from it --------------------------
for n in 000 001; do oiiotool --dumpdata "$SHOTS/shot-$n.exr" >"$TMP/shot-$n.txt" || fail "cannot read shot-$n.exr"; done
python3 - "$TMP/shot-000.txt" "$TMP/shot-001.txt" "$SHOTS/shot-000.json" "$SHOTS/shot-001.json" \
    "$TESTS/e2e/lib" "$NAME" <<'PY' || fail "the ceiling did not change as expected"
import json, math, sys
sys.path.insert(0, sys.argv[5])
from camera import project

def read_dump(path):
    """Linear luminance per pixel, rows top to bottom, from `oiiotool --dumpdata` ("Pixel (x, y): r g b")."""
    values = {}
    for line in open(path):
        line = line.strip()
        if not line.startswith("Pixel ("): continue
        where, rgb = line[len("Pixel ("):].split("):")
        x, y = map(int, where.split(","))
        r, g, b = map(float, rgb.split()[:3])
        values[(x, y)] = 0.2126 * r + 0.7152 * g + 0.0722 * b
    w = 1 + max(x for x, y in values)
    h = 1 + max(y for x, y in values)
    return w, h, [[values[(x, y)] for x in range(w)] for y in range(h)]

w, h, before = read_dump(sys.argv[1])
_, _, after = read_dump(sys.argv[2])
side0, side1 = (json.load(open(p)) for p in sys.argv[3:5])
name = sys.argv[6]
old = next(l for l in side0["luminaires"] if l["name"] == name)["position"]
new = next(l for l in side1["luminaires"] if l["name"] == name)["position"]
print("%s moved from %s to %s (m)" % (name, [round(c, 3) for c in old], [round(c, 3) for c in new]))
# Ceiling pixels: where a ray through the pixel meets the ceiling plane y = 2.8 inside the room
# (6 x 4 m) before anything else could (the camera looks up at it; the walls lie outside that
# rectangle). Luminaire openings (within 0.15 m of any downlight) are left out: they show emission.
cam = side0["camera"]
def ceiling_point(px, py):
    # Inverse of camera.project on the plane y = 2.8: march along the ray in closed form.
    f = [t - p for t, p in zip(cam["target"], cam["position"])]
    n = math.sqrt(sum(c * c for c in f)); f = [c / n for c in f]
    r = [f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0]
    n = math.sqrt(sum(c * c for c in r)); r = [c / n for c in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    t = math.tan(math.radians(cam["fov_deg"]) / 2)
    sx = ((px + 0.5) / w * 2 - 1) * t * w / h
    sy = (1 - (py + 0.5) / h * 2) * t
    d = [f[i] + sx * r[i] + sy * u[i] for i in range(3)]
    if d[1] <= 1e-9: return None
    k = (2.8 - cam["position"][1]) / d[1]
    q = [cam["position"][i] + k * d[i] for i in range(3)]
    return q if abs(q[0]) < 2.95 and abs(q[2]) < 1.95 else None
lights = [l["position"] for l in side0["luminaires"]] + [new]
near, far, ceiling = [], [], []
for py in range(h):
    for px in range(w):
        q = ceiling_point(px, py)
        if q is None or any(math.hypot(q[0] - l[0], q[2] - l[2]) < 0.15 for l in lights): continue
        ceiling.append(after[py][px])
        dn = math.hypot(q[0] - new[0], q[2] - new[2])
        do = math.hypot(q[0] - old[0], q[2] - old[2])
        if dn < 0.6 and do > dn + 0.3: near.append((before[py][px], after[py][px]))
        if dn > 2.0 and do > 2.0: far.append((before[py][px], after[py][px]))
fail = []
if len(ceiling) < 0.3 * w * h: fail.append("only %d of %d pixels show the ceiling" % (len(ceiling), w * h))
if len(near) < 50 or len(far) < 50: fail.append("%d pixels near the new place, %d far (want 50 each)" % (len(near), len(far)))
mean = lambda v: sum(v) / max(1, len(v))
nb, na = mean([b for b, a in near]), mean([a for b, a in near])
fb, fa = mean([b for b, a in far]), mean([a for b, a in far])
dark = min(ceiling) if ceiling else 0.0
print("ceiling near the new place: %.4g -> %.4g (%+.2f %%); far from both: %.4g -> %.4g (%+.2f %%); darkest ceiling "
      "pixel %.4g" % (nb, na, 100 * (na / nb - 1), fb, fa, 100 * (fa / fb - 1), dark))
# The interreflection is deterministic for a given scene (its samples are seeded by the sources),
# so what changed is the move: the ceiling near the new place must brighten by over 1 % and by
# more than the far ceiling changes.
if not (na > 1.01 * nb and na / nb - 1 > abs(fa / fb - 1) + 0.005):
    fail.append("the ceiling near the moved downlight did not brighten more than the far ceiling changed")
if not dark > 0.0: fail.append("a ceiling pixel is black (no interreflected light)")
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
PY
PASSED=1
log "passed"
