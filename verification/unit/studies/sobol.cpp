// Sobol indices (studies/sobol.hpp, docs/studies.md "Sensitivity: Sobol indices"): the
// estimators on Ishigami's function against its closed-form indices; the bootstrap's standard
// error against the delta method's and the 1/√N law; the Saltelli design of a study (A_B^(i) is A
// with variable i's values from B, a run-out's amplitude and phase together, the seeds of a
// Monte-Carlo study); the study file's rules for the design.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "epicycle/studies/sampling.hpp"
#include "epicycle/studies/sobol.hpp"
#include "figures.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;
using Catch::Contains;

namespace {

constexpr double kPi = std::numbers::pi;

// Ishigami & Homma (1990): f = sin x1 + a sin² x2 + b x3⁴ sin x1, x_i ~ U(−π, π).
double Ishigami(const double* x, double a, double b) {
  return std::sin(x[0]) + a * std::sin(x[1]) * std::sin(x[1]) +
         b * std::pow(x[2], 4) * std::sin(x[0]);
}

// The closed-form indices (Sobol' & Levitan 1999; Saltelli et al. 2008, "Global Sensitivity
// Analysis. The Primer", §4.9): V = a²/8 + bπ⁴/5 + b²π⁸/18 + 1/2, V1 = (1 + bπ⁴/5)²/2,
// V2 = a²/8, V3 = 0, V13 = b²π⁸ (1/18 − 1/50); S_T1 = (V1 + V13)/V, S_T2 = V2/V, S_T3 = V13/V.
struct Closed {
  double s[3], st[3];
};
Closed IshigamiIndices(double a, double b) {
  const double pi4 = std::pow(kPi, 4), pi8 = std::pow(kPi, 8);
  const double v = a * a / 8 + b * pi4 / 5 + b * b * pi8 / 18 + 0.5;
  const double v1 = 0.5 * (1 + b * pi4 / 5) * (1 + b * pi4 / 5), v2 = a * a / 8;
  const double v13 = b * b * pi8 * (1.0 / 18 - 1.0 / 50);
  return {{v1 / v, v2 / v, 0.0}, {(v1 + v13) / v, v2 / v, v13 / v}};
}

// Ishigami's outputs in the design's case order y[j (d + 2) + m] (A, B, A_B^(1..3)), drawn from
// the test's own generator.
std::vector<double> IshigamiDesign(long n, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  std::vector<double> y;
  for (long j = 0; j < n; ++j) {
    double a[3], b[3];
    for (double& v : a) v = u(g);
    for (double& v : b) v = u(g);
    y.push_back(Ishigami(a, 7, 0.1));
    y.push_back(Ishigami(b, 7, 0.1));
    for (int i = 0; i < 3; ++i) {
      double e[3] = {a[0], a[1], a[2]};
      e[i] = b[i];
      y.push_back(Ishigami(e, 7, 0.1));
    }
  }
  return y;
}

}  // namespace

