#!/usr/bin/env bash
# A study across two "machines" as a user runs one (docs/studies.md, "Two machines, one rank
# killed"): a hostfile of two nodes, node-a and node-b, both reached through a launch agent that
# stands in for ssh and runs the command on this machine (OpenMPI then starts its daemon on each
# "node" as it would over ssh, and the ranks talk over TCP). Then the same run with rank 1 killed
# (SIGKILL) after a few seconds, and a rerun that resumes. Each run's rows are compared with one
# process's. Needs a build with EPICYCLE_WITH_MPI=ON (tools/setup.sh).
# Usage: bash tools/mpi_two_nodes.sh [CASES] (default 2000)
set -euo pipefail
cd "$(dirname "$0")/.."
cases="${1:-2000}"
exe="$PWD/build/app/epicycle"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # root in containers and CI
cat > "$work/agent.sh" <<'SH'
#!/bin/sh
# ssh's stand-in: drop the host name, run the command here.
shift
exec /bin/sh -c "$*"
SH
chmod +x "$work/agent.sh"
printf 'node-a slots=1\nnode-b slots=1\n' > "$work/hosts"
# The repository's pin-hole study (scenes/studies/pin_tolerance.toml) with more cases and positions.
sed -e "s|^scene = .*|scene = \"$PWD/scenes/paper_stage.toml\"|" -e "s|^samples = .*|samples = $cases|" \
  -e 's|^positions = .*|positions = 144|' scenes/studies/pin_tolerance.toml > "$work/pins.toml"
mpi() { mpirun --hostfile "$work/hosts" --mca plm_rsh_agent "$work/agent.sh" -np 2 "$@"; }
rows() { grep -v -e '^#' -e '^case,' "$1/study_rows.csv" | sort; }
"$exe" study "$work/pins.toml" --out "$work/one" --quiet --threads 1 > /dev/null
echo "one process: $(rows "$work/one" | wc -l) rows"

mpi --display-map "$exe" study "$work/pins.toml" --out "$work/two" --quiet --threads 1 \
  > "$work/two.log" 2>&1
echo "job map: $(grep -A1 -m2 'Data for node: node-' "$work/two.log" | grep -o -e 'node-[ab]' -e 'rank: [0-9]' | paste -sd' ')"
cmp -s <(rows "$work/one") <(rows "$work/two") && echo "two nodes: rows identical to one process" \
  || { echo "two nodes: rows DIFFER"; exit 1; }

# Rank 1 killed mid-study: mpirun ends the job; the rows file keeps whole lines; a rerun resumes.
( mpi "$exe" study "$work/pins.toml" --out "$work/kill" --quiet --threads 1 \
    > "$work/kill.log" 2>&1 && echo 0 > "$work/kill.rc" || echo "$?" > "$work/kill.rc" ) &
sleep 5
for p in $(pgrep -f "study $work/pins.toml --out $work/kill"); do
  if tr '\0' '\n' < "/proc/$p/environ" 2>/dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then
    kill -9 "$p"; killed=$(date +%s.%N)
  fi
done
wait
ended=$(date +%s.%N)
echo "rank 1 killed: mpirun exit $(cat "$work/kill.rc") after $(echo "$ended - ${killed:-$ended}" | bc) s," \
  "$(rows "$work/kill" | wc -l) rows kept, last line whole: $(tail -c1 "$work/kill/study_rows.csv" | od -An -c | tr -d ' ')"
mpi "$exe" study "$work/pins.toml" --out "$work/kill" --quiet --threads 1 > "$work/rerun.log" 2>&1
grep -o '[0-9]* rows resumed, [0-9]* computed' "$work/rerun.log"
cmp -s <(rows "$work/one") <(rows "$work/kill") && echo "after the rerun: rows identical to one process" \
  || { echo "after the rerun: rows DIFFER"; exit 1; }
