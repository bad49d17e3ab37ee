#!/usr/bin/env bash
# Rewrites the measured tables of docs/solvers.md from the program's output: §8, the stability
# table (`epicycle contact stability`, between <!-- stability-table:begin/end -->), and §9, the
# comparison of every back end on the collection (`epicycle contact compare --markdown`, between
# <!-- compare-table:begin/end -->; its CSV and figures go to docs/solvers_compare*).
# Usage: bash tools/update_solver_docs.sh [build-dir]   (default ./build; a Release build)
# Environment: EPICYCLE_REPEAT solves per (back end, problem) for the median time (default 5).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
exe="$build/app/epicycle"
[ -x "$exe" ] || { echo "missing $exe: build first (bash tools/setup.sh)" >&2; exit 1; }
doc=docs/solvers.md
data=verification/data/contact
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$exe" contact stability "$data" > "$work/stability.md"
# compare exits 1 when some back end fails on some problem (the expected failures of the
# collection): the table, CSV and figures are written all the same; only 2 (bad input) stops here.
status=0
"$exe" contact compare "$data" --repeat "${EPICYCLE_REPEAT:-5}" --csv docs/solvers_compare.csv \
  --svg-prefix docs/solvers_compare --markdown "$work/compare.md" || status=$?
[ "$status" -le 1 ] || { echo "contact compare exited $status: no table written" >&2; exit 1; }

# Puts file $2 between the markers <!-- $1:begin --> and <!-- $1:end --> of $doc.
splice() {
  local name=$1 table=$2
  grep -q "<!-- $name:begin -->" "$doc" && grep -q "<!-- $name:end -->" "$doc" ||
    { echo "$doc: markers <!-- $name:begin/end --> not found" >&2; exit 1; }
  awk -v table="$table" -v begin="<!-- $name:begin -->" -v end="<!-- $name:end -->" '
    index($0, begin) { print; while ((getline l < table) > 0) print l; skip = 1; next }
    index($0, end) { skip = 0 }
    !skip { print }' "$doc" > "$work/doc"
  cp "$work/doc" "$doc"
}
splice stability-table "$work/stability.md"
splice compare-table "$work/compare.md"
echo "tables written into $doc (contact compare exit status $status)"