TEST_CASE("Sobol indices of Ishigami's function against the closed form", "[unit][studies]") {
  const Closed c = IshigamiIndices(7, 0.1);
  // The closed form as published (four decimals).
  CHECK(c.s[0] == Approx(0.3139).margin(5e-5));
  CHECK(c.s[1] == Approx(0.4424).margin(5e-5));
  CHECK(c.st[0] == Approx(0.5576).margin(5e-5));
  CHECK(c.st[2] == Approx(0.2437).margin(5e-5));

  const long n = 20000;
  studies::SobolOptions o;
  o.bootstrap = 400;
  o.level = 0.999;
  o.seed = 11;
  const studies::SobolEstimate e = studies::EstimateSobol(IshigamiDesign(n, 5), 3, o);
  REQUIRE(e.rows == n);
  // V(Y) of the design against the closed form V = 13.845 within 4 of its standard errors,
  // √((μ4 − V²)/(2N)) ≤ √(μ4/(2N)), μ4 = E(Y − μ)⁴ ≤ (max |Y − μ|)² V ≤ (1 + 7 + 0.1π⁴ + 3.5)² V.
  const double v = 49.0 / 8 + 0.1 * std::pow(kPi, 4) / 5 + 0.01 * std::pow(kPi, 8) / 18 + 0.5;
  const double range = 1 + 7 + 0.1 * std::pow(kPi, 4) + 3.5;
  CHECK(std::abs(e.variance - v) <= 4 * std::sqrt(range * range * v / (2.0 * n)));
  for (int i = 0; i < 3; ++i) {
    INFO("variable " << i + 1);
    const auto &s = e.first[static_cast<std::size_t>(i)], &t = e.total[static_cast<std::size_t>(i)];
    // Each estimate within 4 standard errors (the bootstrap's) of the closed form: a normal
    // estimator is that far off with probability 6e-5; the 99.9 % percentile interval covers it.
    CHECK(std::abs(s.value - c.s[i]) <= 4 * s.standard_error);
    CHECK(std::abs(t.value - c.st[i]) <= 4 * t.standard_error);
    for (const auto& [name, x, exact] :
         {std::tuple{"S_", s, c.s[i]}, std::tuple{"S_T", t, c.st[i]}})
      test::VerifyRow("Sobol indices, Ishigami (a = 7, b = 0.1), N = 20000: " + std::string(name) +
                          std::to_string(i + 1),
                      "closed form " + test::Sci(exact, 4),
                      test::Sci(x.value, 4) + " [" + test::Sci(x.lower, 4) + ", " +
                          test::Sci(x.upper, 4) + "] (99.9 %)",
                      test::Sci(std::abs(x.value - exact)),
                      "4 bootstrap SE = " + test::Sci(4 * x.standard_error),
                      std::abs(x.value - exact) <= 4 * x.standard_error && x.lower <= exact &&
                          exact <= x.upper);
    CHECK(s.lower <= c.s[i]);
    CHECK(c.s[i] <= s.upper);
    CHECK(t.lower <= c.st[i]);
    CHECK(c.st[i] <= t.upper);
  }
  // The bootstrap's standard error against the delta method's: each index is a ratio of row
  // means, S = mean(u_j)/mean(w_j) with w_j = ((y_A,j − μ)² + (y_B,j − μ)²)/2 (V's share of row
  // j) and u_j = y_B (y_ABi − y_A) (first order) or (y_A − y_ABi)²/2 (total), so
  // SE ≈ sd(u_j − S w_j)/(√N mean(w)) (the centring's own error neglected: the sums' derivatives
  // in μ have expectation 0). A standard error from 400 resamples is itself within ±3.5 % (1σ,
  // 1/√(2·400)): ±15 % allowed (4σ).
  const std::vector<double> y = IshigamiDesign(n, 5);
  double mu = 0;
  for (double x : y) mu += x;
  mu /= static_cast<double>(y.size());
  auto delta_se = [&](int i, bool total) {
    std::vector<double> u, w;
    for (long j = 0; j < n; ++j) {
      const double* r = &y[static_cast<std::size_t>(j) * 5];
      const double a = r[0] - mu, b = r[1] - mu, abi = r[2 + i] - mu;
      u.push_back(total ? 0.5 * (a - abi) * (a - abi) : b * (abi - a));
      w.push_back(0.5 * (a * a + b * b));
    }
    double mu_u = 0, mu_w = 0;
    for (long j = 0; j < n; ++j)
      mu_u += u[static_cast<std::size_t>(j)], mu_w += w[static_cast<std::size_t>(j)];
    mu_u /= static_cast<double>(n);
    mu_w /= static_cast<double>(n);
    double ss = 0;
    for (long j = 0; j < n; ++j) {
      const double d =
          u[static_cast<std::size_t>(j)] - mu_u / mu_w * w[static_cast<std::size_t>(j)];
      ss += d * d;
    }
    return std::sqrt(ss / static_cast<double>(n - 1)) / (std::sqrt(static_cast<double>(n)) * mu_w);
  };
  for (int i = 0; i < 3; ++i) {
    INFO("variable " << i + 1);
    CHECK(e.first[static_cast<std::size_t>(i)].standard_error ==
          Approx(delta_se(i, false)).epsilon(0.15));
    CHECK(e.total[static_cast<std::size_t>(i)].standard_error ==
          Approx(delta_se(i, true)).epsilon(0.15));
  }
  // The bootstrap standard error falls as 1/√N: a quarter of the rows, twice the error. The
  // ratio's own spread (a standard error estimated from 400 resamples is within ±3.5 % at 1σ,
  // two of them ±5 %; and the two designs differ) is well inside [1.6, 2.5].
  const studies::SobolEstimate q = studies::EstimateSobol(IshigamiDesign(n / 4, 6), 3, o);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(q.first[i].standard_error / e.first[i].standard_error == Approx(2.0).margin(0.45));
    CHECK(q.total[i].standard_error / e.total[i].standard_error == Approx(2.0).margin(0.45));
  }
}

