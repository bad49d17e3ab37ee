#!/usr/bin/env bash
# Runs the verification suite with EPICYCLE_FIGURES=1 and writes the VERIFY rows it prints (see
# verification/support/figures.hpp) as the table between the markers
#   <!-- verification-table:begin --> ... <!-- verification-table:end -->
# of docs/verification.md. Usage: bash tools/verification_table.sh [build-dir]   (default ./build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
doc=docs/verification.md
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for layer in geometry compliance solvers transmission dynamics studies; do
  # A layer without tests yet has no executable.
  [ "$layer" = dynamics ] && [ ! -x "$build/verification/epicycle_tests_$layer" ] && continue
  exe="$build/verification/epicycle_tests_$layer"
  [ -x "$exe" ] || { echo "missing $exe: build first (bash tools/setup.sh)" >&2; exit 1; }
  # The suite's own verdict counts too: a failing assertion stops the table.
  if ! EPICYCLE_FIGURES=1 "$exe" > "$work/$layer.out"; then
    tail -30 "$work/$layer.out"
    echo "the $layer suite failed: no table written" >&2
    exit 1
  fi
  sep=$(printf '\037')
  grep "^VERIFY$sep" "$work/$layer.out" | sed "s/^VERIFY$sep/$layer$sep/" >> "$work/rows" || true
done
{
  echo "| layer | check | reference | model | error | tolerance | verdict |"
  echo "|---|---|---|---|---|---|---|"
  awk -F"$(printf '\037')" '{ line = "|"; for (i = 1; i <= NF; ++i) line = line " " $i " |"; print line }' "$work/rows"
  echo
  echo "Produced by \`bash tools/verification_table.sh\` at commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown), $(date -u +%Y-%m-%d)."
} > "$work/table"
grep -q '<!-- verification-table:begin -->' "$doc" && grep -q '<!-- verification-table:end -->' "$doc" ||
  { echo "$doc: markers <!-- verification-table:begin/end --> not found" >&2; exit 1; }
awk -v table="$work/table" '
  /<!-- verification-table:begin -->/ { print; while ((getline l < table) > 0) print l; skip = 1; next }
  /<!-- verification-table:end -->/ { skip = 0 }
  !skip { print }' "$doc" > "$work/doc"
cp "$work/doc" "$doc"
echo "table of $(wc -l < "$work/rows") rows written into $doc"
