#!/usr/bin/env bash
# The model's own discretisation against its cost (docs/quasistatic.md, "Choosing the
# discretisation"): FE mesh refinement 1..R, join depth h x0.5..1.5, gap window x0.1..4, one at a
# time around the default, on the paper's stage with planet 1's 20 um run-out. Writes
# docs/figures/discretisation_study.csv and .svg (change against cost, log-log, one series per
# knob) and prints the table of the docs.
# Usage: bash tools/discretisation_study.sh [--max-refinement R] [--positions N] [--out DIR]
# Needs a configured tree (tools/setup.sh). The influence tables of every setting are built once
# into the disk cache ($EPICYCLE_CACHE_DIR or the default): refinement 4 takes several minutes of
# CPU and a few GB of memory the first time (docs/quasistatic.md gives the figures); later runs
# load them.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build --target discretisation_study -j2 >/dev/null
nice -n 10 build/benchmarks/discretisation_study --out docs/figures "$@"