TEST_CASE("Sobol indices: an additive function's shares sum to one", "[unit][studies]") {
  // f = x1 + 2 x2 + 3 x3 (x_i ~ U(0, 1)): S_i = S_Ti = c_i²/Σc² exactly, no interactions, Σ S_i
  // = 1. The Jansen total is exact term by term here ((y_A − y_ABi)² = c_i² (a_i − b_i)²), so
  // both estimates sit within 4 bootstrap standard errors of the closed form.
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> y;
  const double c[3] = {1, 2, 3};
  auto f = [&](const double* x) { return c[0] * x[0] + c[1] * x[1] + c[2] * x[2]; };
  for (int j = 0; j < 5000; ++j) {
    double a[3], b[3];
    for (double& v : a) v = u(g);
    for (double& v : b) v = u(g);
    y.push_back(f(a));
    y.push_back(f(b));
    for (int i = 0; i < 3; ++i) {
      double e[3] = {a[0], a[1], a[2]};
      e[i] = b[i];
      y.push_back(f(e));
    }
  }
  studies::SobolOptions o;
  o.bootstrap = 300;
  const studies::SobolEstimate e = studies::EstimateSobol(y, 3, o);
  double sum = 0;
  for (int i = 0; i < 3; ++i) {
    const double exact = c[i] * c[i] / 14.0;
    const auto &s = e.first[static_cast<std::size_t>(i)], &t = e.total[static_cast<std::size_t>(i)];
    CHECK(std::abs(s.value - exact) <= 4 * s.standard_error);
    CHECK(std::abs(t.value - exact) <= 4 * t.standard_error);
    sum += s.value;
  }
  CHECK(std::abs(sum - 1.0) < 0.05);
  // A failed case drops its row whole: the estimate is that of the other rows.
  std::vector<double> holed = y;
  holed[7] = std::nan("");  // row 1, A_B^(1)
  std::vector<double> without(y.begin(), y.begin() + 5);
  without.insert(without.end(), y.begin() + 10, y.end());
  o.bootstrap = 0;
  const studies::SobolEstimate h = studies::EstimateSobol(holed, 3, o),
                               w = studies::EstimateSobol(without, 3, o);
  CHECK(h.rows == 4999);
  CHECK(h.first[2].value == Approx(w.first[2].value).epsilon(1e-12));
  CHECK(h.total[0].value == Approx(w.total[0].value).epsilon(1e-12));
  CHECK(std::isnan(h.first[0].lower));  // no resamples asked: no interval
  // A constant output has no shares.
  const studies::SobolEstimate k = studies::EstimateSobol(std::vector<double>(50, 1.5), 3, o);
  CHECK(k.variance == 0);
  CHECK(std::isnan(k.first[0].value));
  CHECK_THROWS_WITH(studies::EstimateSobol(std::vector<double>(7, 1.0), 3, o),
                    Contains("7 outputs: must be N (d + 2) = N x 5"));
}

