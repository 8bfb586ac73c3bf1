#!/usr/bin/env bash
# Coverage-guided fuzzing of every parser (issue 18, part 4; fuzz/). Builds the libFuzzer targets
# with clang, AddressSanitizer and UBSan into build-fuzz/, replays every regression input and seed
# (ctest in build-fuzz), then fuzzes each target for a bounded time, starting from the seeds and
# the corpus earlier runs kept in build-fuzz/corpus/TARGET/. Prints, per target, the executions,
# executions per second, corpus size and crashes; exits 1 if any target crashed (the input is in
# build-fuzz/crashes/TARGET/, emptied when the target runs again: fix the parser, then add the
# input to fuzz/regressions/TARGET/).
#
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
#   SECONDS_PER_TARGET: default $FUZZ_SECONDS or 60; 0 only builds and replays.
#   TARGET: ies ldt tm25 lightfield scene gltf image gldf (default: all).
# Environment: FUZZ_RUNS (stop a target after this many executions as well), FUZZ_SUMMARY (a file
# to append the table to), FUZZ_NO_BUILD=1 (skip the build and the replay: for several runs side by
# side on a build made before), FUZZ_TAG (a suffix for the log, seed and crash folders: two runs of one
# target side by side, sharing its corpus, each on a core).
set -euo pipefail
cd "$(dirname "$0")/.."
source fuzz/targets.sh
seconds=${1:-${FUZZ_SECONDS:-60}}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${FUZZ_TARGETS[@]}")
build=build-fuzz
# The targets that read files write each input to a scratch file: in memory when /dev/shm is there
# (ten times faster than a disk-backed /tmp).
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi
# A quarter of ASan's default quarantine (freed memory held back to catch uses after free):
# recycling the default 256 MB stalled the fuzzers for over 25 s on a loaded 2-core machine, which
# libFuzzer then reported as timeouts of inputs that run in milliseconds.
export ASAN_OPTIONS=${ASAN_OPTIONS:-quarantine_size_mb=64}

if [ -z "${FUZZ_NO_BUILD:-}" ]; then
  command -v clang++ >/dev/null || { echo "fuzz: clang++ is missing (scripts/setup.sh installs it)"; exit 1; }
  CC=clang CXX=clang++ cmake -S . -B "$build" -DCANDELA_FUZZ=ON -DCMAKE_BUILD_TYPE=Release >/dev/null
  echo "fuzz: building the targets in $build (log $build/build.log)"
  cmake --build "$build" -j"$(nproc)" >"$build/build.log" 2>&1 || { tail -40 "$build/build.log"; exit 1; }
  echo "fuzz: replaying the regression inputs and seeds"
  ctest --test-dir "$build" --output-on-failure -j"$(nproc)"
fi
[ "$seconds" -gt 0 ] || exit 0

summary=$(mktemp)
trap 'rm -f "$summary"' EXIT
printf "%-11s %12s %9s %8s %8s %8s %6s\n" target executions exec/s seconds corpus crashes slow >"$summary"
failed=0
tag=${FUZZ_TAG:-}
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t" seeds="$build/seeds/$t$tag" crashes="$build/crashes/$t$tag"
  mkdir -p "$corpus"
  rm -rf "$seeds" "$crashes" && mkdir -p "$seeds" "$crashes"
  while IFS= read -r -d '' f; do cp "$f" "$seeds/$(tr '/ ' '__' <<<"$f")"; done < <(fuzz_seeds "$t")
  # -timeout: an input running a minute is a hang (every target takes milliseconds per input).
  # The image target gets 4 GB: OpenEXR decodes some 1 KB files through tens of thousands of
  # small buffers, which ASan's quarantine held at 2 GB (a 1133-byte EXR found on 2026-11-26
  # peaked at 2.4 GB for 5.5 s with no finding; 54 MB of it was live).
  rss=2048
  [ "$t" = image ] && rss=4096
  args=(-max_total_time="$seconds" -max_len="$(fuzz_max_len "$t")" -rss_limit_mb="$rss" -timeout=60
        -artifact_prefix="$crashes/" -print_final_stats=1)
  [ -n "$(fuzz_dict "$t")" ] && args+=(-dict="$(fuzz_dict "$t")")
  [ -n "${FUZZ_RUNS:-}" ] && args+=(-runs="$FUZZ_RUNS")
  log="$build/fuzz-$t$tag.log"
  echo "fuzz: $t for ${seconds} s (log $log)"
  rc=0 start=$(date +%s)
  "$build/fuzz/fuzz_$t" "${args[@]}" "$corpus" "$seeds" >"$log" 2>&1 || rc=$?
  took=$(($(date +%s) - start))
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  size=$(find "$corpus" -type f | wc -l)
  # libFuzzer also saves inputs slower than 10 s as slow-unit-*: on a loaded machine that is the
  # machine, not the parser (each took milliseconds when run alone), so they are counted apart.
  found=$(find "$crashes" -type f ! -name 'slow-unit-*' | wc -l)
  slow=$(find "$crashes" -type f -name 'slow-unit-*' | wc -l)
  printf "%-11s %12s %9s %8s %8s %8s %6s\n" "$t" "${runs:-?}" "${speed:-?}" "$took" "$size" "$found" "$slow" >>"$summary"
  if [ $rc -ne 0 ] || [ "$found" -gt 0 ]; then
    failed=1
    echo "fuzz: $t FAILED (exit $rc); the report:"
    grep -v "^#\|^INFO\|^stat::" "$log" | tail -40
  fi
done
cat "$summary"
[ -z "${FUZZ_SUMMARY:-}" ] || cat "$summary" >>"$FUZZ_SUMMARY"
exit $failed
