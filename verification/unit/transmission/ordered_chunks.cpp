// The ordered chunks of the position sweeps (transmission/src/ordered_chunks.hpp) with a bound on
// the positions in flight: every position solved and handed on once, in order; a sweep within the
// bound split one chunk per worker as without it; beyond it, no position solved further than the
// bound from the first one not yet handed on, so that a ring of bound + 1 result slots never
// loses a result before it is handed on nor a chunk's previous position before the next is solved;
// an exception stops the workers waiting for the window too.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "../../../transmission/src/ordered_chunks.hpp"

namespace epicycle::transmission::internal {

TEST_CASE("ordered chunks: a bound on the positions in flight, a ring of results",
          "[unit][transmission]") {
  for (int threads : {1, 2, 3}) {
    for (int count : {7, 64, 1000}) {
      const int in_flight = 64, slots = in_flight + 1;
      std::vector<int> ring(static_cast<std::size_t>(slots), -1);
      std::vector<int> solved(static_cast<std::size_t>(count), 0), starts;
      std::vector<int> emitted;
      std::atomic<int> next{0};
      int furthest = 0;
      std::mutex lock;
      std::atomic<bool> ring_ok{true};
      RunOrderedChunks(
          count, threads, solvers::Backend::kActiveSetNewton,
          [&](int k, bool chunk_first, solvers::ContactSolver&) {
            {
              const std::lock_guard<std::mutex> guard(lock);
              furthest = std::max(furthest, k - next.load());
            }
            // The previous position of the chunk is still in its slot.
            if (!chunk_first && ring[static_cast<std::size_t>((k - 1) % slots)] != k - 1)
              ring_ok = false;
            ring[static_cast<std::size_t>(k % slots)] = k;
            ++solved[static_cast<std::size_t>(k)];
          },
          [&](int k) {
            if (ring[static_cast<std::size_t>(k % slots)] != k) ring_ok = false;
            emitted.push_back(k);
            next = k + 1;
          },
          in_flight);
      CAPTURE(threads, count);
      CHECK(ring_ok);
      CHECK(std::all_of(solved.begin(), solved.end(), [](int s) { return s == 1; }));
      REQUIRE(emitted.size() == static_cast<std::size_t>(count));
      for (int k = 0; k < count; ++k) CHECK(emitted[static_cast<std::size_t>(k)] == k);
      CHECK(furthest < in_flight);
    }
  }
}

TEST_CASE("ordered chunks: within the bound, one chunk per worker as without it",
          "[unit][transmission]") {
  // The split of a sweep of `count` positions on `workers` workers without a bound: chunk t
  // starts at count·t/workers (the one-chunk-per-worker rule), whatever the bound above count.
  for (int bound : {0, 100, 1000}) {
    const int count = 100, threads = 3;
    std::vector<int> firsts;
    std::mutex lock;
    RunOrderedChunks(
        count, threads, solvers::Backend::kActiveSetNewton,
        [&](int k, bool chunk_first, solvers::ContactSolver&) {
          const std::lock_guard<std::mutex> guard(lock);
          if (chunk_first) firsts.push_back(k);
        },
        [](int) {}, bound);
    std::sort(firsts.begin(), firsts.end());
    CAPTURE(bound);
    CHECK(firsts == std::vector<int>{0, 33, 66});
  }
}

TEST_CASE("ordered chunks: an exception stops the workers waiting for the window",
          "[unit][transmission]") {
  std::atomic<int> solved{0};
  CHECK_THROWS_WITH(RunOrderedChunks(
                        1000, 3, solvers::Backend::kActiveSetNewton,
                        [&](int k, bool, solvers::ContactSolver&) {
                          ++solved;
                          if (k == 10) throw std::runtime_error("position 10");
                        },
                        [](int) {}, 30),
                    "position 10");
  CHECK(solved < 1000);
}

}  // namespace epicycle::transmission::internal
