// Harmonic balance against shooting (docs/periodic.md §3, "Harmonic balance"): the backlash
// oscillator's orbits, whose contact loss makes the forces non-smooth, to the truncation error of
// the harmonics kept, and its Floquet multipliers by Hill's method; the paper stage's orbit (spring
// contacts, sun fixed) at two speeds to the same kind of bound.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/harmonic_balance.hpp"
#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/periodic_systems.hpp"
#include "epicycle/dynamics/stage_periodic.hpp"
#include "epicycle/io/units.hpp"
#include "figures.hpp"

using namespace epicycle;
using dynamics::FourierBasis;
using dynamics::HarmonicBalanceOptions;
using dynamics::HarmonicBalanceResult;

namespace {

// Σ over the upper octave H/2 < k ≤ H of the harmonics' amplitudes √(a_k² + b_k²), per component.
Eigen::VectorXd UpperOctave(const Eigen::MatrixXd& c) {
  const int h = static_cast<int>(c.rows() - 1) / 2;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(c.cols());
  for (int k = h / 2 + 1; k <= h; ++k)
    for (Eigen::Index i = 0; i < c.cols(); ++i) sum(i) += std::hypot(c(2 * k - 1, i), c(2 * k, i));
  return sum;
}

// The orbit's truncation bound per component: the dropped harmonics Σ_{k>H} |Y_k| and the aliasing
// of the kept ones by them (harmonic N − k of the AFT's samples folds onto k: the same tail again).
// For amplitudes falling like k^{−p}, p ≥ 2 (a force with a kink: the backlash's, a tooth pair's
// entry), Σ_{k>H} ≤ Σ_{H/2<k≤H} (the ratio is 1/(2^{p−1} − 1) ≤ 1), so the bound is twice the
// upper octave of the harmonics kept.
Eigen::VectorXd TruncationBound(const Eigen::MatrixXd& c) { return 2 * UpperOctave(c); }

}  // namespace

TEST_CASE(
    "backlash oscillator: the harmonic-balance orbit approaches shooting's as the truncation error "
    "falls with H",
    "[crosscheck][dynamics][harmonic_balance]") {
  const dynamics::BacklashOscillator s;
  dynamics::ShootingOptions so;
  so.rtol = 1e-11;
  so.atol = Eigen::VectorXd::Constant(1, 1e-13);
  // Ω = 0.6 on the large (separating) orbit from x = 0, Ω = 0.9 separating from x = 1.1, Ω = 1.5 in
  // contact throughout (the linear oscillator's orbit: a single harmonic).
  struct Case {
    double omega, x0;
  };
  for (const Case c : {Case{0.6, 0.0}, Case{0.9, 1.1}, Case{1.5, 1.1}}) {
    const Eigen::Vector2d p(c.omega, s.alternating_force);
    const dynamics::ShootingResult shot = dynamics::SolvePeriodicOrbit(s, so, Eigen::Vector2d(c.x0, 0), p);
    REQUIRE(shot.status == dynamics::ShootingStatus::kConverged);
    const Eigen::MatrixXd orbit = dynamics::SampleOrbit(s, so, shot.initial_state, p, 256);
    double first_error = 0, last_error = 0;
    for (const int h : {16, 32, 64}) {
      HarmonicBalanceOptions o;
      o.harmonics = h;
      o.rtol = 1e-10;
      o.atol = Eigen::VectorXd::Constant(1, 1e-12);
      // The guess: the shooting orbit's coefficients (the branch the test compares with).
      const FourierBasis basis(h, o.SampleCount());
      const Eigen::MatrixXd samples =
          dynamics::SampleOrbit(s, so, shot.initial_state, p, o.SampleCount()).topRows(o.SampleCount());
      const HarmonicBalanceResult r = dynamics::SolveHarmonicBalance(s, o, basis.analysis * samples, p);
      INFO("Omega " << c.omega << ", H " << h << ": " << r.message);
      REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
      const Eigen::MatrixXd hb =
          basis.Evaluate(r.coefficients, Eigen::VectorXd::LinSpaced(257, 0.0, 1.0));
      // The truncation enters through the force: the AFT aliases the force's harmonics above
      // N − H onto the kept ones, and the force's tail is the rate's (v' = f), not the
      // displacement's, which falls faster by a factor k. The dynamics carry a force error to
      // x and to v alike near the natural frequency (δx ≈ δv/ω_n, ω_n = 1 in these units), so both
      // components are held to the bound of both octaves.
      const Eigen::VectorXd octaves = TruncationBound(r.coefficients);
      const Eigen::Vector2d bound = Eigen::Vector2d::Constant(octaves.sum());
      // The shooting orbit's own error: its R to newton_tolerance local tolerances and a global
      // error of one local tolerance a step (docs/periodic.md §2), ≤ 1e-8 here (a few thousand
      // steps at 1e-11); the HB update's to newton_tolerance (1) weighted, 1e-10 |y| + 1e-12.
      const double floor = 1e-8 + 1e-9;
      double error = 0;
      for (int i = 0; i < 2; ++i) {
        const double e = (hb.col(i) - orbit.col(i)).cwiseAbs().maxCoeff();
        error = std::max(error, e);
        CHECK(e <= bound(i) + floor);
      }
      test::FigureValue("backlash Omega " + std::to_string(c.omega).substr(0, 3) + " H " +
                            std::to_string(h) + ": HB - shooting orbit",
                        error, "-");
      test::FigureValue("backlash Omega " + std::to_string(c.omega).substr(0, 3) + " H " +
                            std::to_string(h) + ": truncation bound",
                        bound.maxCoeff() + floor, "-");
      if (h == 16) first_error = error;
      last_error = error;
      // Hill's method: the sum of a 2-state system's exponents is ∫ tr J = −2ζT whatever g(x)
      // (Liouville), so |μ|² = μ μ̄ = e^{−2ζT} for the complex pair both methods find here: the
      // spectral radius agrees to the eigensolvers' round-off. The pair's phase depends on where
      // the contact switches, which the AFT's samples resolve to 1/N of the period: it converges
      // like 1/N (docs/periodic.md §3), and is reported, not asserted.
      CHECK(std::abs(r.floquet.spectral_radius - shot.floquet.spectral_radius) <= 1e-8);
      CHECK(r.floquet.stability == shot.floquet.stability);
      double phase = 0;
      for (const std::complex<double> mu : r.floquet.multipliers) {
        double nearest = 4;  // > π
        for (const std::complex<double> ms : shot.floquet.multipliers)
          nearest = std::min(nearest, std::abs(std::arg(mu * std::conj(ms))));
        phase = std::max(phase, nearest);
      }
      test::FigureValue("backlash Omega " + std::to_string(c.omega).substr(0, 3) + " H " +
                            std::to_string(h) + ": Hill phase error",
                        phase, "rad");
    }
    // The error falls with H (H^{-2} for the separating orbits, measured: docs/periodic.md §3):
    // from 16 to 64 harmonics at least fourfold, unless it is at the floor already (in contact).
    if (first_error > 100 * 1e-8) CHECK(last_error <= first_error / 4);
  }
}

