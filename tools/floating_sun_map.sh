#!/usr/bin/env bash
# The floating sun's load-sharing map (docs/dynamic.md, "Why a floating sun's shares differ"): the
# paper's run-out case (scenes/paper_stage_runout.toml, sun floating) over a planet revolution per
# speed at 60 ... 6000 rpm in 60 rpm steps (100 speeds), and 1200 ... 1800 rpm in 20 rpm steps
# around the main job's speed, where the resonances at the coincidences of
# `epicycle modes scenes/paper_stage_runout.toml --sun floating --speed-range-rpm 60 6000` (3-6 %
# wide, ζ ≈ 0.03-0.06) crowd; friction off and with the scene's (Xu & Kahraman). Per speed the
# largest |LSR - 1/3| and its parts there (dynamics::DecomposeLoadSharing); coincidences of mesh
# harmonics up to 12 marked. Writes
# docs/figures/floating_map{,_fine}_{off,on}.csv and _lsr_deviation.svg. About 400 s CPU in all
# (each friction setting on one thread, the two at once).
# Usage: bash tools/floating_sun_map.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
exe="${1:-build}/app/epicycle"
out=docs/figures
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
map() {  # name friction speeds
  "$exe" dynamic scenes/paper_stage_runout.toml --sun floating --friction "$2" \
    --speed-sweep "$3" --harmonics 12 --threads 1 --quiet --out "$tmp/$1" > "$tmp/$1.log"
  cp "$tmp/$1/speed_sweep.csv" "$out/$1.csv"
  cp "$tmp/$1/speed_sweep_lsr_deviation.svg" "$out/$1_lsr_deviation.svg"
}
both() {  # friction
  map "floating_map_$1" "$2" 60:6000:100
  map "floating_map_fine_$1" "$2" 1200:1800:31
}
both off off &
off=$!
both on xu-kahraman &
on=$!
wait "$off"
wait "$on"
echo "floating-sun map written to $out/floating_map_{off,on}.*"
