#include "ordered_chunks.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace epicycle::transmission::internal {

int SweepWorkers(int requested, int count) {
  const int cores = static_cast<int>(std::thread::hardware_concurrency());  // 0: unknown
  return std::max(1, std::min(count, requested > 0 ? requested : std::max(1, cores)));
}

void RunOrderedChunks(
    int count, int threads, solvers::Backend backend,
    const std::function<void(int k, bool chunk_first, solvers::ContactSolver& solver)>& solve,
    const std::function<void(int k)>& emit) {
  if (count <= 0) return;
  const int workers = SweepWorkers(threads, count);
  // A later chunk's results wait (done, not yet emitted) until the chunks before it are through.
  std::mutex lock;
  std::vector<char> done(static_cast<std::size_t>(count), 0);
  int next = 0;  // the first position not yet emitted
  std::exception_ptr error;
  std::atomic<bool> stop{false};
  auto fail = [&](std::exception_ptr e) {
    const std::lock_guard<std::mutex> guard(lock);
    if (!error) error = e;
    stop = true;
  };
  auto finished = [&](int k) {
    const std::lock_guard<std::mutex> guard(lock);
    done[static_cast<std::size_t>(k)] = 1;
    if (error) return;
    try {
      for (; next < count && done[static_cast<std::size_t>(next)]; ++next) emit(next);
    } catch (...) {
      error = std::current_exception();
      stop = true;
    }
  };
  auto chunk = [&](int begin, int end) {
    try {
      auto solver = solvers::MakeContactSolver(backend);
      for (int k = begin; k < end && !stop; ++k) {
        solve(k, k == begin, *solver);
        finished(k);
      }
    } catch (...) {
      fail(std::current_exception());
    }
  };
  std::vector<std::thread> pool;
  try {
    for (int t = 1; t < workers; ++t)
      pool.emplace_back(chunk, count * t / workers, count * (t + 1) / workers);
  } catch (...) {
    fail(std::current_exception());  // a worker could not start: stop the others, report it
  }
  chunk(0, count / workers);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace epicycle::transmission::internal
