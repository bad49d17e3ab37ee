#!/usr/bin/env bash
# The outputs of every `epicycle ...` command in docs/*.md and README.md from two builds, compared
# byte for byte with the timing and provenance fields masked (tools/docs_outputs.py says what is
# run, what is skipped and what is masked).
#
#   bash tools/check_docs_outputs.sh EXE_A EXE_B OUT [--only REGEX] [--timeout S]
#
# Runs EXE_A's commands into OUT/a and EXE_B's into OUT/b (one folder per command, with its stdout,
# stderr and exit code), then lists the files that differ; exit 1 if one does. Both builds read the
# influence tables from one cache ($EPICYCLE_CACHE_DIR, default OUT/cache), so the first run builds
# them. Slow: every command of the docs, some of them minutes (the speed sweeps, an hour of a
# dynamic run at 1 rpm); --only REGEX runs the commands that match. Not in the test suite.
set -euo pipefail
if (($# < 3)); then
  sed -n '2,12p' "$0" >&2
  exit 2
fi
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
a=$(realpath "$1")
b=$(realpath "$2")
out=$3
shift 3
mkdir -p "$out"
export EPICYCLE_CACHE_DIR=${EPICYCLE_CACHE_DIR:-$(realpath "$out")/cache}
python3 "$root/tools/docs_outputs.py" run "$root" "$a" "$out/a" "$@"
python3 "$root/tools/docs_outputs.py" run "$root" "$b" "$out/b" "$@"
python3 "$root/tools/docs_outputs.py" diff "$out/a" "$out/b"
