// Slices of the face width (docs/model.md §10, face_width.hpp): the coupling matrix against a
// finite-difference solve of the Pasternak layer's equation, and the load across the face of a
// mesh of uniform stiffness per unit width against ISO 6336-1 method C's closed forms for a
// linear misalignment and their counterparts for a parabolic crowning (derived below), solved by
// the project's contact solver on slices built as the stage model builds them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/face_width.hpp"

using namespace epicycle;
using transmission::FaceCoupling;
using transmission::FaceCouplingMatrix;

namespace {

// W of the Pasternak layer w − λ² w'' = p on [0, b], w' = 0 at both ends, by second-order finite
// differences on `cells` cells per slice (an independent discretisation of the same equation):
// W_st = b · (mean over slice s of w_t), w_t the response to a unit load spread over slice t
// (p = 1/Δz there).
Eigen::MatrixXd PasternakByDifferences(int slices, double b, double lambda, int cells) {
  const int n = slices * cells;
  const double h = b / n;
  // Cell-centred unknowns; the Neumann ends by mirrored ghost cells.
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  const double k = lambda * lambda / (h * h);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 1 + 2 * k;
    if (i > 0) a(i, i - 1) = -k;
    if (i + 1 < n) a(i, i + 1) = -k;
  }
  a(0, 0) -= k;
  a(n - 1, n - 1) -= k;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
  Eigen::MatrixXd w(slices, slices);
  const double dz = b / slices;
  for (int t = 0; t < slices; ++t) {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
    p.segment(t * cells, cells).setConstant(1.0 / dz);
    const Eigen::VectorXd u = lu.solve(p);
    for (int s = 0; s < slices; ++s) w(s, t) = b * u.segment(s * cells, cells).mean();
  }
  return w;
}

// One mesh of uniform stiffness c per unit width [N/m²] over the face width b, S slices, the gap
// g(z) ≥ 0 [m] across the face, total force F [N]: the contact problem of the slices (the stage
// model's: C = C0 W with C0 = 1/(c b) the whole face's compliance), solved by the active-set
// Newton back end. Returns the line loads w_s = F_s/Δz [N/m].
template <typename Gap>
std::vector<double> LineLoads(int slices, double b, double c, double force, FaceCoupling coupling,
                              double lambda, Gap gap, double body_share = 0) {
  solvers::ContactProblemData d;
  d.compliance = FaceCouplingMatrix(slices, b, coupling, lambda, body_share) / (c * b);
  const std::vector<double> z = transmission::SliceCentres(slices, b);
  d.overlap.resize(slices);
  for (int s = 0; s < slices; ++s) d.overlap(s) = -gap(z[static_cast<std::size_t>(s)]);
  d.equality_matrix = Eigen::MatrixXd::Ones(1, slices);  // Σ F_s = F, λ the approach
  d.equality_rhs = Eigen::VectorXd::Constant(1, force);
  const solvers::ContactProblem problem(d);
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  solvers::ContactOptions options;
  solvers::ContactSolution solution;
  const solvers::ContactReport report = solver->Solve(problem, options, &solution);
  REQUIRE(report.status == solvers::ContactStatus::kConverged);
  std::vector<double> w(static_cast<std::size_t>(slices));
  for (int s = 0; s < slices; ++s) w[static_cast<std::size_t>(s)] = solution.force(s) * slices / b;
  return w;
}

double KHBeta(const std::vector<double>& w, double force, double b) {
  return *std::max_element(w.begin(), w.end()) / (force / b);
}

// The ISO 20/40 pair's order of magnitude: c = 14 N/(mm·µm) = 1.4e10 N/m², b = 20 mm.
constexpr double kC = 1.4e10, kB = 0.02;

}  // namespace

