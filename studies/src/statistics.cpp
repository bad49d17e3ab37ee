#include "epicycle/studies/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

#include "epicycle/transmission/accumulator.hpp"

namespace epicycle::studies {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Two-sided standard-normal quantile z_{(1+level)/2} by bisection on erfc (no table, any level).
double NormalQuantile(double level) {
  const double tail = 0.5 * (1.0 - level);
  double lo = 0.0, hi = 40.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(mid / std::numbers::sqrt2) > tail ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// P(B <= k) for B ~ Bin(n, p), from the log pmf (no overflow for large n).
std::vector<double> BinomialCdf(long n, double p) {
  std::vector<double> cdf(static_cast<std::size_t>(n + 1));
  const double lp = std::log(p), lq = std::log1p(-p);
  double sum = 0.0;
  for (long k = 0; k <= n; ++k) {
    const double lpmf = std::lgamma(static_cast<double>(n) + 1.0) -
                        std::lgamma(static_cast<double>(k) + 1.0) -
                        std::lgamma(static_cast<double>(n - k) + 1.0) +
                        static_cast<double>(k) * lp + static_cast<double>(n - k) * lq;
    sum += std::exp(lpmf);
    cdf[static_cast<std::size_t>(k)] = std::min(1.0, sum);
  }
  return cdf;
}

std::vector<double> Ranks(const std::vector<double>& x) {
  std::vector<std::size_t> idx(x.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  std::vector<double> r(x.size());
  for (std::size_t i = 0; i < idx.size();) {
    std::size_t j = i;
    while (j + 1 < idx.size() && x[idx[j + 1]] == x[idx[i]]) ++j;
    const double avg = 0.5 * static_cast<double>(i + j) + 1.0;  // ties: the average rank
    for (std::size_t k = i; k <= j; ++k) r[idx[k]] = avg;
    i = j + 1;
  }
  return r;
}

}  // namespace

std::pair<long, long> PercentileRanks(long n, double p, double level) {
  // Ranks l < u with P(B < l) <= α/2 and P(B >= u) <= α/2, B ~ Bin(n, p): then
  // P(x_(l) <= ξ_p <= x_(u)) >= 1 − α for any continuous distribution (order statistics).
  const double alpha = 1.0 - level;
  const std::vector<double> cdf = BinomialCdf(n, p);
  long l = 0;  // the largest l with P(B <= l − 1) <= α/2
  for (long k = 1; k <= n; ++k)
    if (cdf[static_cast<std::size_t>(k - 1)] <= 0.5 * alpha) l = k;
  long u = n + 1;  // the smallest u with P(B >= u) = 1 − P(B <= u − 1) <= α/2
  for (long k = n; k >= 1; --k)
    if (1.0 - cdf[static_cast<std::size_t>(k - 1)] <= 0.5 * alpha) u = k;
  return {l, u};
}

std::pair<double, double> ClopperPearson(long k, long n, double level) {
  if (n < 1 || k < 0 || k > n || !(level > 0 && level < 1))
    throw std::invalid_argument("ClopperPearson: k = " + std::to_string(k) + ", n = " +
                                std::to_string(n) + ", level = " + std::to_string(level) +
                                ": needs 0 <= k <= n, n >= 1 and 0 < level < 1");
  const double half = 0.5 * (1.0 - level);
  // P(B <= k | p) falls as p grows; bisection on p in (0, 1) to 2^-60 (no closed form except at
  // k = 0 and k = n, which the bisection reaches as well).
  auto solve = [&](auto above_target) {
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (above_target(mid) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  const double lower =
      k == 0 ? 0.0 : solve([&](double p) {  // P(B >= k | p) = 1 − P(B <= k − 1 | p) < α/2
        return 1.0 - BinomialCdf(n, p)[static_cast<std::size_t>(k - 1)] < half;
      });
  const double upper = k == n ? 1.0 : solve([&](double p) {  // P(B <= k | p) > α/2
    return BinomialCdf(n, p)[static_cast<std::size_t>(k)] > half;
  });
  return {lower, upper};
}

Exceedance ExceedanceProbability(const std::vector<double>& x, double threshold, double level) {
  Exceedance e;
  e.threshold = threshold;
  e.level = level;
  for (double v : x) {
    if (!std::isfinite(v)) continue;
    ++e.count;
    e.above += v > threshold ? 1 : 0;
  }
  if (e.count == 0) {
    e.p = e.lower = e.upper = kNaN;
    return e;
  }
  e.p = static_cast<double>(e.above) / static_cast<double>(e.count);
  std::tie(e.lower, e.upper) = ClopperPearson(e.above, e.count, level);
  return e;
}

SampleSummary Summarise(std::vector<double> x, const std::vector<double>& levels, double level) {
  x.erase(std::remove_if(x.begin(), x.end(), [](double v) { return !std::isfinite(v); }), x.end());
  std::sort(x.begin(), x.end());
  SampleSummary s;
  s.level = level;
  // Mean, min and max by the project's one accumulator (the values in ascending order), with its
  // rule for empty input: NaN.
  transmission::Accumulator acc;
  for (double v : x) acc.Add(v);
  s.count = acc.count();
  s.mean = acc.mean();
  s.min = acc.min();
  s.max = acc.max();
  const long n = s.count;
  if (n == 0) {
    s.standard_deviation = s.mean_lower = s.mean_upper = kNaN;
    for (double p : levels) s.percentiles.push_back({p, kNaN, kNaN, kNaN});
    return s;
  }
  const double nd = static_cast<double>(n);
  double ss = 0.0;
  for (double v : x) ss += (v - s.mean) * (v - s.mean);
  s.standard_deviation = n > 1 ? std::sqrt(ss / (nd - 1.0)) : kNaN;
  const double half = n > 1 ? NormalQuantile(level) * s.standard_deviation / std::sqrt(nd) : kNaN;
  s.mean_lower = s.mean - half;
  s.mean_upper = s.mean + half;
  for (double p : levels) {
    Percentile q;
    q.p = p;
    const long k = std::clamp(static_cast<long>(std::ceil(nd * p)), 1L, n);
    q.value = x[static_cast<std::size_t>(k - 1)];
    const auto [l, u] = PercentileRanks(n, p, level);
    q.lower = l >= 1 ? x[static_cast<std::size_t>(l - 1)] : kNaN;
    q.upper = u <= n ? x[static_cast<std::size_t>(u - 1)] : kNaN;
    s.percentiles.push_back(q);
  }
  return s;
}

double SpearmanCorrelation(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> a, b;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) {
      a.push_back(x[i]);
      b.push_back(y[i]);
    }
  }
  if (a.size() < 3) return kNaN;
  const std::vector<double> ra = Ranks(a), rb = Ranks(b);
  const double n = static_cast<double>(ra.size());
  const double ma = std::accumulate(ra.begin(), ra.end(), 0.0) / n;
  const double mb = std::accumulate(rb.begin(), rb.end(), 0.0) / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    sab += (ra[i] - ma) * (rb[i] - mb);
    saa += (ra[i] - ma) * (ra[i] - ma);
    sbb += (rb[i] - mb) * (rb[i] - mb);
  }
  if (saa == 0.0 || sbb == 0.0) return kNaN;
  return sab / std::sqrt(saa * sbb);
}

Histogram MakeHistogram(const std::vector<double>& values) {
  std::vector<double> x;
  for (double v : values)
    if (std::isfinite(v)) x.push_back(v);
  Histogram h;
  if (x.empty()) return h;
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  const double iqr =
      x[static_cast<std::size_t>(0.75 * (n - 1))] - x[static_cast<std::size_t>(0.25 * (n - 1))];
  const double span = x.back() - x.front();
  int bins = 1;
  if (span > 0 && iqr > 0) bins = static_cast<int>(std::ceil(span / (2.0 * iqr / std::cbrt(n))));
  bins = std::clamp(bins, 1, 200);
  h.lo = x.front();
  h.width = span > 0 ? span / bins : 1.0;
  h.counts.assign(static_cast<std::size_t>(bins), 0);
  for (double v : x) {
    const int b = std::min(bins - 1, static_cast<int>((v - h.lo) / h.width));
    ++h.counts[static_cast<std::size_t>(b)];
  }
  return h;
}

}  // namespace epicycle::studies
