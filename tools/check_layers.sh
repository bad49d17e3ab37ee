#!/usr/bin/env bash
# The contact core (solvers/) stands on its own: it includes no header of a layer above it (only
# epicycle/solvers/, the bottom layer epicycle/io/ and the generated epicycle/config.h) and no
# TOML header, and its target links no TOML library and no epicycle library but io's.
#
#   bash tools/check_layers.sh SOURCE_DIR [LINKED...]
#
# LINKED: every target and library epicycle_solvers links, directly or through the targets it
# links (the closure verification/CMakeLists.txt computes from the targets' LINK_LIBRARIES and
# INTERFACE_LINK_LIBRARIES). Prints FILE:LINE of every include and each link that breaks a rule and
# exits 1 if there is one (CTest "layers: the contact core links no TOML library and includes no
# layer above it").
source "$(dirname "${BASH_SOURCE[0]}")/check_common.sh" "$1"
shift
failures=0
checked=0

# Includes of the contact core's sources and headers.
mapfile -t -d '' files < <(list_files | grep -zE '^solvers/.*\.(cpp|hpp|h)$' | sort -z)
for f in "${files[@]}"; do
  while IFS= read -r hit; do
    checked=$((checked + 1))
    line=${hit%%:*}
    text=${hit#*:}
    if [[ "$text" =~ \#[[:space:]]*include[[:space:]]*[\"\<]epicycle/ ]] &&
       ! [[ "$text" =~ [\"\<]epicycle/(solvers|io)/ || "$text" =~ [\"\<]epicycle/config\.h ]]; then
      echo "$f:$line: the contact core includes a layer above it: $text"
      failures=$((failures + 1))
    elif [[ "$text" =~ [\"\<]toml ]]; then
      echo "$f:$line: the contact core includes a TOML header: $text"
      failures=$((failures + 1))
    fi
  done < <(grep -nE '^[[:space:]]*#[[:space:]]*include' "$f" || true)
done

# What its target links.
if (($# == 0)); then
  echo "check_layers: no link closure of epicycle_solvers given"
  exit 1
fi
for lib in "$@"; do
  checked=$((checked + 1))
  if [[ "${lib,,}" == *toml* ]]; then
    echo "epicycle_solvers links a TOML library: $lib"
    failures=$((failures + 1))
  elif [[ "$lib" == epicycle_* ]] &&
       ! [[ "$lib" =~ ^epicycle_(solvers|io|config|warnings|nlopt)$ ]]; then
    echo "epicycle_solvers links a library of another layer: $lib"
    failures=$((failures + 1))
  fi
done
finish check_layers "$failures" "$checked" "includes and links"
