// Statistics of a study's results: moments, percentiles with distribution-free confidence
// intervals, histogram, empirical CDF and rank correlation (docs/studies.md).
#pragma once

#include <string>
#include <vector>

namespace epicycle::studies {

/// A percentile P_p and its confidence interval from order statistics.
struct Percentile {
  double p = 0;      ///< the level, in (0, 1) [-]
  double value = 0;  ///< x_(⌈n p⌉), the sample quantile (inverse of the empirical CDF)
  /// [x_(l), x_(u)] with the ranks l < u the narrowest central pair for which B ~ Bin(n, p)
  /// satisfies P(l ≤ B < u) ≥ level (exact binomial, distribution-free: it needs only
  /// independent draws of a continuous variable). NaN when n is too small for that bound to exist
  /// on that side (e.g. the upper bound of P99.9 with fewer than about 3000 cases).
  double lower = 0, upper = 0;
};

struct SampleSummary {
  long count = 0;
  double mean = 0;                        ///< x̄
  double standard_deviation = 0;          ///< s, with n − 1
  double mean_lower = 0, mean_upper = 0;  ///< x̄ ∓ z s/√n (normal approximation, CLT)
  double min = 0, max = 0;
  std::vector<Percentile> percentiles;
  double level = 0.95;  ///< of every interval [-]
};

/// The summary of `x` (NaN entries skipped) at confidence `level`, percentiles at `levels`.
/// With no finite value every statistic is NaN.
SampleSummary Summarise(std::vector<double> x, const std::vector<double>& levels,
                        double level = 0.95);

/// The exact binomial order-statistic ranks (1-based) of the CI of percentile p for n samples;
/// 0 or n + 1 where the bound does not exist.
std::pair<long, long> PercentileRanks(long n, double p, double level);

/// Spearman's rank correlation of x and y (ties get their average rank); NaN if either is
/// constant or fewer than 3 pairs are given. Pairs with a NaN are skipped.
double SpearmanCorrelation(const std::vector<double>& x, const std::vector<double>& y);

struct Histogram {
  double lo = 0, width = 0;
  std::vector<long> counts;
};
/// Freedman–Diaconis bin width 2·IQR·n^(−1/3) (at least 1 bin, at most 200).
Histogram MakeHistogram(const std::vector<double>& x);

}  // namespace epicycle::studies
