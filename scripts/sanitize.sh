#!/usr/bin/env bash
# CI's sanitizer stage (issue 19): a Debug build with AddressSanitizer and UndefinedBehaviorSanitizer
# in build-asan/, running the CPU and GL tests (not the CLI or editor end-to-end ones, which drive
# the Release binary's timing). Any ASan report, UBSan report (-fno-sanitize-recover) or leak fails
# the test that produced it. -O1 rather than Debug's -O0: ASan's recommended level, and -O0 made the
# Monte Carlo tests too slow for CI on 2 cores; asserts stay on (no NDEBUG). -g1 (line tables:
# the reports' stacks keep their files and lines) rather than -g: the full debug information made
# each file's compile about 40 % longer (tests/surfaces_test.cpp 17.5 s against 12.2 s).
# FluxAudit (every photometric file with every technique in a box: minutes of the same
# estimators the photometric and hard-case tests run under the sanitizers too) is left to the
# Release stage.
# An argument is a Google Test filter of the tests to run (for example 'Photometric*').
set -euo pipefail
cd "$(dirname "$0")/.."
# The generated light fields the tests load (scripts/build.sh makes them with the Release binary;
# CI has run it already).
if [ ! -f resources/luminaires/generated/car-headlight.lf.json ] ||
   [ ! -f resources/luminaires/generated/bike-headlight.lf.json ]; then
  bash scripts/build.sh
fi
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" \
  -DCMAKE_C_FLAGS_DEBUG="-g1 -O1" -DCANDELA_SANITIZE=ON >/dev/null
cmake --build build-asan -j"$(nproc)" --target candela_tests candela_gltests
# Leaks inside Mesa's llvmpipe and the system's libraries are theirs, not ours: suppressed by
# library in tests/sanitize/lsan.supp, each with its reason.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitize/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Six long tests repeat, at many points and sample counts, code that shorter tests run under the
# sanitizers too; under ASan they took 590 of the stage's 2200 test-seconds (the obstruction
# sweep alone 280 s, 28 times its Release time), so they run in the Release stage only:
# every technique's shadow of the table (Obstruction.EveryEnvironmentTechnique... and the
# validation's obstruction case keep the shadow code under ASan), the light field's disc
# occluder (LightFieldVisibility's boxed luminaire and the light-field probes), glslang over
# every shader variant (an external tool: nothing of ours to sanitize), the flux from a sphere of
# probes and the brute-force quadrature (PhotometryIes' closed-form fluxes, the photometric
# luminaire's other tests), and the classroom's 2048-ray gathers at 40 points (the office's
# adaptive test runs the same gather and refinement under the sanitizers). Likewise the layouts
# of the classroom and the office and the classroom written two ways, which run the whole surfaces
# calculation up to a dozen times (the L-shaped room's layout and the room tests keep that code
# under the sanitizers). Every shard of the test binaries reads the filter (tests/CMakeLists.txt).
LONG='Obstruction.EveryTechniqueOfEveryKind*:LightFieldVisibility.ProbeMatchesADisc*:ShaderVariants.*:PhotometricLuminaire.FluxFromASphereOfProbes*:PhotometryIes.ExactQuadratureMatchesBruteForce*:IndirectAtPoints.RefinementFollowsOccludersEdges*:FluxAudit.*:Layout.TheClassroom*:Layout.TheOffice*:Room.TheClassroomAsARoom*'
export GTEST_FILTER="${1:-*}-$LONG"
cd build-asan
ctest --output-on-failure -j"$(nproc)" -L '^(cpu|gl)$'
