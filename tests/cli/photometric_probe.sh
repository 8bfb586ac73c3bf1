#!/usr/bin/env bash
# `candela probe` on a photometric luminaire (a Lambertian 1000 cos(gamma) cd table on a 0.6 x 0.3 m
# opening, 3 m up, aimed down): beyond ten opening sizes every technique agrees with the point law
# I(w) cos / d^2 computed here in Python from the closed form (not from the file's table), within
# 1 % (the reference also within 4 of its standard errors), on the CPU and on the GPU. `info`
# reports the flux of IES and EULUMDAT files; bad photometric input gives clear errors.
set -uo pipefail
binary=$1
data="$2/data/photometric"
photometry="$2/data/photometry"
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }
source "$2/cli/lib/expect.sh"

law=$(python3 - "$data/far_points.csv" <<'PY'
import csv, math, sys
for row in csv.DictReader(open(sys.argv[1])):
    p = [float(row[k]) for k in "xyz"]; n = [float(row["n" + k]) for k in "xyz"]
    v = [0 - p[0], 3 - p[1], 0 - p[2]]            # receiver -> luminaire centre
    d = math.sqrt(sum(c * c for c in v))
    cos_gamma = (3 - p[1]) / d                    # (p - c) / d along the aim, -y
    intensity = 1000 * max(cos_gamma, 0)
    cos_r = max(sum(a * b for a, b in zip(n, v)) / d, 0)
    print(intensity * cos_r / d ** 2)
PY
)
for device in cpu gpu; do
  for t in reference point scattered mc-poisson-24 hybrid adaptive; do
    out=$("$binary" probe "$data/probe_scene.json" --points "$data/far_points.csv" --technique "$t" --spp 20000 --device $device 2>/dev/null)
    bad=$(paste -d, <(tail -n +2 <<<"$out") <(echo "$law") | awk -F, '{
        e = $7; se = $11; r = $12; tol = 0.01 * r + 4 * se;
        d = e - r; if (d < 0) d = -d; if (d > tol || e != e) print NR ": " e " vs " r " (tol " tol ")" }')
    check "$t on $device agrees with I cos / d^2: $bad" '[ -z "$bad" ] && [ $(wc -l <<<"$out") -eq 5 ]'
  done
done
info=$("$binary" info "$photometry/ldt/lidrs/example.ldt" 2>&1)
check "info on an EULUMDAT file: $info" 'grep -q "luminaire flux (exact quadrature of the table): 5136.1" <<<"$info" && grep -q "lamp flux 5134 lm x light output ratio 1 = 5134 lm" <<<"$info"'
info=$("$binary" info "$data/probe_scene.json" 2>&1)
check "info on a scene lists the photometric luminaire: $info" 'grep -q "photometric .*lambert.ies: IES LM-63-2002, type C" <<<"$info" && grep -q "flux 3141.6 lm" <<<"$info"'

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The light output ratio as designers read it (luminaire flux / lamp flux), and a warning where the
# file's own figures disagree (by more than 1 %). lambert.ies's table holds 3141.57 lm (pi x 1000
# lm, less what interpolating linearly between its 0.5-degree samples loses).
info=$("$binary" info "$photometry/ldt/lidrs/example.ldt" 2>&1)
check "LOR of an EULUMDAT file that agrees with itself: $info" \
  'grep -qF "light output ratio (luminaire flux / lamp flux): 100.0 % (5136.13 lm / 5134 lm; the file declares 100 %)" <<<"$info" && ! grep -q "declares a light output ratio" <<<"$info"'
# info on a copy of FILE edited by the sed expression EXPR, written to $tmp/NAME.
info_of_edit() {  # NAME FILE EXPR
  sed "$3" "$2" >"$tmp/$1"
  "$binary" info "$tmp/$1" 2>&1
}
info=$(info_of_edit lor60.ldt "$photometry/lenient/lorl_zero.ldt" '23s/.*/60/')
check "LORL 60 % against a table of 99.9 % warns: $info" \
  'grep -qF "warning: $tmp/lor60.ldt: the file declares a light output ratio of 60 % but its table gives 99.9 % of the lamp flux" <<<"$info"'
info=$(info_of_edit lor995.ldt "$photometry/lenient/lorl_zero.ldt" '23s/.*/99.5/')
check "LORL 99.5 % against 99.9 % is within 1 %: $info" '! grep -q "declares a light output ratio" <<<"$info"'
info=$(info_of_edit lamp4000.ies "$data/lambert.ies" '5s/^1 -1 1 /1 4000 1 /')
check "IES with 4000 lamp lumens: LOR 78.5 %, no warning: $info" \
  'grep -qF "light output ratio (luminaire flux / lamp flux): 78.5 % (3141.57 lm / 4000 lm)" <<<"$info" && ! grep -q "^warning" <<<"$info"'
info=$(info_of_edit lamp2000.ies "$data/lambert.ies" '5s/^1 -1 1 /1 2000 1 /')
check "IES whose table outshines its lamps warns: $info" \
  'grep -qF "warning: $tmp/lamp2000.ies: the table'"'"'s flux is 157.1 % of the rated lamp flux" <<<"$info"'
info=$("$binary" info "$data/lambert.ies" 2>&1)
check "absolute photometry states no ratio: $info" '! grep -q "light output ratio" <<<"$info"'

sed 's/lambert.ies/nowhere.ies/' "$data/probe_scene.json" > "$tmp/missing.json"
expect "nowhere.ies" "no such file" -- probe "$tmp/missing.json" --points "$data/far_points.csv"
echo "not photometry" > "$tmp/light.txt"
sed "s|lambert.ies|$tmp/light.txt|" "$data/probe_scene.json" > "$tmp/badext.json"
expect "light.txt" ".ies" ".ldt" -- probe "$tmp/badext.json" --points "$data/far_points.csv"
expect "Truncated Profile - 01.IES:24" "expected 10 values" -- info "$photometry/ies/ies_rescale/Truncated Profile - 01.IES"
expect "Invalid Profile - 01.ies:1" "TILT" -- info "$photometry/ies/ies_rescale/Invalid Profile - 01.ies"

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
