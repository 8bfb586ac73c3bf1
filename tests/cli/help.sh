#!/usr/bin/env bash
# Every command explains itself: `candela --help` lists the commands, and for each of them
# `candela CMD --help` and `candela help CMD` print the same usage with an example whose files
# exist; every option its forms and example name is one it declares; `--version` names the version
# and the commit; an unknown command exits 2 with the list.
set -uo pipefail
binary=$1
source_dir=$(cd "$2/.." && pwd)
failures=0
passed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL: $1"; fi; }

list=$("$binary" --help); rc=$?
check "--help exits 0 (rc $rc)" '[ $rc -eq 0 ]'
commands=$(awk '/^  [a-z]+  / {print $1}' <<<"$list")
check "--help lists the thirteen commands: $(tr '\n' ' ' <<<"$commands")" \
  '[ "$(wc -l <<<"$commands")" -eq 13 ]'
for command in $commands; do
  help=$("$binary" "$command" --help); rc=$?
  check "$command --help exits 0 (rc $rc)" '[ $rc -eq 0 ]'
  check "$command --help has its usage and an example" \
    'grep -q "^  candela $command " <<<"$help" && grep -q "^example:" <<<"$help"'
  check "help $command prints what $command --help does" '[ "$("$binary" help "$command")" = "$help" ]'
  # The example's files are in the repository (a newcomer can run it as it stands).
  example=$(sed -n '/^example:/{n;p}' <<<"$help")
  for word in $example; do
    case "$word" in
      resources/* | tests/*)
        check "$command's example names $word, which exists" '[ -e "$source_dir/$word" ]' ;;
    esac
  done
  # Every option the forms name is one the command declares (listed under its options), and the
  # example runs no option the command lacks.
  declared=$(grep -oE '^  (--[a-z][a-z0-9-]*|-h, --help)' <<<"$help" | sed 's/^  //')
  forms=$(sed -n '/^usage:/,/^$/p' <<<"$help"; sed -n '/^example:/{n;p}' <<<"$help")
  for option in $(grep -oE '(^|[][ |])--[a-z][a-z0-9-]*' <<<"$forms" | grep -oE -- '--[a-z0-9-]+' |
                  sort -u); do
    check "$command: $option in its forms or example is declared" \
      'grep -qxF -- "$option" <<<"$declared"'
  done
done
version=$("$binary" --version); rc=$?
check "--version (rc $rc): $version" '[ $rc -eq 0 ] && grep -Eq "^candela [0-9]+\.[0-9]+\.[0-9]+ \(commit [0-9a-f]+|unknown\)" <<<"$version"'
err=$("$binary" nonsense 2>&1 >/dev/null); rc=$?
check "an unknown command exits 2 and lists the commands (rc $rc)" \
  '[ $rc -eq 2 ] && grep -q "unknown command \"nonsense\"" <<<"$err" && grep -q "^  grid " <<<"$err"'
err=$("$binary" help nonsense 2>&1 >/dev/null); rc=$?
check "help of an unknown command exits 2 (rc $rc)" '[ $rc -eq 2 ]'
echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
