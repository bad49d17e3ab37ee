#include "ordered_chunks.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
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
    const std::function<void(int k)>& emit, int in_flight) {
  if (count <= 0) return;
  const int workers = SweepWorkers(threads, count);
  // Chunks: one per worker, or of at most in_flight/workers positions for a longer sweep.
  const bool bounded = in_flight > 0 && count > in_flight;
  const long per_chunk = bounded ? std::max(1, in_flight / workers) : count;
  const long chunks = bounded ? std::max<long>(workers, (count + per_chunk - 1) / per_chunk)
                              : workers;
  auto begin = [&](long c) { return static_cast<int>(count * c / chunks); };
  // A later chunk's results wait (done, not yet emitted) until the chunks before it are through.
  std::mutex lock;
  std::condition_variable advanced;  // `next` moved on, or the run stopped
  std::vector<char> done(static_cast<std::size_t>(count), 0);
  int next = 0;         // the first position not yet emitted
  long next_chunk = 0;  // the first chunk no worker has taken
  std::exception_ptr error;
  std::atomic<bool> stop{false};
  auto fail = [&](std::exception_ptr e) {
    {
      const std::lock_guard<std::mutex> guard(lock);
      if (!error) error = e;
      stop = true;
    }
    advanced.notify_all();
  };
  auto finished = [&](int k) {
    {
      const std::lock_guard<std::mutex> guard(lock);
      done[static_cast<std::size_t>(k)] = 1;
      if (error) return;
      try {
        for (; next < count && done[static_cast<std::size_t>(next)]; ++next) emit(next);
      } catch (...) {
        error = std::current_exception();
        stop = true;
      }
    }
    advanced.notify_all();
  };
  auto work = [&] {
    try {
      for (;;) {
        long c = 0;
        {
          // The next chunk, once all of it lies within in_flight positions of `next`.
          std::unique_lock<std::mutex> guard(lock);
          if (stop || next_chunk >= chunks) return;
          c = next_chunk++;
          advanced.wait(guard, [&] { return stop || !bounded || begin(c + 1) - next <= in_flight; });
          if (stop) return;
        }
        auto solver = solvers::MakeContactSolver(backend);
        for (int k = begin(c), end = begin(c + 1); k < end && !stop; ++k) {
          solve(k, k == begin(c), *solver);
          finished(k);
        }
      }
    } catch (...) {
      fail(std::current_exception());
    }
  };
  std::vector<std::thread> pool;
  try {
    for (int t = 1; t < workers; ++t) pool.emplace_back(work);
  } catch (...) {
    fail(std::current_exception());  // a worker could not start: stop the others, report it
  }
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace epicycle::transmission::internal
