#!/usr/bin/env bash
# No function of the libraries is longer than 200 lines: a longer one is split into steps a reader
# can name. Checked over the .cpp files of the libraries (io, geometry, compliance, solvers,
# transmission, dynamics, studies, report), the Python bindings (python/src) and the FE reference
# (verification/fe_reference); a body runs from its opening to its closing brace
# (tools/check_function_length.py).
#
#   bash tools/check_function_length.sh [SOURCE_DIR]
#
# Prints FILE:LINE of every body over the limit and exits 1 if there is one (CTest "code: no
# function over 200 lines in the libraries").
source "$(dirname "${BASH_SOURCE[0]}")/check_common.sh" "$@"
limit=200
# Longer bodies allowed, as FILE:FUNCTION.
allowed=()
mapfile -t -d '' files < <(list_files |
  grep -zE '^(io|geometry|compliance|solvers|transmission|dynamics|studies|report)/.*\.cpp$|^python/src/.*\.cpp$|^verification/fe_reference/.*\.cpp$' |
  sort -z)
if ((${#files[@]} == 0)); then
  echo "check_function_length: no source files found (wrong folder?)"
  exit 1
fi
IFS=,
exec python3 "$root/tools/check_function_length.py" "$limit" "${allowed[*]}" "${files[@]}"