TEST_CASE("Sobol design of a study: A, B and A_B^(i) from the Monte-Carlo streams",
          "[unit][studies]") {
  const studies::StudySpec s = studies::ParseStudy(
      test::StudyText("seed = 9\ndesign = \"sobol\"\nsamples = 12\nsun = \"fixed\"",
                      "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planets\"\n"
                      "distribution = \"normal\"\nsigma_um = 5.0\n"
                      "[[variable]]\nquantity = \"runout\"\ngear = \"sun\"\n"
                      "distribution = \"uniform\"\nmin_um = 0\nmax_um = 10\n"),
      "sobol.toml", "");
  // d = 4 variables (three pins, one run-out of two columns): N (d + 2) cases.
  REQUIRE(s.variables.size() == 4);
  CHECK(s.Cases() == 12 * 6);
  CHECK(studies::SobolVariableNames(s) ==
        std::vector<std::string>{"planet1.pin_tangential", "planet2.pin_tangential",
                                 "planet3.pin_tangential", "sun.runout"});
  // The same file as a Monte-Carlo study: its case k is stream k.
  const studies::StudySpec mc = studies::ParseStudy(
      test::StudyText("seed = 9\nsamples = 24\nsun = \"fixed\"",
                      "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planets\"\n"
                      "distribution = \"normal\"\nsigma_um = 5.0\n"
                      "[[variable]]\nquantity = \"runout\"\ngear = \"sun\"\n"
                      "distribution = \"uniform\"\nmin_um = 0\nmax_um = 10\n"),
      "mc.toml", "");
  for (long j : {0L, 5L, 11L}) {
    const std::vector<double> a = studies::SampleCase(s, 6 * j),
                              b = studies::SampleCase(s, 6 * j + 1);
    CHECK(a == studies::SampleCase(mc, 2 * j));
    CHECK(b == studies::SampleCase(mc, 2 * j + 1));
    // Columns: pin1, pin2, pin3, run-out amplitude, run-out phase.
    const std::size_t first[4] = {0, 1, 2, 3}, count[4] = {1, 1, 1, 2};
    for (int i = 0; i < 4; ++i) {
      const std::vector<double> e = studies::SampleCase(s, 6 * j + 2 + i);
      for (std::size_t k = 0; k < 5; ++k) {
        const bool from_b = k >= first[i] && k < first[i] + count[i];
        INFO("row " << j << ", A_B^(" << i + 1 << "), column " << k);
        CHECK(e[k] == (from_b ? b[k] : a[k]));
        CHECK(a[k] != b[k]);  // independent draws: no column coincides
      }
    }
    const studies::SobolCase c = studies::SobolCaseOf(s, 6 * j + 3);
    CHECK(c.row == j);
    CHECK(c.matrix == 3);
  }
}

TEST_CASE("study file: the Sobol design's rules", "[unit][studies]") {
  const std::string pins =
      "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planets\"\ndistribution = "
      "\"normal\"\nsigma_um = 5.0\n";
  CHECK_THAT(test::StudyError(test::StudyText("design = \"sobol\"\nsamples = 4", pins)),
             Contains("study.samples = 4") &&
                 Contains("with design = \"sobol\" the base sample N must be a whole number in "
                          "[10, 200000000]") &&
                 Contains("N (d + 2) = N x 5 cases, d = 3 variables"));
  CHECK_THAT(test::StudyError(test::StudyText(
                 "design = \"sobol\"\nsamples = 20",
                 pins + "[[variable]]\nquantity = \"torque\"\ndistribution = \"grid\"\n"
                        "values_Nm = [-500.0, -600.0]\n")),
             Contains("study.design = \"sobol\"") &&
                 Contains("variable stage.torque_Nm has distribution \"grid\": a Sobol design "
                          "samples random variables only"));
  CHECK_THAT(test::StudyError(test::StudyText("design = \"sobol\"\nsamples = 20", "")),
             Contains("study.design = \"sobol\": a Sobol design needs at least one random "
                      "[[variable]]"));
  CHECK_THAT(test::StudyError(test::StudyText("design = \"saltelli\"", pins)),
             Contains("study.design = \"saltelli\"") &&
                 Contains("must be one of \"monte-carlo\", \"sobol\""));
}
