// The parallel loop of the position sweeps (the stage's quasi-static sweep, a mesh's stiffness
// cycle): positions split into contiguous chunks, each chunk run in order by one worker (so a
// position may start from the one before it in its chunk), and every result handed on in the
// order of the positions as soon as it and every earlier one are done.
#pragma once

#include <functional>

#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::transmission::internal {

/// Workers for `count` positions: `requested` (0: std::thread::hardware_concurrency(), at least
/// 1), at most `count`.
int SweepWorkers(int requested, int count);

/// Runs solve(k, chunk_first, solver) for every k in [0, count) on SweepWorkers(threads, count)
/// workers, each chunk in increasing k with a contact solver of `backend` of its own (the solvers
/// keep storage between calls, so they are not shared); chunk_first is true for a chunk's first
/// position (it must not lean on k − 1). emit(k) is called once for every k, in increasing order,
/// under one lock, from whichever worker completes the run of finished positions. An exception
/// from solve or emit stops the workers (each finishes its current position) and is rethrown here.
///
/// `in_flight` = 0 or count ≤ in_flight: one chunk per worker (count·t/workers .. count·(t+1)/
/// workers). Otherwise the positions go in chunks of at most in_flight/workers positions, taken
/// by the workers in order, and a chunk starts only when all of it lies within `in_flight`
/// positions of the first one not yet emitted: every k being solved, or solved and not yet
/// emitted, is below next + in_flight (next: the first k not emitted), so a caller may keep the
/// results in a ring of in_flight + 1 slots (slot k mod (in_flight + 1); position k − 1's slot
/// still holds it while k is solved).
void RunOrderedChunks(
    int count, int threads, solvers::Backend backend,
    const std::function<void(int k, bool chunk_first, solvers::ContactSolver& solver)>& solve,
    const std::function<void(int k)>& emit, int in_flight = 0);

}  // namespace epicycle::transmission::internal
