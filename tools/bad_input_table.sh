#!/usr/bin/env bash
# Runs the bad-input tests with EPICYCLE_FIGURES=1 and writes the BADINPUT rows they print
# (verification/unit/transmission/bad_input.cpp: input, expected message, the message the
# program gave, verdict) as the table between the markers
#   <!-- bad-input-table:begin --> ... <!-- bad-input-table:end -->
# of docs/bad_inputs.md. Usage: bash tools/bad_input_table.sh [build-dir]   (default ./build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
doc=docs/bad_inputs.md
exe="$build/verification/epicycle_tests_transmission"
[ -x "$exe" ] || { echo "missing $exe: build first (bash tools/setup.sh)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if ! EPICYCLE_FIGURES=1 "$exe" "[bad-input]" > "$work/out"; then
  tail -30 "$work/out"
  echo "the bad-input tests failed: no table written" >&2
  exit 1
fi
sep=$(printf '\037')
{
  echo "| input | expected in the message | message given | verdict |"
  echo "|---|---|---|---|"
  grep "^BADINPUT$sep" "$work/out" | sed "s/^BADINPUT$sep//" |
    awk -F"$sep" '{ line = "|"; for (i = 1; i <= NF; ++i) line = line " " $i " |"; print line }'
  echo
  echo "Produced by \`bash tools/bad_input_table.sh\` at commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown), $(date -u +%Y-%m-%d)."
} > "$work/table"
awk -v table="$work/table" '
  /<!-- bad-input-table:begin -->/ { print; while ((getline l < table) > 0) print l; skip = 1; next }
  /<!-- bad-input-table:end -->/ { skip = 0 }
  !skip { print }' "$doc" > "$work/doc"
cp "$work/doc" "$doc"
echo "table of $(grep -c "^BADINPUT$sep" "$work/out") rows written into $doc"
