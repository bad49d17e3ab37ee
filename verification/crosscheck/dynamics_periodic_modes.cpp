// Floquet multipliers of the paper stage's linear model against its eigenvalues (docs/periodic.md
// §3, "Floquet multipliers and modes"): the stage linearised as the modes driver linearises it
// (DynamicModel::Linearise at carrier 0 with the tangent mesh stiffness of `epicycle modes`,
// constant mesh stiffness, no contact loss), M q̈ + C q̇ + K q = f cos(2πt/T), written as a
// T-periodic system y' = A y + b cos(2πt/T) and solved by shooting over the mesh period T. For a
// linear time-invariant system the multipliers are μ_k = exp(λ_k T), λ_k the eigenvalues of A
// (docs/periodic.md §1): without damping λ = ±iω_k with ω_k = 2π f_k the modes driver's natural
// frequencies; with the model's damping the eigenvalues of A from Eigen's eigensolver.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/modes_run.hpp"
#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/stage_periodic.hpp"
#include "figures.hpp"

using namespace epicycle;

namespace {

using Complex = std::complex<double>;

// y' = A y + b cos(2πt/T): the linearised stage, T its mesh period.
class LinearStage final : public dynamics::PeriodicSystem {
 public:
  LinearStage(Eigen::MatrixXd a, Eigen::VectorXd b, double period)
      : a_(std::move(a)), b_(std::move(b)), period_(period) {}
  int size() const override { return static_cast<int>(a_.rows()); }
  std::vector<dynamics::PeriodicParameter> parameters() const override { return {}; }
  double Period(const Eigen::VectorXd&) const override { return period_; }
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
           Eigen::VectorXd* f) const override {
    *f = a_ * y + b_ * std::cos(2 * std::numbers::pi * t / period_);
    return true;
  }
  bool has_jacobian() const override { return true; }
  bool Jacobian(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                Eigen::MatrixXd* jac) const override {
    *jac = a_;
    return true;
  }

 private:
  Eigen::MatrixXd a_;
  Eigen::VectorXd b_;
  double period_;
};

// A = [0 I; −M⁻¹K −M⁻¹C].
Eigen::MatrixXd StateMatrix(const Eigen::MatrixXd& m, const Eigen::MatrixXd& k,
                            const Eigen::MatrixXd& c) {
  const Eigen::Index n = m.rows();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  a.topRightCorner(n, n) = Eigen::MatrixXd::Identity(n, n);
  a.bottomLeftCorner(n, n) = -m.ldlt().solve(k);
  a.bottomRightCorner(n, n) = -m.ldlt().solve(c);
  return a;
}

// The largest distance between each reference value and the multiplier paired with it: each
// reference takes the nearest multiplier not yet taken (both lists of one size).
double WorstPairing(const std::vector<Complex>& reference, std::vector<Complex> multipliers) {
  REQUIRE(reference.size() == multipliers.size());
  double worst = 0;
  for (const Complex& r : reference) {
    auto nearest = std::min_element(
        multipliers.begin(), multipliers.end(),
        [&](const Complex& a, const Complex& b) { return std::abs(a - r) < std::abs(b - r); });
    worst = std::max(worst, std::abs(*nearest - r));
    multipliers.erase(nearest);
  }
  return worst;
}

struct Linearised {
  std::shared_ptr<const dynamics::StageDynamics> rig;
  dynamics::ModesRecord modes;
  Eigen::MatrixXd m, k, c;
  double period = 0;  // the mesh period [s]
};

