#!/usr/bin/env bash
# candela render --pane ... --sheet DIR: the comparison sheet headless (issue 7, part 5).
#   - a panel over a floor, its closed form (A) against Monte Carlo at 16 spp (B): the files
#     exist with the sheet's size, the exact pane errs by the reference's own noise alone and
#     less than the Monte Carlo one;
#   - the sidecar reproduces the sheet: its scene, panes, size and reference budget rendered
#     again give the same errors (same seeds, deterministic passes);
#   - bad input: unknown techniques, too many panes, --out with --sheet, a missing --sheet.
set -uo pipefail
binary=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0
passed=0

source "$(dirname "$0")/lib/expect.sh"  # expect SUBSTRING... -- ARGS

check() {  # check DESCRIPTION COMMAND...: counts a pass when the command succeeds
  local what=$1
  shift
  if "$@"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $what"; fi
}

# A floor under a Lambertian panel, nothing in between: "analytic" is exact there.
scene="$out/panel.json"
cat >"$scene" <<'JSON'
{"geometry": [{"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [6, 6]}, "albedo": [0.5, 0.6, 0.7]}],
 "luminaires": [{"type": "lambertian-rect", "name": "Panel", "size": [1, 0.5], "radiance": [10, 10, 10],
                 "position": [0.2, 2.5, -0.3], "aim": [0.1, -1, 0], "technique": "analytic"}],
 "camera": {"position": [0, 1.5, 4], "target": [0, 0.5, 0], "fov_deg": 50}}
JSON
args=(--pane "" --pane "lambertian-rect=reference:16" --size 96x64 --spp 16 --reference-spp 64)
if "$binary" render "$scene" --sheet "$out/a" "${args[@]}" >"$out/a.txt" 2>"$out/a.err"; then
  passed=$((passed + 1))
else
  failures=$((failures + 1))
  echo "FAIL: candela render --sheet: $(cat "$out/a.err")"
fi
check "sheet files" test -s "$out/a/sheet-000.png" -a -s "$out/a/sheet-000.exr" -a -s "$out/a/sheet-000.json"
check "printed the file names" grep -q "wrote $out/a/sheet-000.png" "$out/a.txt"
check "sheet PNG has the sidecar's size" python3 - "$out/a/sheet-000.json" \
  "$(identify -format '%w %h' "$out/a/sheet-000.png" 2>/dev/null)" <<'PY'
import json, sys
sys.exit(0 if " ".join(map(str, json.load(open(sys.argv[1]))["sheet_size"])) == sys.argv[2] else 1)
PY
check "the exact pane errs by the reference's noise, Monte Carlo by more" python3 - "$out/a/sheet-000.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
a, b = j["panes"]
noise = j["reference"]["noise_rel_rmse"]
print(f"render_sheet: A {a['techniques']} raw {a['rel_rmse_raw']:.4f}, B {b['techniques']} "
      f"{b['rel_rmse']:.4f}, reference noise {noise:.4f}")
ok = a["techniques"] == "analytic" and b["techniques"] == "reference" and b["spp"] == 16
ok = ok and j["reference"]["spp"] == 64 and j["render_size"] == [96, 64] and j["tiles"] == ["A", "B", "reference"]
# Against a noisy reference an exact image errs by that noise (20 %: the spread of the noise
# estimate from 6000 pixels, as in comparison_gltest); 16 spp against 64 adds twice the noise.
ok = ok and abs(a["rel_rmse_raw"] / noise - 1) < 0.2 and b["rel_rmse"] > 1.5 * noise
sys.exit(0 if ok else 1)
PY

# Reproduce from the sidecar alone: its scene and settings, rendered again.
python3 - "$out/a/sheet-000.json" "$out/again.json" "$out/again.args" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
json.dump(j["scene"], open(sys.argv[2], "w"))
args = []
for p in j["panes"]:
    args += ["--pane", f"{p['technique']}:{p['sample_budget']}"]
args += ["--size", "%dx%d" % tuple(j["render_size"]), "--reference-spp", str(j["reference"]["sample_budget"])]
open(sys.argv[3], "w").write("\n".join(args) + "\n")
PY
mapfile -t again <"$out/again.args"
if ("$binary" render "$out/again.json" --sheet "$out/b" "${again[@]}" \
      >"$out/b.txt" 2>"$out/b.err"); then
  check "the sidecar reproduces the errors" python3 - "$out/a/sheet-000.json" "$out/b/sheet-000.json" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
same = all(abs(p[k] - q[k]) <= 1e-9 * max(1.0, abs(p[k]))
           for p, q in zip(a["panes"], b["panes"]) for k in ("mean_delta_e", "rel_rmse", "spp"))
sys.exit(0 if same and a["reference"]["spp"] == b["reference"]["spp"] else 1)
PY
else
  failures=$((failures + 1))
  echo "FAIL: rendering the sidecar's scene again: $(cat "$out/b.err")"
fi

expect "no kind has a technique \"magic\"" -- render "$scene" --sheet "$out/c" --pane magic
expect "photometric has no technique \"analytic\"" -- render "$scene" --sheet "$out/c" --pane photometric=analytic
expect_usage "1 to 4 times" -- render "$scene" --sheet "$out/c" --pane "" --pane "" --pane "" --pane "" --pane ""
expect_usage "--out" "not of a comparison sheet" -- render "$scene" --sheet "$out/c" --pane "" --out "$out/c.png"
expect_usage "--sheet DIR" -- render "$scene" --pane ""
expect "expected an integer" -- render "$scene" --sheet "$out/c" --pane "analytic:many"
check "no sheet written for bad input" test ! -e "$out/c"

echo "render_sheet: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
