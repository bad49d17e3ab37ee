#include "epicycle/studies/sobol.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "epicycle/studies/sampling.hpp"

namespace epicycle::studies {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The first column of each variable in StudySpec::Columns() and its count (a run-out has two).
std::vector<std::pair<std::size_t, std::size_t>> VariableColumns(const StudySpec& study) {
  std::vector<std::pair<std::size_t, std::size_t>> c;
  std::size_t at = 0;
  for (const Variable& v : study.variables) {
    const std::size_t n = v.Columns().size();
    c.emplace_back(at, n);
    at += n;
  }
  return c;
}

// The point estimates from the rows `use` (indices into the rows of y, repeats allowed).
struct Point {
  double mean = kNaN, variance = kNaN;
  std::vector<double> first, total;
};

Point Estimate(const std::vector<double>& y, int d, const std::vector<long>& use) {
  const auto w = static_cast<std::size_t>(d + 2);
  Point p;
  p.first.assign(static_cast<std::size_t>(d), kNaN);
  p.total.assign(static_cast<std::size_t>(d), kNaN);
  const auto n = static_cast<double>(use.size());
  if (use.size() < 2) return p;
  double sum = 0;
  for (long j : use)
    for (std::size_t m = 0; m < w; ++m) sum += y[static_cast<std::size_t>(j) * w + m];
  p.mean = sum / (n * static_cast<double>(w));
  // V(Y) from the 2N outputs of A and B (independent draws of Y), sample variance.
  double ab = 0;
  for (long j : use)
    ab += y[static_cast<std::size_t>(j) * w] + y[static_cast<std::size_t>(j) * w + 1];
  ab /= 2 * n;
  double ss = 0;
  for (long j : use)
    for (std::size_t m = 0; m < 2; ++m) {
      const double e = y[static_cast<std::size_t>(j) * w + m] - ab;
      ss += e * e;
    }
  p.variance = ss / (2 * n - 1);
  if (!(p.variance > 0)) return p;  // a constant output: no shares
  for (int i = 0; i < d; ++i) {
    double first = 0, total = 0;
    for (long j : use) {
      const double* r = &y[static_cast<std::size_t>(j) * w];
      // Centred on the mean: the first-order sum's expectation does not depend on it, its
      // variance does (an uncentred K_γ ≈ 1.2 adds μ² V(y_ABi − y_A)/N to it).
      const double a = r[0] - p.mean, b = r[1] - p.mean, abi = r[2 + i] - p.mean;
      first += b * (abi - a);
      total += (a - abi) * (a - abi);
    }
    p.first[static_cast<std::size_t>(i)] = first / n / p.variance;
    p.total[static_cast<std::size_t>(i)] = total / (2 * n) / p.variance;
  }
  return p;
}

// The value of rank ⌈B q⌉ (1-based, clamped to [1, B]) of the sorted replicates.
double OrderStatistic(const std::vector<double>& sorted, double q) {
  const auto b = static_cast<double>(sorted.size());
  const long rank = std::clamp(static_cast<long>(std::ceil(b * q)), 1L, static_cast<long>(b));
  return sorted[static_cast<std::size_t>(rank - 1)];
}

}  // namespace

SobolCase SobolCaseOf(const StudySpec& study, long case_id) {
  const long w = static_cast<long>(study.variables.size()) + 2;
  return {case_id / w, static_cast<int>(case_id % w)};
}

std::vector<double> SobolCaseValues(const StudySpec& study, long case_id) {
  const SobolCase c = SobolCaseOf(study, case_id);
  if (c.matrix == 1) return DrawValues(study, 2 * c.row + 1);
  std::vector<double> values = DrawValues(study, 2 * c.row);
  if (c.matrix == 0) return values;
  const std::vector<double> b = DrawValues(study, 2 * c.row + 1);
  const auto [first, count] = VariableColumns(study)[static_cast<std::size_t>(c.matrix - 2)];
  for (std::size_t k = first; k < first + count; ++k) values[k] = b[k];
  return values;
}

std::vector<std::string> SobolVariableNames(const StudySpec& study) {
  std::vector<std::string> names;
  for (const Variable& v : study.variables) {
    std::string c = v.Columns().front();
    // The column without its unit (and a run-out without "_amplitude"): the variable.
    c = c.substr(0, c.rfind('_'));
    if (v.quantity == Quantity::kRunout) c = c.substr(0, c.rfind('_'));
    names.push_back(c);
  }
  return names;
}

void SobolOptions::Validate() const {
  if (bootstrap < 0 || bootstrap > 100000)
    throw std::invalid_argument("Sobol bootstrap = " + std::to_string(bootstrap) +
                                ": must be a whole number in [0, 100000] (resamples)");
  if (!(level > 0 && level < 1))
    throw std::invalid_argument("Sobol level = " + std::to_string(level) +
                                ": must be in (0, 1) (a confidence level)");
}

