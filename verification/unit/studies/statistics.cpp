// The studies' statistics against closed forms: the order-statistic ranks of a percentile's
// confidence interval (the classic median table), its coverage by brute force, Spearman's ρ
// without ties (1 − 6Σd²/(n(n²−1))) and its invariance under monotone maps; the Clopper–Pearson
// interval of an exceedance probability against its closed forms, a published value and its
// definition summed term by term.
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

TEST_CASE("exceedance probability with its Clopper-Pearson interval", "[unit][studies]") {
  // Closed forms at the ends (the binomial tail is one term there): k = 0 of n gives
  // [0, 1 − (α/2)^(1/n)], k = n gives [(α/2)^(1/n), 1]; n = 10, 95 %: 0.3084971, 0.6915029.
  const double a = std::pow(0.025, 0.1);
  auto [lo0, up0] = studies::ClopperPearson(0, 10, 0.95);
  CHECK(lo0 == 0.0);
  CHECK(up0 == Approx(1.0 - a).epsilon(1e-12));
  auto [lon, upn] = studies::ClopperPearson(10, 10, 0.95);
  CHECK(lon == Approx(a).epsilon(1e-12));
  CHECK(upn == 1.0);
  // k = 5 of n = 20: the published interval [0.08657, 0.49105] (R's binom.test, the Beta
  // quantiles B(0.025; 5, 16) and B(0.975; 6, 15)), to its printed digits.
  auto [lo, up] = studies::ClopperPearson(5, 20, 0.95);
  CHECK(lo == Approx(0.0865715).margin(1e-6));
  CHECK(up == Approx(0.4910459).margin(1e-6));
  // The definition by direct summation of the pmf (not the library's binomial CDF):
  // P(B >= 5 | p_L) = P(B <= 5 | p_U) = 0.025.
  auto tail = [](int k0, int k1, int n, double p) {
    double s = 0;
    for (int k = k0; k <= k1; ++k)
      s += std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0)) *
           std::pow(p, k) * std::pow(1 - p, n - k);
    return s;
  };
  CHECK(tail(5, 20, 20, lo) == Approx(0.025).margin(1e-10));
  CHECK(tail(0, 5, 20, up) == Approx(0.025).margin(1e-10));
  // Large n, p = 1/2: within 5 % of the normal approximation's half-width 1.96 √(1/4n) = 0.03099
  // for n = 1000 (the exact interval is slightly wider: it is conservative).
  auto [lh, uh] = studies::ClopperPearson(500, 1000, 0.95);
  CHECK(0.5 * (uh - lh) == Approx(0.030990).epsilon(0.05));
  CHECK(0.5 * (uh - lh) >= 0.030990);
  CHECK_THROWS_AS(studies::ClopperPearson(3, 2, 0.95), std::invalid_argument);

  // A known count: 7 of the 21 finite values exceed 1.25 (1.25 itself is not "> 1.25"), the NaN
  // is skipped; the interval is that of k = 7, n = 20.
  std::vector<double> kg;
  for (int i = 0; i < 13; ++i) kg.push_back(1.0 + 0.01 * i);  // 1.00 .. 1.12
  kg.push_back(1.25);
  for (int i = 0; i < 6; ++i) kg.push_back(1.3 + 0.1 * i);
  kg.push_back(std::nan(""));
  // 14 at or below, 6 above so far, and one just above.
  kg.push_back(1.2500001);
  const studies::Exceedance e = studies::ExceedanceProbability(kg, 1.25);
  CHECK(e.count == 21);
  CHECK(e.above == 7);
  CHECK(e.p == Approx(7.0 / 21.0));
  const auto [l7, u7] = studies::ClopperPearson(7, 21, 0.95);
  CHECK(e.lower == l7);
  CHECK(e.upper == u7);
  CHECK(tail(7, 21, 21, e.lower) == Approx(0.025).margin(1e-10));
  CHECK(tail(0, 7, 21, e.upper) == Approx(0.025).margin(1e-10));
  CHECK(std::isnan(studies::ExceedanceProbability({}, 1.2).p));
}
