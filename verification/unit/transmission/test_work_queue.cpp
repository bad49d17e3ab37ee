// The shared work queue (transmission/work_queue.hpp): every job runs once and is handed over
// once, under one lock; an exception stops the queue and reaches the caller.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <vector>

#include "epicycle/transmission/work_queue.hpp"

namespace epicycle::transmission {

TEST_CASE("work queue: every job once, every hand-over once, for 1 to 4 workers",
          "[unit][transmission]") {
  for (int threads : {1, 2, 4}) {
    const std::size_t count = 257;
    std::vector<int> ran(count, 0), handed(count, 0);
    std::vector<long> squares(count, -1);
    int inside = 0, most_inside = 0;  // only touched under the queue's lock
    RunWorkQueue(
        count, threads,
        [&](std::size_t i) {
          ++ran[i];  // own slot
          squares[i] = static_cast<long>(i * i);
        },
        [&](std::size_t i) {
          most_inside = std::max(most_inside, ++inside);
          ++handed[i];
          CHECK(squares[i] == static_cast<long>(i * i));  // the job finished before its hand-over
          --inside;
        });
    for (std::size_t i = 0; i < count; ++i) {
      CHECK(ran[i] == 1);
      CHECK(handed[i] == 1);
    }
    CHECK(most_inside == 1);
  }
}

TEST_CASE("work queue: an exception from a job or a hand-over stops it and is rethrown",
          "[unit][transmission]") {
  for (int threads : {1, 3}) {
    std::atomic<int> started{0};
    CHECK_THROWS_WITH(RunWorkQueue(1000, threads,
                                   [&](std::size_t i) {
                                     ++started;
                                     if (i == 37) throw std::runtime_error("job 37 failed");
                                   },
                                   {}),
                      "job 37 failed");
    // No new job after the failure: at most the ones already taken by the other workers.
    CHECK(started.load() <= 37 + 1 + threads);
    int handed = 0;
    CHECK_THROWS_WITH(RunWorkQueue(
                          1000, threads, [](std::size_t) {},
                          [&](std::size_t) {
                            if (++handed == 5) throw std::runtime_error("sink full");
                          }),
                      "sink full");
    CHECK(handed == 5);
  }
}

}  // namespace epicycle::transmission
