#!/usr/bin/env bash
# Quick start 1: install what is missing, build, and run the main job on the paper's stage: the
# quasi-static load sharing with planet 1's 20 um run-out over one planet revolution, constrained
# (sun fixed) and floating, as in the paper's Figs. 4-6, first quasi-static, then in motion with the
# dynamic model at a sun speed of 1300 rpm: between the mesh-harmonic coincidences h12 x 3133 Hz
# (1220 rpm) and h8 x the floating sun's translational mode 2518 Hz (1471 rpm), where the floating
# load sharing is the stage's away from resonance (docs/dynamic.md, "The main job's speed").
# Results (CSV, JSON, SVG) in ./results.
set -euo pipefail
cd "$(dirname "$0")/.."
# The program alone: the test suite is built by tools/test.sh.
EPICYCLE_BUILD_TARGETS=epicycle bash tools/setup.sh
for sun in fixed floating; do
  echo
  ./build/app/epicycle quasistatic scenes/paper_stage_runout.toml --range planet \
    --sun "$sun" --out "results/paper_stage_runout_$sun"
done
for sun in fixed floating; do
  echo
  ./build/app/epicycle dynamic scenes/paper_stage_runout.toml --range planet --speed-rpm 1300 \
    --sun "$sun" --out "results/paper_stage_runout_dynamic_$sun"
done
