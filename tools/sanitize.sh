#!/usr/bin/env bash
# Routine check: the whole verification suite under AddressSanitizer + UndefinedBehaviorSanitizer,
# the gmsh tests and the install test included.
# Builds ./build-asan with Debian's clang (EPICYCLE_SANITIZE=address,undefined, the gmsh mesher
# on), optimised -O1 with line tables only: a Debug sanitizer build does not finish the FE tests on
# a 2-core machine, and gcc's sanitizer build of the suite (Eigen-heavy) takes several times
# longer to compile than clang's. Every report is fatal (-fno-sanitize-recover=all), so a report
# fails its test. Reports inside third-party libraries that are not instrumented (libgmsh 4.8) are
# suppressed by function name in tools/sanitizers/*.supp, each entry commented; none names
# epicycle's code.
# Usage: bash tools/sanitize.sh [ctest arguments...]
#   EPICYCLE_JOBS (default 2); EPICYCLE_NICE (default 10) niceness of the build and the suite.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${EPICYCLE_JOBS:-2}"
niceness="${EPICYCLE_NICE:-10}"
command -v clang++ > /dev/null || {
  echo "sanitize.sh: installing clang"
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang
}
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
mkdir -p build-asan
CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only -DNDEBUG" \
  -DEPICYCLE_SANITIZE=address,undefined -DEPICYCLE_WITH_GMSH=ON -DEPICYCLE_BUILD_BENCHMARKS=OFF \
  "${launcher[@]}" > build-asan/configure.log || { cat build-asan/configure.log; exit 1; }
start=$(date +%s)
nice -n "$niceness" cmake --build build-asan -j "$jobs"
built=$(date +%s)
supp="$PWD/tools/sanitizers"
export ASAN_OPTIONS="suppressions=$supp/asan.supp:detect_leaks=1:abort_on_error=1:strict_string_checks=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$supp/lsan.supp:print_suppressions=1"
export UBSAN_OPTIONS="suppressions=$supp/ubsan.supp:print_stacktrace=1:halt_on_error=1"
status=0
nice -n "$niceness" ctest --test-dir build-asan --output-on-failure -j "$jobs" --timeout 1800 "$@" \
  || status=$?
end=$(date +%s)
echo "sanitize.sh: build $((built - start)) s, suite $((end - built)) s (wall, -j $jobs)"
exit $status
