#!/usr/bin/env bash
# Writes every driver record's keys (the epicycle_record_keys program: each record's VisitRecord,
# report/tools/record_keys.cpp) as the tables between the markers
#   <!-- record-keys:begin --> ... <!-- record-keys:end -->
# of docs/records.md. Usage: bash tools/record_keys.sh [build-dir]   (default ./build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
exe="$build/report/epicycle_record_keys"
[ -x "$exe" ] || { echo "missing $exe: cmake --build $build --target epicycle_record_keys" >&2; exit 1; }
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
mv "$work/doc" "$doc"
echo "wrote $(grep -c '^| `' "$work/table") keys into $doc"
