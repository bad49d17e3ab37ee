#include "epicycle/transmission/work_queue.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace epicycle::transmission {

void RunWorkQueue(std::size_t count, int threads, const std::function<void(std::size_t i)>& job,
                  const std::function<void(std::size_t i)>& done) {
  std::atomic<std::size_t> next{0};
  std::mutex lock;
  std::exception_ptr error;
  auto stop = [&] {  // under the lock
    if (!error) error = std::current_exception();
    next = count;  // no new jobs; the running ones end
  };
  auto work = [&] {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= count) return;
      try {
        job(i);
      } catch (...) {
        const std::lock_guard<std::mutex> guard(lock);
        stop();
        return;
      }
      const std::lock_guard<std::mutex> guard(lock);
      if (error) return;
      try {
        if (done) done(i);
      } catch (...) {
        stop();
        return;
      }
    }
  };
  const int workers = static_cast<int>(
      std::max<std::size_t>(1, std::min<std::size_t>(count, std::max(1, threads))));
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace epicycle::transmission
