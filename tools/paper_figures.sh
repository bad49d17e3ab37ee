#!/usr/bin/env bash
# Regenerates the figures of docs/ from the built program: mesh-stiffness curves of the pair
# scenes, and the quasi-static load sharing of the paper's stage without errors (one mesh cycle)
# and with planet 1's 20 um run-out (one planet revolution), constrained and floating; the same
# run-out case with the dynamic model at 1500 rpm; the spectra of the stage with and without it;
# speed sweeps of the stage with and without it; the floating sun's load-sharing map; the load
# across the face width of the stage with a pin tilted and with the carrier's wind-up.
# Usage: bash tools/paper_figures.sh [build-dir]   (default ./build; tables cached as usual)
set -euo pipefail
cd "$(dirname "$0")/.."
exe="${1:-build}/app/epicycle"
out=docs/figures
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
for pair in iso_pair_20_40 iso_pair_30_30 paper_sun_planet paper_planet_ring; do
  "$exe" stiffness "scenes/$pair.toml" --positions 60 --out "$tmp/$pair" > "$tmp/$pair.log"
  cp "$tmp/$pair/stiffness_gear1-gear2.svg" "$out/stiffness_$pair.svg"
  cp "$tmp/$pair/stiffness_gear1-gear2.json" "$out/stiffness_$pair.json"
done
run() {  # name scene sun range positions
  "$exe" quasistatic "scenes/$2.toml" --sun "$3" --range "$4" --positions "$5" --quiet \
    --out "$tmp/$1" > "$tmp/$1.log"
  for f in lsr te sun_path; do cp "$tmp/$1/quasistatic_$f.svg" "$out/$1_$f.svg"; done
  cp "$tmp/$1/quasistatic_summary.json" "$out/$1_summary.json"
}
run noerrors_fixed paper_stage fixed cycle 72
run noerrors_floating paper_stage floating cycle 72
run runout_fixed paper_stage_runout fixed planet 2880
run runout_floating paper_stage_runout floating planet 2880
# The dynamic model: the paper's run-out case in motion at 1500 rpm over a planet revolution.
dyn() {  # name scene sun
  "$exe" dynamic "scenes/$2.toml" --sun "$3" --range planet --outputs-per-cycle 20 --quiet \
    --out "$tmp/$1" > "$tmp/$1.log"
  for f in lsr te orbit; do cp "$tmp/$1/dynamic_$f.svg" "$out/$1_$f.svg"; done
  cp "$tmp/$1/dynamic_summary.json" "$out/$1_summary.json"
}
dyn dynamic_runout_fixed paper_stage_runout fixed
dyn dynamic_runout_floating paper_stage_runout floating
# Spectra (docs/spectra.md), sun fixed, 1500 rpm: 4 mesh cycles of start transient
# and three carrier revolutions (199 mesh cycles = 199·81/26000 s), 24 outputs per mesh cycle.
spectrum() {  # name scene
  "$exe" dynamic "scenes/$2.toml" --sun fixed --speed-rpm 1500 --time 0.619961538461538 \
    --outputs-per-cycle 24 --spectrum --quiet --out "$tmp/$1" > "$tmp/$1.log"
  for f in te ring_force_x; do cp "$tmp/$1/dynamic_spectrum_$f.svg" "$out/$1_$f.svg"; done
  cp "$tmp/$1/dynamic_spectrum.csv" "$out/$1.csv"
}
spectrum spectrum_healthy paper_stage
spectrum spectrum_runout paper_stage_runout
# Speed sweeps (docs/speed_sweeps.md), sun fixed: the run-out case over a planet
# revolution per speed, and the stage without errors over 3 mesh cycles per speed on a finer grid.
sweep() {  # name scene speeds [options]
  local name=$1 scene=$2 speeds=$3
  shift 3
  "$exe" dynamic "scenes/$scene.toml" --sun fixed --speed-sweep "$speeds" --quiet \
    --out "$tmp/$name" "$@" > "$tmp/$name.log"
  for f in k_gamma dynamic_factor te_amplitude; do
    cp "$tmp/$name/speed_sweep_$f.svg" "$out/${name}_$f.svg"
  done
  cp "$tmp/$name/speed_sweep_summary.json" "$out/${name}_summary.json"
}
sweep speed_sweep_runout paper_stage_runout 500:12000:47
sweep speed_sweep_noerrors paper_stage 500:12000:116 --window-cycles 3
# Across the face width (docs/face_width.md): a pin tilted radially, tangentially, the carrier's
# wind-up; one mesh cycle, rated (the ratings' tables: tools/face_width_table.py).
face() {  # name scene
  "$exe" quasistatic "scenes/$2.toml" --rating --quiet --out "$tmp/$1" > "$tmp/$1.log"
  for f in face_load k_hbeta; do cp "$tmp/$1/quasistatic_$f.svg" "$out/$1_$f.svg"; done
  cp "$tmp/$1/quasistatic_summary.json" "$out/$1_summary.json"
}
face face_pin_tilt_radial paper_stage_pin_tilt
face face_pin_tilt_tangential paper_stage_pin_tilt_tangential
face face_wind_up paper_stage_wind_up
python3 tools/face_width_table.py "radial tilt=$out/face_pin_tilt_radial_summary.json" \
  "tangential tilt=$out/face_pin_tilt_tangential_summary.json" \
  "wind-up=$out/face_wind_up_summary.json" > "$out/face_ratings.md"
# The same three cases in 10 slices coupled by the structure's 3D kernels, and in 10 uncoupled
# slices for the like-for-like comparison (docs/face_width.md, "Coupled by the structure").
face face_pin_tilt_radial_structure paper_stage_pin_tilt_structure
face face_pin_tilt_tangential_structure paper_stage_pin_tilt_tangential_structure
face face_wind_up_structure paper_stage_wind_up_structure
python3 tools/face_width_table.py "radial tilt=$out/face_pin_tilt_radial_structure_summary.json" \
  "tangential tilt=$out/face_pin_tilt_tangential_structure_summary.json" \
  "wind-up=$out/face_wind_up_structure_summary.json" > "$out/face_ratings_structure.md"
# The floating sun's largest |LSR - 1/3| and its parts over speed (docs/dynamic.md, "Why a
# floating sun's shares differ").
bash tools/floating_sun_map.sh "${1:-build}"
echo "figures written to $out"
