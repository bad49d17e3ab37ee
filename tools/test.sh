#!/usr/bin/env bash
# Quick start 2: install what is missing, build, and run the whole verification suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 900
