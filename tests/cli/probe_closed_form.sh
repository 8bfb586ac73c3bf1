#!/usr/bin/env bash
# candela probe on a Lambertian rectangle against independent closed forms and quadrature.
set -euo pipefail
binary=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
python3 "$(dirname "$0")/probe_closed_form.py" "$binary" "$dir"
