#!/usr/bin/env bash
# Scaling of a tolerance study (docs/studies.md): the same 1000-case study with 1 and 2 threads,
# and (when built with EPICYCLE_WITH_MPI) with 1, 2 and 4 MPI ranks of 1 thread each (4 ranks are
# oversubscribed on a 2-core machine). Prints cases per second as the program reports them (the
# computation only, tables loaded from the cache). Usage: bash tools/study_scaling.sh [CASES]
set -euo pipefail
cd "$(dirname "$0")/.."
cases="${1:-1000}"
exe=build/app/epicycle
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/scaling.toml" <<TOML
[study]
name = "scaling"
scene = "$PWD/scenes/paper_stage.toml"
seed = 1
samples = $cases
positions = 36
sun = "fixed"

[[variable]]
quantity = "pin_tangential"
gear = "planets"
distribution = "normal"
sigma_um = 5.0
TOML
rate() { grep -o '([0-9.]* cases/s' | tr -d '(' ; }
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for t in 1 2; do
  echo "threads $t: $("$exe" study "$work/scaling.toml" --out "$work/t$t" --threads "$t" --quiet | rate)"
done
if "$exe" --help >/dev/null && grep -q "EPICYCLE_HAVE_MPI 1" build/generated/epicycle/config.h; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  for np in 1 2 4; do
    echo "MPI ranks $np x 1 thread: $(mpirun --oversubscribe -np "$np" "$exe" study "$work/scaling.toml" \
      --out "$work/np$np" --threads 1 --quiet | rate)"
  done
fi
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
