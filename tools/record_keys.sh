#!/usr/bin/env bash
# Writes every driver record's keys (the epicycle_record_keys program: each record's VisitRecord,
# report/tools/record_keys.cpp) as the tables between the markers
#   <!-- record-keys:begin --> ... <!-- record-keys:end -->
# of docs/records.md.
#   bash tools/record_keys.sh [build-dir]           (default ./build) rewrites the tables
#   bash tools/record_keys.sh --check EXE [SOURCE]  exit 1 if the tables differ from EXE's output
#                                                   (CTest "docs: records.md lists ...")
set -euo pipefail
check=0
if [ "${1:-}" = "--check" ]; then
  check=1
  exe=$2
  cd "${3:-$(dirname "$0")/..}"
else
  cd "$(dirname "$0")/.."
  build="${1:-build}"
  exe="$build/report/epicycle_record_keys"
fi
[ -x "$exe" ] || { echo "missing $exe: cmake --build BUILD --target epicycle_record_keys" >&2; exit 1; }
doc=docs/records.md
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$exe" > "$work/table"
awk -v table="$work/table" '
  /<!-- record-keys:begin -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
  /<!-- record-keys:end -->/ { skip = 0 }
  !skip { print }
' "$doc" > "$work/doc"
grep -q '<!-- record-keys:end -->' "$work/doc" || { echo "$doc: no record-keys markers" >&2; exit 1; }
keys=$(grep -c '^| `' "$work/table")
if ((check)); then
  if ! diff -u "$doc" "$work/doc"; then
    echo "record_keys: $doc is not the records' keys: run bash tools/record_keys.sh"
    exit 1
  fi
  echo "record_keys: all $keys keys of $doc are the records'"
  exit 0
fi
mv "$work/doc" "$doc"
echo "wrote $keys keys into $doc"