namespace {

test::DynamicRig SpringRig(double rpm) {
  test::RigOptions o;
  o.spring = 1e-9;
  o.spring_mesh_stiffness = 1.5e9;
  o.sun = transmission::SunSupport::kFixed;
  o.edit = [rpm](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(rpm); };
  return test::MakeRig(test::SceneText("paper_stage.toml"), "springs", o);
}

}  // namespace

TEST_CASE(
    "paper stage, perfect, springs: the harmonic-balance orbit is shooting's to the truncation "
    "error",
    "[crosscheck][dynamics][harmonic_balance]") {
  for (const double rpm : {4000.0, 10000.0}) {
    const auto rig = SpringRig(rpm);
    const dynamics::DynamicModel& m = *rig.model;
    const dynamics::StagePeriodicSystem system(m, solvers::Backend::kActiveSetNewton, {});
    const int n = m.size();
    dynamics::ShootingOptions so;
    so.rtol = 1e-8;
    Eigen::VectorXd atol(2 * n);
    for (int k = 0; k < n; ++k) {
      atol(k) = m.dofs()[k].axis == dynamics::MotionDof::kRotation ? 1e-11 : 1e-12;
      atol(n + k) = atol(k) * 1e4;
    }
    so.atol = atol;
    Eigen::VectorXd y0 = Eigen::VectorXd::Zero(2 * n);
    y0.head(n) = m.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
    const dynamics::ShootingResult shot = dynamics::SolvePeriodicOrbit(system, so, y0);
    REQUIRE(shot.status == dynamics::ShootingStatus::kConverged);
    const Eigen::MatrixXd orbit = dynamics::SampleOrbit(system, so, shot.initial_state, {}, 128);
    HarmonicBalanceOptions o;
    o.harmonics = 32;
    o.rtol = so.rtol;
    o.atol = so.atol;
    const HarmonicBalanceResult r = dynamics::SolveHarmonicBalance(system, o, y0);
    INFO(rpm << " rpm: " << r.message);
    REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
    test::FigureValue("stage " + std::to_string(static_cast<int>(rpm)) +
                          " rpm, H 32: Newton iterations from the quasi-static start",
                      r.iterations, "-");
    const FourierBasis basis(o.harmonics, o.SampleCount());
    const Eigen::MatrixXd hb =
        basis.Evaluate(r.coefficients, Eigen::VectorXd::LinSpaced(129, 0.0, 1.0));
    const Eigen::VectorXd bound = TruncationBound(r.coefficients);
    double worst = 0;
    for (int i = 0; i < 2 * n; ++i) {
      // Shooting's orbit error: (steps + newton_tolerance)/(1 − ρ) local tolerances
      // (docs/periodic.md §3, the stage's rows), with the steps of its period.
      const double steps = static_cast<double>(shot.steps) / static_cast<double>(shot.integrations);
      const double scale = orbit.col(i).cwiseAbs().maxCoeff();
      const double floor = (steps + so.newton_tolerance) / (1 - shot.floquet.spectral_radius) *
                           (so.rtol * scale + so.atol(i));
      const double e = (hb.col(i) - orbit.col(i)).cwiseAbs().maxCoeff();
      INFO("component " << i << ": error " << e << ", bound " << bound(i) << " + " << floor);
      CHECK(e <= bound(i) + floor);
      worst = std::max(worst, e / (bound(i) + floor));
    }
    test::FigureValue("stage " + std::to_string(static_cast<int>(rpm)) +
                          " rpm, H 32: worst HB error over its bound",
                      worst, "-");
    // Stability: both stable, spectral radii close (Hill's is the truncated system's).
    CHECK(r.floquet.stability == shot.floquet.stability);
    test::FigureValue("stage " + std::to_string(static_cast<int>(rpm)) + " rpm: spectral radius Hill",
                      r.floquet.spectral_radius, "-");
    test::FigureValue("stage " + std::to_string(static_cast<int>(rpm)) +
                          " rpm: spectral radius shooting",
                      shot.floquet.spectral_radius, "-");
  }
}
