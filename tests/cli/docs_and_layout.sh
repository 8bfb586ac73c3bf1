#!/usr/bin/env bash
# The guide and the code's shape: README.md and docs/ tell no history (no dates, commit hashes or
# issue references) and show only commands and options the binary has (scripts/check-docs.py);
# the README's command list names exactly the commands of `candela --help`; every #include points
# down the layers of docs/architecture.md (scripts/check-layout.py); pi is defined once in C++.
set -uo pipefail
binary=$1
source_dir=$(cd "$2/.." && pwd)
failures=0
check() { if eval "$2"; then echo "ok: $1"; else failures=$((failures + 1)); echo "FAIL: $1"; fi; }

check "no history in README.md and docs/" 'python3 "$source_dir/scripts/check-docs.py"'
check "every command the docs show exists with the options they give" \
  'python3 "$source_dir/scripts/check-docs.py" --commands "$binary"'
check "every include points down the layers" 'python3 "$source_dir/scripts/check-layout.py"'

# The README's "Command line" section has a line for each command of the table ("- `CMD ...`: ..."),
# and no other.
listed=$("$binary" --help | awk '/^  [a-z]+  / {print $1}' | sort)
readme=$(sed -n '/^## Command line/,/^## /p' "$source_dir/README.md" |
  grep -oE '^- `[a-z]+' | cut -c4- | sort -u)
check "README.md's command list is the command table's ($(tr '\n' ' ' <<<"$readme"))" \
  '[ "$listed" = "$readme" ]'

# One definition of pi in the C++ sources (shaders/shared/Constants.h), tests included.
defs=$(cd "$source_dir" && git ls-files '*.h' '*.cpp' |
  xargs grep -nE '\b(kPi|kPI|PI|pi)\b *= *3\.14|#define +\w*PI\w* +3\.14' || true)
check "pi is defined once: $(tr '\n' ';' <<<"$defs")" '[ "$(grep -c . <<<"$defs")" -eq 1 ]'

[ $failures -eq 0 ] || { echo "$failures check(s) failed"; exit 1; }
