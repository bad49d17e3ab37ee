// Statistics of a study's results: moments, percentiles with distribution-free confidence
// intervals, histogram, empirical CDF and rank correlation (docs/studies.md).
#pragma once

#include <utility>
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

/// An exceedance probability P(X > x) estimated from k of n independent cases above x, with its
/// Clopper–Pearson interval (exact binomial, conservative: it covers p with probability >= level
/// for every p, docs/studies.md "Results").
struct Exceedance {
  double threshold = 0;  ///< x [the variable's unit]
  long count = 0;        ///< n, the cases with a finite value [-]
  long above = 0;        ///< k, the cases with a value > x [-]
  double p = 0;          ///< k/n (NaN for n = 0) [-]
  double lower = 0, upper = 0;  ///< [p_L, p_U]; p_L = 0 for k = 0, p_U = 1 for k = n [-]
  double level = 0.95;          ///< of the interval [-]
};

/// The Clopper–Pearson interval of a binomial proportion from k successes in n trials: p_L solves
/// P(B >= k | p_L) = α/2, p_U solves P(B <= k | p_U) = α/2, B ~ Bin(n, p), α = 1 − level.
/// @throws std::invalid_argument unless 0 <= k <= n, n >= 1 and level in (0, 1).
std::pair<double, double> ClopperPearson(long k, long n, double level);

/// P(X > x) of the finite entries of `x` (NaN skipped) with its Clopper–Pearson interval.
Exceedance ExceedanceProbability(const std::vector<double>& x, double threshold,
                                 double level = 0.95);

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