TEST_CASE("face coupling: uncoupled strips are S I, the Pasternak layer its finite-difference "
          "solve, symmetric, positive definite, rows summing to S",
          "[unit][transmission][face_width]") {
  CHECK(FaceCouplingMatrix(8, kB, FaceCoupling::kNone, 0).isApprox(
      8.0 * Eigen::MatrixXd::Identity(8, 8), 0));
  CHECK(FaceCouplingMatrix(1, kB, FaceCoupling::kPasternak, 1e-3)(0, 0) == 1.0);
  for (const double lambda : {0.5e-3, 4e-3, 40e-3}) {
    const int S = 10;
    const Eigen::MatrixXd w = FaceCouplingMatrix(S, kB, FaceCoupling::kPasternak, lambda);
    CHECK((w - w.transpose()).cwiseAbs().maxCoeff() == 0);
    // ∫_0^b G dx' = 1: every row sums to S, to rounding (the integrals are in closed form; their
    // terms are O(1) in units of λ for these λ: 1e-13 relative covers a few hundred ulps).
    for (int s = 0; s < S; ++s) CHECK(std::abs(w.row(s).sum() - S) <= 1e-13 * S);
    CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(w).eigenvalues().minCoeff() > 0);
    // The finite differences converge at O(h²): 400 cells per slice, h = b/4000; the error of
    // the slice means is about (h/λ)²/12 of the entries: below 1e-5 relative for λ ≥ 0.5 mm.
    const Eigen::MatrixXd fd = PasternakByDifferences(S, kB, lambda, 400);
    INFO("lambda " << lambda << " largest difference "
                   << (w - fd).cwiseAbs().maxCoeff() / w.cwiseAbs().maxCoeff());
    CHECK((w - fd).cwiseAbs().maxCoeff() <= 1e-5 * w.cwiseAbs().maxCoeff());
  }
  // The limits: λ → 0 uncoupled strips (a slice's load spreads into its neighbours over λ from
  // its ends: an interior diagonal entry is S (1 − λ/Δz), half the loss to each neighbour, to
  // O(e^(−Δz/λ))), λ → ∞ a rigid face (every entry 1, off by
  // O((b/λ)²) = 4e-4 at λ = 1 m).
  CHECK((FaceCouplingMatrix(10, kB, FaceCoupling::kPasternak, 1e-7) -
         10.0 * Eigen::MatrixXd::Identity(10, 10))
            .cwiseAbs()
            .maxCoeff() <= (1 + 1e-6) * 10 * 1e-7 / (kB / 10));
  CHECK((FaceCouplingMatrix(10, kB, FaceCoupling::kPasternak, 1.0).array() - 1).abs().maxCoeff() <
        (kB / 1.0) * (kB / 1.0));
  CHECK_THROWS_WITH(FaceCouplingMatrix(0, kB, FaceCoupling::kNone, 0),
                    Catch::Contains("slices = 0: must be at least 1"));
  CHECK_THROWS_WITH(FaceCouplingMatrix(4, kB, FaceCoupling::kPasternak, 0),
                    Catch::Contains("coupling_length = 0 m: must be > 0"));
}

TEST_CASE("face width: K_Hbeta of a linear misalignment is ISO 6336-1's 1 + c F_beta b/(2F), "
          "sqrt(2 c F_beta b/F) once the face lifts off",
          "[unit][transmission][face_width]") {
  const double F = 20000;  // [N]
  // Full contact: the load is linear in z, so a slice's mean is its centre's value and the
  // discrete K_Hβ is exactly 1 + x (1 − 1/S), x = c F_β b/(2F): to the solver's tolerance.
  for (const double f_beta : {5e-6, 20e-6}) {  // x = 0.035, 0.14
    const double x = kC * f_beta * kB / (2 * F);
    for (const int S : {4, 10, 40}) {
      const auto w = LineLoads(S, kB, kC, F, FaceCoupling::kNone, 0,
                               [&](double z) { return f_beta * (z / kB + 0.5); });
      CHECK(KHBeta(w, F, kB) == Approx(1 + x * (1 - 1.0 / S)).epsilon(1e-9));
    }
  }
  // Lifting off: K = sqrt(2 c F_β b/F) = 2.37 for F_β = 200 µm; the loaded length ℓ = 2b/K. The
  // largest slice's mean falls short of the edge value by Δz/(2ℓ) relative, and the contact's
  // end cut by a slice adds a second-order term: the error is within K Δz/ℓ = K²/(2S) of K and
  // falls with S.
  const double f_beta = 200e-6;
  const double k_exact = std::sqrt(2 * kC * f_beta * kB / F);
  double last = 1e300;
  for (const int S : {10, 40, 160}) {
    const auto w = LineLoads(S, kB, kC, F, FaceCoupling::kNone, 0,
                             [&](double z) { return f_beta * (z / kB + 0.5); });
    const double err = std::abs(KHBeta(w, F, kB) - k_exact);
    INFO("S " << S << " K " << KHBeta(w, F, kB) << " closed form " << k_exact);
    CHECK(err <= k_exact * k_exact / (2.0 * S));
    CHECK(err < last);
    last = err;
  }
}

