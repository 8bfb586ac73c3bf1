# Shared by the CLI test scripts (sourced, not run; it is not a test itself). The caller sets
# `binary` and initialises `passed` and `failures` to 0.

# expect EXPECTED_SUBSTRING... -- ARGS: runs candela ARGS, wants exit 1 (EXPECT_RC, when set)
# and every substring in what it prints on stderr.
expect() {
  local wants=()
  while [ "$1" != "--" ]; do wants+=("$1"); shift; done
  shift
  local err
  err=$("$binary" "$@" 2>&1 >/dev/null)
  local rc=$?
  local ok=1
  [ $rc -eq "${EXPECT_RC:-1}" ] || ok=0
  for w in "${wants[@]}"; do
    grep -qF -- "$w" <<<"$err" || ok=0
  done
  if [ $ok -eq 1 ]; then
    passed=$((passed + 1))
  else
    failures=$((failures + 1))
    echo "FAIL: candela $* (exit $rc) wanted [${wants[*]}], got: $err"
  fi
}

# expect_usage EXPECTED_SUBSTRING... -- ARGS: bad usage (an unknown option, a missing argument):
# exit 2, the substrings, and the command's usage after the error.
expect_usage() {
  local wants=()
  while [ "$1" != "--" ]; do wants+=("$1"); shift; done
  EXPECT_RC=2 expect "${wants[@]}" "usage:" "$@"
}
