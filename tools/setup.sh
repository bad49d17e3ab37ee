#!/usr/bin/env bash
# Installs what is missing (Debian 12 packages only), configures and builds epicycle in ./build.
# Used by tools/stage.sh and tools/test.sh; safe to run again (it only installs what is missing).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config libeigen3-dev libnlopt-cxx-dev coinor-libipopt-dev
          libsundials-dev catch2 libbenchmark-dev libtomlplusplus-dev libcli11-dev
          nlohmann-json3-dev libfmt-dev libgmsh-dev libopenmpi-dev openmpi-bin
          pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
          python3-openturns parallel python3-dask python3-distributed python3-mypy)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "epicycle: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

build_type="${EPICYCLE_BUILD_TYPE:-Release}"
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
mkdir -p build
# The test build includes the optional gmsh mesher (the suite compares it with the mapped one).
# gmsh is GPL and Ipopt EPL: a binary to distribute is configured with EPICYCLE_WITH_GMSH=OFF (the
# default of CMakeLists.txt); this build is not distributed. Pass -DEPICYCLE_WITH_GMSH=OFF to drop it.
# The studies' MPI runner is built too (OpenMPI is installed above), so that `mpirun -np N epicycle
# study` shares the cases among the ranks (a build without it refuses to run under a launcher).
# The Python module is built for Debian's interpreter (python3-numpy, python3-pytest are its
# packages), not for whatever `python3` comes first on the PATH.
cmake -S . -B build -DCMAKE_BUILD_TYPE="$build_type" -DEPICYCLE_WERROR="$werror" -DEPICYCLE_WITH_MPI=ON \
  -DEPICYCLE_WITH_GMSH=ON -DPython3_EXECUTABLE=/usr/bin/python3 "$@" > build/configure.log \
  || { cat build/configure.log; exit 1; }
# EPICYCLE_BUILD_TARGETS (space-separated) builds only those targets: tools/stage.sh builds the
# program alone, so the main job's first number does not wait for the test suite's build.
targets=()
for t in ${EPICYCLE_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build build -j "$(nproc)" "${targets[@]}"