TEST_CASE("face width: the tooth_body coupling (1 - phi) S I + phi 1 1^T keeps the plane model "
          "under a uniform load and meets a linear gap with the tooth's stiffness c/(1 - phi)",
          "[unit][transmission][face_width]") {
  CHECK_THROWS_WITH(FaceCouplingMatrix(4, kB, FaceCoupling::kToothBody, 0, 1.0),
                    Catch::Contains("body_share = 1") && Catch::Contains("[0, 1)"));
  CHECK_THROWS_WITH(FaceCouplingMatrix(4, kB, FaceCoupling::kToothBody, 0, -0.1),
                    Catch::Contains("body_share = -0.1"));
  CHECK_THROWS_WITH(FaceCouplingMatrix(4, kB, FaceCoupling::kToothBody, -1e-3, 0.3),
                    Catch::Contains("coupling_length = -0.001") && Catch::Contains(">= 0"));
  // With a tooth length λ the tooth part is the Pasternak layer's W, scaled by 1 − φ.
  CHECK(FaceCouplingMatrix(6, kB, FaceCoupling::kToothBody, 3e-3, 0.3)
            .isApprox(0.7 * FaceCouplingMatrix(6, kB, FaceCoupling::kPasternak, 3e-3) +
                          Eigen::MatrixXd::Constant(6, 6, 0.3),
                      1e-14));
  CHECK(FaceCouplingMatrix(6, kB, FaceCoupling::kToothBody, 0, 0)
            .isApprox(FaceCouplingMatrix(6, kB, FaceCoupling::kNone, 0), 0));
  const Eigen::MatrixXd w = FaceCouplingMatrix(10, kB, FaceCoupling::kToothBody, 0, 0.4);
  // Entries 0.4 and 6.4: sums of ten exact binary fractions' neighbours, 1e-14 relative.
  for (int s = 0; s < 10; ++s) CHECK(std::abs(w.row(s).sum() - 10) <= 1e-14 * 10);
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(w).eigenvalues().minCoeff() ==
        Approx(0.6 * 10).epsilon(1e-12));
  // Slice s deflects by (1/(c b)) [(1 − φ) S F_s + φ F] = δ − g(z_s): with q_s = F_s S/b,
  // q_s = c/(1 − φ) (δ − g(z_s) − φ F/(c b)), linear in z with slope c F_β/((1 − φ) b) while the
  // whole face carries, so the discrete K_Hβ is exactly 1 + x (1 − 1/S)/(1 − φ), x = c F_β b/(2F);
  // once the face lifts off, the uncoupled closed form with c/(1 − φ), within K²/(2S) as above.
  const double F = 20000, phi = 0.4;
  for (const int S : {4, 10, 40}) {
    const double f_beta = 20e-6, x = kC * f_beta * kB / (2 * F);
    const auto full = LineLoads(S, kB, kC, F, FaceCoupling::kToothBody, 0,
                                [&](double z) { return f_beta * (z / kB + 0.5); }, phi);
    CHECK(KHBeta(full, F, kB) == Approx(1 + x * (1 - 1.0 / S) / (1 - phi)).epsilon(1e-9));
  }
  const double f_beta = 120e-6;
  const double k_exact = std::sqrt(2 * kC / (1 - phi) * f_beta * kB / F);
  for (const int S : {40, 160}) {
    const auto lifted = LineLoads(S, kB, kC, F, FaceCoupling::kToothBody, 0,
                                  [&](double z) { return f_beta * (z / kB + 0.5); }, phi);
    INFO("S " << S << " K " << KHBeta(lifted, F, kB) << " closed form " << k_exact);
    CHECK(std::abs(KHBeta(lifted, F, kB) - k_exact) <= k_exact * k_exact / (2.0 * S));
  }
}

