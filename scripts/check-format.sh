#!/usr/bin/env bash
# The format check CI runs (STYLE.md; the rules are .clang-format's): every C++ file of the
# repository as clang-format would write it. Generated files (the GL loader) are left out.
# Fix with: git ls-files '*.cpp' '*.h' | grep -v '^renderer/gl/GlFunctions' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check-format: clang-format is missing (scripts/setup.sh installs it)"; exit 1; }
mapfile -t files < <(git ls-files '*.cpp' '*.h' | grep -v '^renderer/gl/GlFunctions\.')
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if clang-format --dry-run -Werror "${files[@]}" 2>"$log"; then
  echo "check-format: ${#files[@]} files as clang-format writes them"
else
  echo "check-format: $(grep -c "error:" "$log") places differ from clang-format's; the first:"
  head -20 "$log"
  exit 1
fi
