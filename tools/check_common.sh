# Shared by the house checks run in the suite (tools/check_doc_citations.sh, tools/check_tests.sh):
# `source check_common.sh [SOURCE_DIR]` enters the source folder (default: this script's parent),
# sets $root, and matches bytes (the checks' patterns hold § and – as bytes).
set -euo pipefail
export LC_ALL=C
root=$(cd "${1:-$(dirname "${BASH_SOURCE[0]}")/..}" && pwd)
cd "$root"

# The files of the source folder, NUL-separated: what git tracks and the untracked files it does
# not ignore, or everything outside build trees when this is not a git checkout.
# (Files deleted but not yet committed are left out.)
list_files() {
  if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -z --cached --others --exclude-standard |
      while IFS= read -r -d '' f; do [[ -f "$f" ]] && printf '%s\0' "$f"; done
  else
    find . -path './build*' -prune -o -path './.git' -prune -o -type f -print0 | sed -z 's|^\./||'
  fi
}

# finish NAME FAILURES CHECKED WHAT: the verdict line and the exit status (1 on a failure, or when
# nothing was checked: a wrong folder must not pass).
finish() {
  local name=$1 failures=$2 checked=$3 what=$4
  if ((failures > 0)); then
    echo "$name: $failures problem(s) in $checked $what"
    exit 1
  fi
  if ((checked == 0)); then
    echo "$name: no $what found (wrong folder?)"
    exit 1
  fi
  echo "$name: all $checked $what pass"
}
