// The work queue shared by the drivers that run independent jobs in parallel (the speeds of a
// speed sweep, the cases of a study): one loop, so that exceptions, stopping and the order of the
// hand-over are the same everywhere. (A sweep whose positions lean on their neighbours uses the
// ordered chunks of the quasi-static sweep instead.)
#pragma once

#include <cstddef>
#include <functional>

namespace epicycle::transmission {

/// Runs job(i) for every i in [0, count) on `threads` workers (the calling thread is one of them;
/// at most `count`, at least 1), which take the indices in increasing order from one queue, and
/// then done(i) under one lock, in the order the jobs finish. Each job must keep to its own data
/// (its own solver, its own result slot). An exception from a job or from done stops the queue:
/// no new job starts, the running ones finish, and the first exception is rethrown here.
void RunWorkQueue(std::size_t count, int threads, const std::function<void(std::size_t i)>& job,
                  const std::function<void(std::size_t i)>& done);

}  // namespace epicycle::transmission
