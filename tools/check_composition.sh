#!/usr/bin/env bash
# The composition of a run exists once, in the drivers' libraries: no front end (app/, python/) and
# not the output layer (report/) builds a stage's compliance or a model (ARCHITECTURE.md, "Drivers:
# a request, a run, a record"). The front ends parse options into a request and format a record;
# the run (transmission::RunQuasiStatic, RunStiffness, dynamics::RunModes, StageDynamics, the
# studies' runner) builds the rig.
#
#   bash tools/check_composition.sh [SOURCE_DIR]
#
# What counts as building, in a .cpp/.hpp file of app/, python/ or report/:
#   a compliance: constructing transmission::FeStageCompliance or FePairCompliance (a variable
#                 `FeStageCompliance c(...)` / `{...}`, a temporary `FeStageCompliance(...)`, or
#                 std::make_unique / make_shared of it), or transmission::StageMeshPairs (planet
#                 1's meshes as pairs on a built stage's tables: the rating's c_γ and the modal
#                 mesh stiffness, which the runs build);
#   a model:      constructing transmission::StageModel or dynamics::DynamicModel in the same ways.
# Not counted: the libraries' builders themselves (transmission::StageRig, dynamics::StageDynamics:
# a front end may keep one per scene, as Python does, and hand it to a request), a copy of a rig's
# model (`rig->Model(...)`), a stage alone (transmission::MakeStage: the geometry report draws
# it), declarations of pointers and references. Tests (verification/) and benchmarks build parts to
# measure them and are not checked.
# Prints FILE:LINE of every construction and exits 1 if there is one (CTest "composition: ...").
source "$(dirname "${BASH_SOURCE[0]}")/check_common.sh" "${1:-}"
failures=0
checked=0
types='FeStageCompliance|FePairCompliance|StageMeshPairs|StageModel|DynamicModel'
# A variable or a temporary of one of the types, or make_unique/make_shared of it.
construct="(^|[^[:alnum:]_:<>*&])((transmission|dynamics)::)?($types)[[:space:]]*([[:alpha:]_][[:alnum:]_]*[[:space:]]*)?[({]"
make="make_(unique|shared)<[[:space:]]*(const[[:space:]]+)?((transmission|dynamics)::)?($types)[[:space:]]*>"

mapfile -t -d '' files < <(list_files | grep -zE '^(app|python|report)/.*\.(cpp|hpp|h)$' | sort -z)
for f in "${files[@]}"; do
  checked=$((checked + 1))
  while IFS= read -r hit; do
    line=${hit%%:*}
    text=${hit#*:}
    [[ "$text" =~ ^[[:space:]]*(//|\*|/\*) ]] && continue  # a comment
    [[ "$text" =~ (->|\.)Model\( ]] && continue            # a copy of a rig's model
    echo "$f:$line: a front end builds a compliance or a model (the drivers' libraries do): $text"
    failures=$((failures + 1))
  done < <(grep -nE "$construct|$make" "$f" || true)
done
finish check_composition "$failures" "$checked" "front-end and report files"
