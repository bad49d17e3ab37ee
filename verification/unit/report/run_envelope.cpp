// The dynamic run's sampling rule (dynamics::DefaultOutputsPerCycle) against the mode it must
// resolve, and the plots' mesh-cycle envelope (report::BinEnvelope) against the raw states.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/report/run_files.hpp"

using namespace epicycle;

TEST_CASE("outputs per mesh cycle: at least 10 per period of the highest mode below the cap",
          "[unit][report]") {
  // Outputs per period of f_max = N f_m / f_max, computed here from the frequencies, not the rule.
  // The paper stage at 1500 rpm: f_m = 325 Hz, f_max = 6742 Hz (`epicycle dynamic` prints both).
  for (double f_m : {0.2, 3.25, 32.5, 325.0, 3250.0})
    for (double f_max : {0.0, 100.0, 6742.0, 20000.0}) {
      const int n = dynamics::DefaultOutputsPerCycle(f_max, f_m);
      CHECK(n >= 20);
      CHECK(n <= dynamics::kOutputsPerModePeriod * dynamics::kMaxResolvedHarmonic);
      if (f_max > 0 && f_max <= dynamics::kMaxResolvedHarmonic * f_m)
        CHECK(n * f_m / f_max >= dynamics::kOutputsPerModePeriod);
      // Not more than needed: one output fewer per cycle breaks the rule (above the floor of 20).
      if (n > 20 && f_max <= dynamics::kMaxResolvedHarmonic * f_m)
        CHECK((n - 1) * f_m / f_max < dynamics::kOutputsPerModePeriod);
    }
  CHECK_THROWS_AS(dynamics::DefaultOutputsPerCycle(100, 0), std::invalid_argument);
}

TEST_CASE("mesh-cycle envelope: every raw state within its bin, the mean the bin's average",
          "[unit][report]") {
  // A signal sampled 37 times per cycle of width 0.5 (not a whole number per bin): a mean, a
  // vibration at 9.3 cycles per bin and a slow drift, two values.
  const double width = 0.5;
  report::BinEnvelope envelope(2, 0.0, width);
  std::vector<double> xs;
  std::vector<std::vector<double>> raw;
  for (int k = 1; k <= 37 * 20; ++k) {
    const double x = width * k / 37.0;
    const std::vector<double> v{1.0 / 3 + 0.05 * std::sin(2 * M_PI * 9.3 * x / width) + 0.01 * x,
                                -2.0 * std::cos(0.7 * x)};
    envelope.Add(x, v);
    xs.push_back(x);
    raw.push_back(v);
  }
  const auto bins = envelope.Bins();
  CHECK(bins.size() >= 20);
  long total = 0;
  for (const auto& b : bins) {
    total += b.count;
    for (std::size_t j = 0; j < 2; ++j) {
      double sum = 0, lo = INFINITY, hi = -INFINITY;
      long count = 0;
      for (std::size_t k = 0; k < xs.size(); ++k) {
        if (xs[k] < b.x_first || xs[k] > b.x_last) continue;
        ++count;
        sum += raw[k][j];
        lo = std::min(lo, raw[k][j]);
        hi = std::max(hi, raw[k][j]);
        CHECK(raw[k][j] >= b.min[j]);
        CHECK(raw[k][j] <= b.max[j]);
      }
      CHECK(count == b.count);
      CHECK(lo == b.min[j]);  // the extremes are raw values themselves
      CHECK(hi == b.max[j]);
      // Same sums in the same order: equal but for the division, 1 ulp of the mean.
      const double average = sum / static_cast<double>(count);
      CHECK(std::abs(b.mean[j] - average) <= 2.3e-16 * std::abs(average));
    }
    // A bin holds states of one mesh-cycle window only.
    CHECK(std::floor(b.x_first / width) == std::floor(b.x_last / width));
  }
  CHECK(total == static_cast<long>(xs.size()));
}
