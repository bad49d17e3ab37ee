#!/usr/bin/env bash
# Every numbered section that code, scripts and docs cite in a page of docs/ exists.
#
#   bash tools/check_doc_citations.sh [SOURCE_DIR]
#
# A citation is `docs/NAME.md §N`, `NAME.md §N` (inside docs/), `[NAME.md](NAME.md) §N`, a range
# `§N–M` (every section from N to M is checked) or a list `§N, §M`. The section exists when
# docs/NAME.md has a heading line `## N.` (docs/model.md: `## 7. Dynamic model`). A citation of a
# page that does not exist fails too. Prints every failure as FILE:LINE and exits 1 if there is
# one (CTest "docs: every cited section exists").
source "$(dirname "${BASH_SOURCE[0]}")/check_common.sh" "$@"

cite='[A-Za-z0-9_]+\.md\)? §[0-9]+((–|-)[0-9]+)?(, §[0-9]+((–|-)[0-9]+)?)*'
failures=0
checked=0
# The files to search: code, build and test scripts, docs.
sources() {
  list_files | grep -zE '\.(cpp|hpp|h|cc|in|txt|cmake|sh|py|md|toml|json)$'
}

while IFS= read -r hit; do
  file=${hit%%:*}
  hit=${hit#*:}
  line=${hit%%:*}
  text=${hit#*:}
  name=${text%%.md*}
  # `docs/NAME.md` or, inside docs/ and in Markdown links, `NAME.md` next to the citing page.
  page="docs/$name.md"
  # Every number of the citation, ranges expanded.
  numbers=()
  rest="§${text#*§}"
  while [[ "$rest" =~ ^§([0-9]+)((–|-)([0-9]+))?(, )?(.*)$ ]]; do
    lo=${BASH_REMATCH[1]}
    hi=${BASH_REMATCH[4]:-$lo}
    for ((n = lo; n <= hi; ++n)); do numbers+=("$n"); done
    rest=${BASH_REMATCH[6]}
  done
  for n in "${numbers[@]}"; do
    checked=$((checked + 1))
    if [[ ! -f "$page" ]]; then
      echo "$file:$line: cites $page §$n, but $page does not exist"
      failures=$((failures + 1))
    elif ! grep -q "^## $n\. " "$page"; then
      echo "$file:$line: cites $page §$n, but $page has no heading '## $n.'"
      failures=$((failures + 1))
    fi
  done
done < <(sources | xargs -0 grep -HnoE "$cite" || true)

finish check_doc_citations "$failures" "$checked" "cited sections"
