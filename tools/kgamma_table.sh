#!/usr/bin/env bash
# The standard's K_gamma table put to the test (docs/studies.md, "The standard's K_gamma table"):
# runs the 24 studies scenes/studies/kgamma_table/planets<N>_class<A>[_fixed].toml (N = 3..6
# planets, ISO 1328-1 classes 5..7, floating and fixed sun) and gathers P(K_gamma > table value)
# with its interval into docs/figures/kgamma_table_{floating,fixed}{.csv,.md,.svg,_p95.svg};
# then the pin holes' share (planets4_class6_pins_only.toml, no run-out).
# Usage: bash tools/kgamma_table.sh [--out DIR] [--threads T] [--max-cases M]
# Needs a configured tree (tools/setup.sh). A rerun with the same --out resumes every study
# (docs/studies.md "Resuming"); the influence tables of the four stages are built once into the
# disk cache ($EPICYCLE_CACHE_DIR or the default).
set -euo pipefail
cd "$(dirname "$0")/.."
out=kgamma-table-out threads=2 max=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --max-cases) max=(--max-cases "$2"); shift 2 ;;
    *) echo "kgamma_table.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
cmake --build build --target epicycle kgamma_table -j2 >/dev/null
mkdir -p "$out"
start=$(date +%s)
for support in floating fixed; do
  suffix=""
  [ "$support" = fixed ] && suffix=_fixed
  cells=()
  for n in 3 4 5 6; do
    for a in 5 6 7; do
      name=planets${n}_class${a}${suffix}
      t0=$(date +%s)
      build/app/epicycle study "scenes/studies/kgamma_table/$name.toml" --out "$out/$name" \
        --threads "$threads" --quiet "${max[@]}" > "$out/$name.log" \
        || echo "$name: exit status $? (its failed cases named above; the summary leaves them out)"
      echo "$name: $(( $(date +%s) - t0 )) s; $(grep -m1 "P(K_gamma" "$out/$name.log")"
      cells+=("$n:$a:$out/$name/study_summary.json")
    done
  done
  mkdir -p docs/figures
  build/benchmarks/kgamma_table docs/figures/kgamma_table_$support "$support sun" "${cells[@]}"
done
# The pin holes' share: 4 planets, class 6, floating sun, without the run-outs.
name=planets4_class6_pins_only
build/app/epicycle study "scenes/studies/kgamma_table/$name.toml" --out "$out/$name" \
  --threads "$threads" --quiet "${max[@]}" > "$out/$name.log" || echo "$name: exit status $?"
echo "$name: $(grep -m1 "P(K_gamma" "$out/$name.log"); $(grep -m1 "K_gamma  " "$out/$name.log")"
echo "all studies: $(( $(date +%s) - start )) s on $threads threads"
