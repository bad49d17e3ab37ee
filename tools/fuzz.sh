#!/usr/bin/env bash
# Routine check: libFuzzer on the scene reader, the contact-problem reader, the study-file reader
# and the command line's options, for a bounded time.
# Builds ./build-fuzz with clang (Debian's clang package) and EPICYCLE_BUILD_FUZZERS=ON (ASan +
# UBSan + libFuzzer coverage), seeds a working corpus from the repository's inputs (scenes/,
# verification/data/contact, verification/data/bad_inputs, verification/fuzz/corpus) and runs each
# target for FUZZ_SECONDS (default 600), one after the other, one job each. Findings (crashes,
# sanitizer reports, timeouts) are written to build-fuzz/artifacts/ and fail the script: add the
# input to verification/fuzz/corpus/<scene|contact>/ once fixed, so that the suite replays it.
# Usage: bash tools/fuzz.sh [scene|contact|study|options ...]   (default all four)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-600}"
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene contact study options)
command -v clang++ > /dev/null || {
  echo "fuzz.sh: installing clang"
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang
}
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
mkdir -p build-fuzz
CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DEPICYCLE_BUILD_FUZZERS=ON \
  -DEPICYCLE_BUILD_TESTS=OFF -DEPICYCLE_BUILD_BENCHMARKS=OFF "${launcher[@]}" \
  > build-fuzz/configure.log || { cat build-fuzz/configure.log; exit 1; }
cmake --build build-fuzz --target fuzz_scene fuzz_contact_problem fuzz_study fuzz_options -j "${EPICYCLE_JOBS:-2}"
status=0
for t in "${targets[@]}"; do
  case "$t" in
    scene) exe=fuzz_scene; seeds=(scenes verification/data/bad_inputs verification/fuzz/corpus/scene) ;;
    contact) exe=fuzz_contact_problem; seeds=(verification/data/contact verification/fuzz/corpus/contact) ;;
    study) exe=fuzz_study; seeds=(scenes/studies verification/fuzz/corpus/study) ;;
    options) exe=fuzz_options; seeds=(verification/fuzz/corpus/options) ;;
    *) echo "fuzz.sh: unknown target $t (scene, contact, study, options)" >&2; exit 2 ;;
  esac
  corpus="build-fuzz/corpus/$t"
  mkdir -p "$corpus" build-fuzz/artifacts
  for s in "${seeds[@]}"; do
    [ -d "$s" ] && find "$s" -type f \( -name '*.toml' -o -name '*.json' -o -path '*/corpus/*' \) \
      ! -name expected_failures.json -exec cp -n {} "$corpus/" \;
  done
  echo "== $exe: ${seconds} s from $(ls "$corpus" | wc -l) inputs"
  ASAN_OPTIONS="detect_leaks=1" "build-fuzz/verification/fuzz/$exe" "$corpus" -max_total_time="$seconds" \
    -timeout=30 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix=build-fuzz/artifacts/"$t"- > "build-fuzz/$t.log" 2>&1 || status=$?
  grep -E "^#[0-9]+.*(INITED|DONE)" "build-fuzz/$t.log" | tail -2
  grep -E "^stat::" "build-fuzz/$t.log" || true
  grep -E "ERROR|finding|deadly|timeout" "build-fuzz/$t.log" | head -5 || true
done
exit $status