// The paper stage (its scene as given: sun fixed, 8 states) through the modes driver, and the
// same linearisation with its damping matrix.
Linearised PaperStage() {
  Linearised out;
  dynamics::ModesRequest request;
  request.scene = transmission::ParseScene(test::SceneText("paper_stage.toml"), "paper_stage");
  out.rig = std::make_shared<const dynamics::StageDynamics>(request.scene, test::SuiteTables());
  request.rig = out.rig;
  dynamics::ModesSink sink;
  out.modes = dynamics::RunModes(request, sink);
  // The modes driver's model: the tangent mesh stiffness (and the mesh damping it sets).
  dynamics::DynamicModel model = out.rig->model;
  model.SetMeshStiffness(out.modes.mesh_stiffness[0], out.modes.mesh_stiffness[1]);
  model.Linearise(0.0, &out.m, &out.k, &out.c);
  const dynamics::StagePeriodicSystem stage(model, solvers::Backend::kActiveSetNewton, {});
  out.period = stage.Period(stage.DefaultParameters());
  return out;
}

// Shooting on the linear stage with the tolerances of the stage's shooting tests (rtol 1e-8,
// 1e-11 rad, 1e-12 m, the rates' × 1e4), from rest.
dynamics::ShootingOptions Tolerances(const dynamics::DynamicModel& model) {
  const int n = model.size();
  dynamics::ShootingOptions so;
  so.rtol = 1e-8;
  so.atol.resize(2 * n);
  for (int j = 0; j < n; ++j) {
    so.atol(j) = model.dofs()[static_cast<std::size_t>(j)].axis ==
                         dynamics::MotionDof::kRotation
                     ? 1e-11
                     : 1e-12;
    so.atol(n + j) = so.atol(j) * 1e4;
  }
  return so;
}

// The bound on |μ − exp(λT)| from the integration's tolerances. In the coordinates scaled by
// the absolute tolerances, ỹ = D⁻¹y (D = diag(atol)), column j of the monodromy is held per step
// to rtol (|M̃_ij| + 1) (docs/periodic.md §2: column j's tolerance atol_i rtol/atol_j); a local
// error made at s reaches s = 1 through the flow exp(Ã(1 − s)T), of 2-norm ≤ κ(V) (V the
// eigenvectors of Ã, every Re λ ≤ 0), so over N steps each entry is within
// κ(V) N rtol (max|M̃| + 1) and ‖δM̃‖₂ ≤ 2n times that (2n × 2n entries); Bauer–Fike moves each
// eigenvalue of the diagonalisable M̃ = V e^{ΛT} V⁻¹ by at most κ(V) ‖δM̃‖₂.
double MultiplierTolerance(const Eigen::MatrixXd& a, const Eigen::VectorXd& atol, double rtol,
                           double steps, const Eigen::MatrixXd& monodromy) {
  const Eigen::MatrixXd scaled = atol.cwiseInverse().asDiagonal() * a * atol.asDiagonal();
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(scaled);
  const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(eig.eigenvectors());
  const double kappa = svd.singularValues()(0) /
                       svd.singularValues()(svd.singularValues().size() - 1);
  const Eigen::MatrixXd m_scaled =
      atol.cwiseInverse().asDiagonal() * monodromy * atol.asDiagonal();
  const double entry = kappa * steps * rtol * (m_scaled.cwiseAbs().maxCoeff() + 1);
  test::FigureValue("linear stage: condition number of the eigenvectors (scaled)", kappa, "-");
  return kappa * static_cast<double>(a.rows()) * entry;
}

}  // namespace

