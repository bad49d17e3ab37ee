#!/usr/bin/env bash
# The paper's stage with a floating sun: the largest |LSR − 1/3| (off-line-of-action tip contacts)
# against the amount of long tip relief on every gear, linear and parabolic (docs/geometry.md).
# Runs the hidden [.study] case of the transmission suite; needs a built tree (tools/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build --target epicycle_tests_transmission -j2 >/dev/null
EPICYCLE_FIGURES=1 build/verification/epicycle_tests_transmission "[.study]" | sed -n 's/^FIGURE //p;/^  /p'
