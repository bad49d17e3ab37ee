// The parallel loop of the position sweeps (the stage's quasi-static sweep, a mesh's stiffness
// cycle): positions split into contiguous chunks, one per worker, each chunk run in order (so a
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
/// workers, each over one contiguous chunk in increasing k and with its own contact solver of
/// `backend` (the solvers keep storage between calls, so they are not shared); chunk_first is
/// true for a chunk's first position (it must not lean on k − 1). emit(k) is called once for
/// every k, in increasing order, under one lock, from whichever worker completes the run of
/// finished positions. An exception from solve or emit stops the workers (each finishes its
/// current position) and is rethrown here.
void RunOrderedChunks(
    int count, int threads, solvers::Backend backend,
    const std::function<void(int k, bool chunk_first, solvers::ContactSolver& solver)>& solve,
    const std::function<void(int k)>& emit);

}  // namespace epicycle::transmission::internal