SobolEstimate EstimateSobol(const std::vector<double>& y, int d, const SobolOptions& options) {
  options.Validate();
  if (d < 1)
    throw std::invalid_argument("Sobol indices: d = " + std::to_string(d) +
                                " variables: must be >= 1");
  const auto w = static_cast<std::size_t>(d + 2);
  if (y.size() % w != 0)
    throw std::invalid_argument("Sobol indices: " + std::to_string(y.size()) +
                                " outputs: must be N (d + 2) = N x " + std::to_string(w));
  std::vector<long> rows;
  for (std::size_t j = 0; j < y.size() / w; ++j) {
    bool ok = true;
    for (std::size_t m = 0; m < w; ++m) ok = ok && std::isfinite(y[j * w + m]);
    if (ok) rows.push_back(static_cast<long>(j));
  }
  const Point p = Estimate(y, d, rows);
  SobolEstimate e;
  e.rows = static_cast<long>(rows.size());
  e.mean = p.mean;
  e.variance = p.variance;
  const auto nd = static_cast<std::size_t>(d);
  e.first.resize(nd);
  e.total.resize(nd);
  double sum = 0;
  for (std::size_t i = 0; i < nd; ++i) {
    e.first[i] = {p.first[i], kNaN, kNaN, kNaN};
    e.total[i] = {p.total[i], kNaN, kNaN, kNaN};
    sum += p.first[i];
  }
  e.sum_first = {sum, kNaN, kNaN, kNaN};
  if (options.bootstrap == 0 || rows.size() < 2 || !(p.variance > 0)) return e;
  // Resamples of the rows, drawn from one stream (the same for every output of a study).
  CaseStream rng(options.seed, -1, 0);
  const auto b = static_cast<std::size_t>(options.bootstrap);
  std::vector<std::vector<double>> first(nd), total(nd);
  std::vector<double> sums;
  std::vector<long> use(rows.size());
  for (std::size_t r = 0; r < b; ++r) {
    for (long& u : use) {
      const auto k = static_cast<std::size_t>(rng.Uniform() * static_cast<double>(rows.size()));
      u = rows[std::min(k, rows.size() - 1)];
    }
    const Point q = Estimate(y, d, use);
    if (!(q.variance > 0)) continue;  // a resample of one repeated row: no shares to resample
    double qsum = 0;
    for (std::size_t i = 0; i < nd; ++i) {
      first[i].push_back(q.first[i]);
      total[i].push_back(q.total[i]);
      qsum += q.first[i];
    }
    sums.push_back(qsum);
  }
  const double lo = 0.5 * (1 - options.level), hi = 0.5 * (1 + options.level);
  auto interval = [&](std::vector<double>& x, SobolIndex* s) {
    if (x.size() < 2) return;
    double m = 0;
    for (double v : x) m += v;
    m /= static_cast<double>(x.size());
    double ss = 0;
    for (double v : x) ss += (v - m) * (v - m);
    s->standard_error = std::sqrt(ss / static_cast<double>(x.size() - 1));
    std::sort(x.begin(), x.end());
    s->lower = OrderStatistic(x, lo);
    s->upper = OrderStatistic(x, hi);
  };
  for (std::size_t i = 0; i < nd; ++i) {
    interval(first[i], &e.first[i]);
    interval(total[i], &e.total[i]);
  }
  interval(sums, &e.sum_first);
  return e;
}

SobolSummary SummariseSobol(const StudySpec& study, const std::vector<CaseRow>& rows,
                            const SobolOptions& options) {
  if (study.design != Design::kSobol)
    throw std::invalid_argument(study.source + ": not a Sobol study (design = \"sobol\")");
  const int d = static_cast<int>(study.variables.size());
  SobolSummary s;
  s.base_samples = study.samples;
  s.bootstrap = options.bootstrap;
  s.level = options.level;
  s.variables = SobolVariableNames(study);
  // The outputs of every case in design order (NaN: no row yet or a failed case).
  std::vector<std::string> names = {"K_gamma", "K_gamma_mean", "LSR_min",
                                    "LSR_max", "TE_pp_urad",   "sun_orbit_um"};
  const std::vector<std::string> gears = study.StressGears();
  for (const std::string& g : gears)
    for (const char* q : {"sigma_t_", "sigma_c_", "sigma_range_"}) names.push_back(q + g + "_MPa");
  if (study.Rated())
    for (const std::string& g : gears)
      for (const char* q : {"S_F_", "S_H_"}) names.push_back(q + g);
  for (const std::string& m : study.FaceMeshes())
    for (const char* q : {"K_Hbeta_", "K_gamma_K_Hbeta_"}) names.push_back(q + m);
  for (const std::string& c : study.HelicalColumns()) names.push_back(c);
  const auto cases = static_cast<std::size_t>(study.Cases());
  std::vector<std::vector<double>> y(names.size(), std::vector<double>(cases, kNaN));
  for (const CaseRow& r : rows) {
    if (!r.ok() || r.id < 0 || static_cast<std::size_t>(r.id) >= cases) continue;
    const auto k = static_cast<std::size_t>(r.id);
    std::size_t o = 0;
    for (double v :
         {r.k_gamma, r.k_gamma_mean, r.lsr_min, r.lsr_max, r.te_peak_to_peak, r.sun_orbit})
      y[o++][k] = v;
    for (double v : r.root_stress) y[o++][k] = v;
    for (double v : r.safety) y[o++][k] = v;
    for (double v : r.face_load) y[o++][k] = v;
    for (double v : r.helical) y[o++][k] = v;
  }
  for (std::size_t o = 0; o < names.size(); ++o)
    s.outputs.push_back({names[o], EstimateSobol(y[o], d, options)});
  s.complete_rows = s.outputs.front().estimate.rows;  // K_γ: finite in every ok row
  return s;
}

}  // namespace epicycle::studies
