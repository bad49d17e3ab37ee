#!/usr/bin/env bash
# The suite's conventions (verification/README.md), checked in the suite:
#  - every Catch2 test case carries one of the tags [unit], [crosscheck], [reference] (hidden
#    cases, a tag starting with "[.", are studies run by name and are not checked);
#  - test files follow one naming scheme: verification/unit/<layer>/<subject>.cpp (no test_
#    prefix, no _test suffix), verification/crosscheck/<layer>_<subject>.cpp and
#    verification/reference/<layer>_<subject>.cpp, <layer> one of the suites.
#
#   bash tools/check_tests.sh [SOURCE_DIR]
#
# Prints FILE:LINE of every case or file that breaks a rule and exits 1 if there is one (CTest
# "tests: every case is tagged and every file named by the scheme").
source "$(dirname "${BASH_SOURCE[0]}")/check_common.sh" "$@"
layers="io|geometry|solvers|compliance|transmission|dynamics|studies|report"
failures=0

# Tags and names. A case's declaration runs from its TEST_CASE( (or SCENARIO(, ...) to the first
# "{"; its name holds no ';' (catch_discover_tests passes it to CTest, which splits it there).
mapfile -t -d '' sources < <(list_files | grep -z '^verification/.*\.cpp$' | sort -z)
untagged=$(awk '
  function flush() {
    if (decl != "") {
      total++
      if (decl !~ /\[\./ && decl !~ /\[(unit|crosscheck|reference)\]/) {
        gsub(/[[:space:]]+/, " ", decl)
        print FILENAME ":" start ": no [unit], [crosscheck] or [reference] tag: " decl
      }
      name = decl
      sub(/"[[:space:]]*,[[:space:]]*"\[.*/, "", name)
      if (name ~ /;/) {
        gsub(/[[:space:]]+/, " ", name)
        print FILENAME ":" start ": a \";\" in the name, where CTest splits the case and runs none of it: " name
      }
    }
    decl = ""
  }
  FNR == 1 { flush() }
  /^[[:space:]]*(TEST_CASE|TEST_CASE_METHOD|TEMPLATE_TEST_CASE|SCENARIO)[[:space:]]*\(/ {
    flush(); start = FNR; decl = $0; if ($0 ~ /\{/) flush(); next
  }
  decl != "" { decl = decl " " $0; if ($0 ~ /\{/) flush() }
  END { flush(); print "cases " total > "/dev/stderr" }
' "${sources[@]}" 2>/tmp/check_tests.$$ || true)
cases=$(sed -n 's/^cases //p' /tmp/check_tests.$$)
rm -f /tmp/check_tests.$$
if [[ -n "$untagged" ]]; then
  echo "$untagged"
  failures=$((failures + $(grep -c . <<<"$untagged")))
fi

# File names.
for f in "${sources[@]}"; do
  case "$f" in
    verification/unit/*)
      if [[ ! "$f" =~ ^verification/unit/($layers)/[a-z0-9_]+\.cpp$ ]] ||
        [[ "$(basename "$f")" =~ ^test_|_test\.cpp$ ]]; then
        echo "$f:1: not named unit/<layer>/<subject>.cpp"
        failures=$((failures + 1))
      fi
      ;;
    verification/crosscheck/* | verification/reference/*)
      kind=${f#verification/}
      kind=${kind%%/*}
      if [[ ! "$f" =~ ^verification/$kind/($layers)_[a-z0-9_]+\.cpp$ ]] ||
        [[ "$(basename "$f")" =~ ^test_|_test\.cpp$ ]]; then
        echo "$f:1: not named $kind/<layer>_<subject>.cpp"
        failures=$((failures + 1))
      fi
      ;;
  esac
done

finish check_tests "$failures" "$((cases + ${#sources[@]}))" "test cases and test files"
