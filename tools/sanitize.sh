#!/usr/bin/env bash
# Routine check: the whole verification suite under AddressSanitizer + UndefinedBehaviorSanitizer.
# Builds ./build-asan (optimised, -O2 -g: a Debug sanitizer build does not finish the FE tests on a
# 2-core machine) with EPICYCLE_SANITIZE=address,undefined and the gmsh mesher, then runs ctest.
# Every sanitizer report is fatal (-fno-sanitize-recover=all), so a report fails its test.
# Reports inside third-party libraries are suppressed by name in tools/sanitizers/*.supp.
# Usage: bash tools/sanitize.sh [ctest arguments...]   (EPICYCLE_JOBS, default 2)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${EPICYCLE_JOBS:-2}"
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
mkdir -p build-asan
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DEPICYCLE_SANITIZE=address,undefined \
  -DEPICYCLE_WITH_GMSH=ON -DEPICYCLE_BUILD_BENCHMARKS=OFF "${launcher[@]}" > build-asan/configure.log \
  || { cat build-asan/configure.log; exit 1; }
start=$(date +%s)
cmake --build build-asan -j "$jobs"
built=$(date +%s)
supp="$PWD/tools/sanitizers"
export ASAN_OPTIONS="suppressions=$supp/asan.supp:detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="suppressions=$supp/ubsan.supp:print_stacktrace=1:halt_on_error=1"
status=0
ctest --test-dir build-asan --output-on-failure -j "$jobs" --timeout 1800 "$@" || status=$?
end=$(date +%s)
echo "sanitize.sh: build $((built - start)) s, suite $((end - built)) s (wall, -j $jobs)"
exit $status