TEST_CASE(
    "paper stage, linearised with constant mesh stiffness: the Floquet multipliers are "
    "exp(lambda T) of the modes driver's frequencies (undamped) and of the damped eigenvalues",
    "[crosscheck][dynamics][periodic]") {
  const Linearised lin = PaperStage();
  const dynamics::DynamicModel& model = lin.rig->model;
  const Eigen::Index n = lin.m.rows();
  REQUIRE(n == model.size());
  const double T = lin.period;
  test::FigureValue("linear stage: mesh period", T, "s");
  const dynamics::ShootingOptions so = Tolerances(model);
  // The forcing: the static deflection under a cosine of the mesh period (a load of K·1 µrad per
  // DOF), so that the orbit is not the rest state.
  const Eigen::VectorXd load = lin.k * Eigen::VectorXd::Constant(n, 1e-6);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * n);
  b.tail(n) = lin.m.ldlt().solve(load);

  SECTION("undamped: mu = exp(+-i 2 pi f_k T), f_k the modes driver's natural frequencies") {
    const Eigen::MatrixXd a = StateMatrix(lin.m, lin.k, Eigen::MatrixXd::Zero(n, n));
    const LinearStage system(a, b, T);
    const dynamics::ShootingResult r =
        dynamics::SolvePeriodicOrbit(system, so, Eigen::VectorXd::Zero(2 * n));
    INFO(r.message);
    REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
    std::vector<Complex> reference;
    double grouping = 0;  // the modes' grouping: a group's mean within 1e-6 f of each member
    for (const dynamics::Mode& mode : lin.modes.modes) {
      REQUIRE_FALSE(mode.rigid);  // a held sun and a driven carrier: no rigid-body mode
      const double phase = 2 * std::numbers::pi * mode.frequency * T;
      for (int k = 0; k < mode.multiplicity; ++k) {
        reference.push_back(std::polar(1.0, phase));
        reference.push_back(std::polar(1.0, -phase));
      }
      if (mode.multiplicity > 1) grouping = std::max(grouping, 1e-6 * phase);
    }
    const double steps = static_cast<double>(r.steps) / static_cast<double>(r.integrations);
    const double worst = WorstPairing(reference, r.floquet.multipliers);
    const double tol = MultiplierTolerance(a, so.atol, so.rtol, steps, r.monodromy) + grouping;
    test::FigureValue("linear stage undamped: steps per period", steps, "-");
    test::FigureValue("linear stage undamped: highest f_k T", lin.modes.modes.back().frequency * T,
                      "-");
    test::FigureValue("linear stage undamped: worst |mu - exp(i 2 pi f T)|", worst, "-");
    test::FigureValue("linear stage undamped: tolerance", tol, "-");
    CHECK(worst <= tol);
    // Without damping every multiplier is on the unit circle, to the same bound.
    for (const Complex& mu : r.floquet.multipliers) CHECK(std::abs(std::abs(mu) - 1) <= tol);
  }

  SECTION("damped: mu = exp(lambda_k T), lambda_k the eigenvalues of A with the model's damping") {
    REQUIRE(lin.c.norm() > 0);
    const Eigen::MatrixXd a = StateMatrix(lin.m, lin.k, lin.c);
    const LinearStage system(a, b, T);
    const dynamics::ShootingResult r =
        dynamics::SolvePeriodicOrbit(system, so, Eigen::VectorXd::Zero(2 * n));
    INFO(r.message);
    REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(a);
    std::vector<Complex> reference;
    double slowest = 0;  // the least decay rate −Re λ [1/s]
    for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k) {
      reference.push_back(std::exp(eig.eigenvalues()(k) * T));
      slowest = k == 0 ? -eig.eigenvalues()(k).real()
                       : std::min(slowest, -eig.eigenvalues()(k).real());
    }
    REQUIRE(slowest > 0);  // damped: every multiplier inside the circle
    const double steps = static_cast<double>(r.steps) / static_cast<double>(r.integrations);
    const double worst = WorstPairing(reference, r.floquet.multipliers);
    const double tol = MultiplierTolerance(a, so.atol, so.rtol, steps, r.monodromy);
    test::FigureValue("linear stage damped: slowest decay rate", slowest, "1/s");
    test::FigureValue("linear stage damped: spectral radius", r.floquet.spectral_radius, "-");
    test::FigureValue("linear stage damped: worst |mu - exp(lambda T)|", worst, "-");
    test::FigureValue("linear stage damped: tolerance", tol, "-");
    CHECK(worst <= tol);
    CHECK(r.floquet.stability == dynamics::Stability::kStable);
    // The spectral radius is exp(−σ_min T), σ_min the slowest decay.
    CHECK(std::abs(r.floquet.spectral_radius - std::exp(-slowest * T)) <= tol);
  }
}
