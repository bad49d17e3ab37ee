// The studies' statistics against closed forms: the order-statistic ranks of a percentile's
// confidence interval (the classic median table), its coverage by brute force, Spearman's ρ
// without ties (1 − 6Σd²/(n(n²−1))) and its invariance under monotone maps.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "epicycle/studies/statistics.hpp"

using namespace epicycle;

TEST_CASE("percentile confidence intervals from order statistics", "[unit][studies]") {
  // The median of n = 20 at 95 %: [x_(6), x_(15)] (coverage 95.86 %, the textbook table).
  const auto [l, u] = studies::PercentileRanks(20, 0.5, 0.95);
  CHECK(l == 6);
  CHECK(u == 15);
  // Brute-force coverage of the P95 interval for n = 200 uniform draws (ξ_0.95 = 0.95): at
  // least 95 % minus 3σ of 2000 trials' binomial noise (σ = √(0.95·0.05/2000) = 0.0049).
  std::mt19937_64 g(1);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int covered = 0;
  const int trials = 2000;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> x(200);
    for (double& v : x) v = U(g);
    const auto s = studies::Summarise(x, {0.95});
    covered += (s.percentiles[0].lower <= 0.95 && 0.95 <= s.percentiles[0].upper) ? 1 : 0;
  }
  CHECK(static_cast<double>(covered) / trials >= 0.95 - 3 * 0.0049);
  // Too few samples for an upper bound of P99.9: reported as NaN, not made up.
  const auto s = studies::Summarise(std::vector<double>{1, 2, 3, 4, 5}, {0.999});
  CHECK(std::isnan(s.percentiles[0].upper));
}

TEST_CASE("Spearman rank correlation", "[unit][studies]") {
  const std::vector<double> x{1, 2, 3, 4, 5, 6, 7}, y{2, 1, 4, 3, 7, 5, 6};
  double d2 = 0;  // ranks are the values here
  for (std::size_t i = 0; i < x.size(); ++i) d2 += (x[i] - y[i]) * (x[i] - y[i]);
  const double n = 7, closed = 1.0 - 6.0 * d2 / (n * (n * n - 1.0));
  CHECK(studies::SpearmanCorrelation(x, y) == Approx(closed).epsilon(1e-14));
  std::vector<double> ey;
  for (double v : y) ey.push_back(std::exp(v));  // monotone: the same ranks
  CHECK(studies::SpearmanCorrelation(x, ey) == Approx(closed).epsilon(1e-14));
  CHECK(std::isnan(studies::SpearmanCorrelation(x, std::vector<double>(7, 1.0))));
}