TEST_CASE("face width: K_Hbeta of a parabolic crowning, 1 + c C_beta b/(3F) in full contact and "
          "(3/2)^(2/3) (c C_beta b/F)^(1/3) once the ends lift off",
          "[unit][transmission][face_width]") {
  // Derivation (uniform c, gap C (2z/b)², approach a): full contact, F = c b (a − C/3) and the
  // peak c a, so K = 1 + x/3 with x = c C b/F, while a ≥ C (x ≤ 3/2). Beyond, contact over
  // |z| ≤ z0 = (b/2) sqrt(a/C): F = (4/3) c a z0, so a = (3 F sqrt(C)/(2 c b))^(2/3) and
  // K = c a b/F = (3/2)^(2/3) x^(1/3) (= 3/2 at x = 3/2: the two meet).
  const double F = 20000;
  // Full contact, even S: the midpoint sum of z² is (b³/12)(1 − 1/S²) and the peak slices sit at
  // z = ±Δz/2, so the discrete K is exactly 1 + (x/3)(1 − 4/S²).
  for (const double crown : {2e-6, 5e-6}) {  // x = 0.028, 0.07
    const double x = kC * crown * kB / F;
    for (const int S : {4, 10, 40}) {
      const auto w = LineLoads(S, kB, kC, F, FaceCoupling::kNone, 0, [&](double z) {
        return crown * (2 * z / kB) * (2 * z / kB);
      });
      CHECK(KHBeta(w, F, kB) == Approx(1 + x / 3 * (1 - 4.0 / (S * S))).epsilon(1e-9));
    }
  }
  // Ends lifted: C = 100 µm, x = 1.4, just below 3/2... take C = 400 µm, x = 5.6.
  const double crown = 400e-6, x = kC * crown * kB / F;
  const double k_exact = std::pow(1.5, 2.0 / 3.0) * std::cbrt(x);
  double last = 1e300;
  for (const int S : {10, 40, 160}) {
    const auto w = LineLoads(S, kB, kC, F, FaceCoupling::kNone, 0, [&](double z) {
      return crown * (2 * z / kB) * (2 * z / kB);
    });
    const double err = std::abs(KHBeta(w, F, kB) - k_exact);
    // The peak slice sits Δz/2 off the centre (second order) and the contact's ends are cut by
    // slices (a kink of the load: first order in Δz/ℓ, ℓ = 2 z0 = 3b/(2K) the loaded length,
    // times the share of the load near the ends): within K Δz/ℓ of K.
    const double loaded = 1.5 * kB / k_exact;
    INFO("S " << S << " K " << KHBeta(w, F, kB) << " closed form " << k_exact);
    CHECK(err <= k_exact * (kB / S) / loaded);
    CHECK(err < last);
    last = err;
  }
}

TEST_CASE("face width: a uniform gap loads the face uniformly under any coupling (no edge effect "
          "from the kernel), and coupling spreads a misalignment's peak",
          "[unit][transmission][face_width]") {
  const double F = 20000;
  for (const double lambda : {1e-3, 5e-3}) {
    const auto w = LineLoads(20, kB, kC, F, FaceCoupling::kPasternak, lambda,
                             [](double) { return 0.0; });
    for (double v : w) CHECK(v == Approx(F / kB).epsilon(1e-9));
  }
  // With a misalignment, the layer's coupling changes the peak with λ; as λ → 0 it is the
  // uncoupled strips' (W → S I: a slice shares O(λ/Δz) of its deflection with each neighbour,
  // so K_Hβ − 1 changes by that share: within 2 (λ/Δz)(K − 1) at λ = Δz/200).
  const auto gap = [](double z) { return 10e-6 * (z / kB + 0.5); };
  const double uncoupled = KHBeta(LineLoads(20, kB, kC, F, FaceCoupling::kNone, 0, gap), F, kB);
  const double thin =
      KHBeta(LineLoads(20, kB, kC, F, FaceCoupling::kPasternak, kB / 20 / 200, gap), F, kB);
  CHECK(std::abs(thin - uncoupled) <= 2.0 / 200 * (uncoupled - 1));
}
