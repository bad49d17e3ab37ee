#!/usr/bin/env bash
# Quick start 1: install what is missing, build, and run the main job on the paper's stage.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
./build/app/epicycle geometry scenes/paper_stage.toml
