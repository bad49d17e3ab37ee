// The active-set Newton's direct path for problems without equalities (positions given: the
// dynamic model's problem at every right-hand side). Every problem of the collection in
// verification/data/contact with its equalities dropped is solved by the direct path and checked
//  - against the definition of a solution, recomputed here from ContactProblem::Gap in SI units
//    (the physical local-term closed forms, not the solver's scaled ones): F ≥ 0 and
//    ‖min(F/F*, g/ℓ*)‖∞ ≤ tolerance, plus the round-off of that recomputation;
//  - against the globalised Newton's phase 1 alone (line search, face solver with refinement: the
//    general code, not the direct path) at 1e-12, within the suite's agreement criterion for back
//    ends (1e-6 relative in forces);
//  - warm from a nearby problem: the same answer as cold, in fewer iterations;
//  - warm from one time step away (every overlap moved by 3e-5 of the length scale) with local
//    terms: one step, as the third-order (Chebyshev) step on the kept factorisation promises
//    (its error |u''| dx³/x ~ 1e-13 for steps dx ~ 1e-4 of contacts with x ≳ 1e-2, below the
//    target 1e-11), where Newton's step leaves ½|u''| dx² ~ 1e-10 and needs a second: with the
//    quadratic term left out, 20 of the 22 problems tested took two steps. (At a move of 1e-4,
//    two problems whose steps reach 4 % of a contact's force need a second step either way.)
// A direct path that gives up hands over to the general path, and the message says so; one whose
// answer misses the tolerance by the driver's own residual (whatever its own stopping test said)
// is rejected and the general path runs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "direct_newton.hpp"  // the driver with a direct path of the test's own
#include "epicycle/solvers/contact_solver.hpp"
#include "figures.hpp"
#include "solvers_support.hpp"

namespace epicycle::solvers {
namespace {

ContactProblemData WithoutEqualities(ContactProblemData d) {
  const Eigen::Index n = d.overlap.size();
  d.equality_matrix.resize(0, n);
  d.equality_rhs.resize(0);
  d.support_stiffness.resize(0, 0);
  d.multiplier_labels.clear();
  return d;
}

// ‖min(F/F*, g/ℓ*)‖∞ and the most negative F/F*, from the problem's own gap in SI units.
double NaturalResidual(const ContactProblem& p, const ContactSolution& s) {
  const ContactScales sc = ComputeContactScales(p);
  const Eigen::VectorXd g = p.Gap(s.force.cwiseMax(0.0), Eigen::VectorXd());
  double r = 0.0;
  for (int j = 0; j < p.num_contacts(); ++j) {
    r = std::max(r, std::abs(std::min(s.force(j) / sc.force, g(j) / sc.length)));
    r = std::max(r, std::max(0.0, -s.force(j) / sc.force));
  }
  return r;
}

}  // namespace

TEST_CASE("direct path: the collection without equalities, against the definition and phase 2",
          "[crosscheck][solvers]") {
  const auto files = test::CollectionFiles();
  REQUIRE(files.size() >= 30);
  // The residual recomputed in SI and rescaled differs from the solver's scaled one by round-off:
  // the gap's terms are O(1) in units of ℓ* (δ0 and C F of the overlapping contacts), so a few
  // hundred ulps of 1 cover it.
  constexpr double kRoundOff = 1e-13;
  int direct = 0, loaded = 0;
  double worst_residual = 0.0, worst_difference = 0.0, worst_warm = 0.0;
  for (const std::string& path : files) {
    const ContactProblemFile file = ReadContactProblemFile(path);
    const ContactProblem problem(WithoutEqualities(file.data));
    INFO(problem.name());
    auto solver = MakeContactSolver(Backend::kActiveSetNewton);
    ContactOptions options;  // tolerance 1e-10
    ContactSolution sol;
    const ContactReport r = solver->Solve(problem, options, &sol);
    INFO(r.message);
    REQUIRE(r.status == ContactStatus::kConverged);
    if (r.message.find("direct path:") != std::string::npos) ++direct;
    if (sol.force.maxCoeff() > 0) ++loaded;
    const double res = NaturalResidual(problem, sol);
    CHECK(res <= options.tolerance + kRoundOff);
    worst_residual = std::max(worst_residual, res);

    ContactOptions tight;
    tight.tolerance = 1e-12;
    tight.backend_options = {{"newton.phase1_only", "1"}};
    ContactSolution ref;
    const ContactReport rr =
        MakeContactSolver(Backend::kActiveSetNewton)->Solve(problem, tight, &ref);
    INFO("phase 1: " << rr.message);
    // As in the collection test: 1e-12 is below the round-off floor of the stiffest problems,
    // whose reference then stops at its stagnation point; it must still be within 1e-9.
    REQUIRE(rr.residual.total <= 1e-9);
    const double d = CompareSolutions(problem, sol, ref).force;
    CHECK(d <= 1e-6);
    worst_difference = std::max(worst_difference, d);

    // A nearby problem (every second overlap moved by 0.2 µm), warm from this answer.
    ContactProblemData moved = WithoutEqualities(file.data);
    for (Eigen::Index j = 0; j < moved.overlap.size(); j += 2) moved.overlap(j) += 0.2e-6;
    const ContactProblem nearby(moved);
    ContactSolution w = sol, c;
    ContactOptions warm = options;
    warm.warm_start = true;
    const ContactReport rw = solver->Solve(nearby, warm, &w);
    const ContactReport rc = solver->Solve(nearby, options, &c);
    INFO("warm: " << rw.message << " / cold: " << rc.message);
    CHECK(rw.status == ContactStatus::kConverged);
    CHECK(rc.status == ContactStatus::kConverged);
    CHECK(rw.iterations <= rc.iterations);
    const double dw = CompareSolutions(nearby, w, c).force;
    CHECK(dw <= 1e-6);
    worst_warm = std::max(worst_warm, dw);
  }
  // The collection must exercise the path: most problems go through it, and most are loaded.
  CHECK(direct >= static_cast<int>(files.size()) * 3 / 4);
  CHECK(loaded >= static_cast<int>(files.size()) / 2);
  const std::string what = "contact direct path (no equalities), " + std::to_string(files.size()) +
                           " collection problems, " + std::to_string(direct) + " solved by it";
  epicycle::test::VerifyRow(
      what, "KKT recomputed from the problem in SI; globalised Newton at 1e-12",
      "residual " + epicycle::test::Sci(worst_residual) + ", forces " +
          epicycle::test::Sci(worst_difference) + ", warm vs cold " +
          epicycle::test::Sci(worst_warm),
      epicycle::test::Sci(std::max(worst_difference, worst_warm)), "1e-6",
      worst_residual <= 1e-10 + kRoundOff && worst_difference <= 1e-6 && worst_warm <= 1e-6);
}

TEST_CASE("direct path: one time step away, a warm start with local terms takes one step",
          "[crosscheck][solvers]") {
  int tested = 0;
  double worst = 0.0;
  for (const std::string& path : test::CollectionFiles()) {
    const ContactProblemFile file = ReadContactProblemFile(path);
    const ContactProblemData data = WithoutEqualities(file.data);
    const ContactProblem problem(data);
    if (!problem.has_local()) continue;
    INFO(problem.name());
    auto solver = MakeContactSolver(Backend::kActiveSetNewton);
    ContactOptions options;  // tolerance 1e-10: the direct path's target is 1e-11
    ContactSolution sol;
    REQUIRE(solver->Solve(problem, options, &sol).status == ContactStatus::kConverged);
    // Strict complementarity with a margin (every contact has x_j or g_j/ℓ* above 1e-2): a move
    // of 1e-4 cannot change the active set, which the step on the kept factorisation needs.
    const ContactScales sc = ComputeContactScales(problem);
    const Eigen::VectorXd g = problem.Gap(sol.force, Eigen::VectorXd());
    bool margin = sol.force.maxCoeff() > 0.0;
    for (int j = 0; j < problem.num_contacts(); ++j)
      margin = margin && std::max(sol.force(j) / sc.force, g(j) / sc.length) > 1e-2;
    if (!margin) continue;
    ContactProblemData moved = data;
    moved.overlap.array() += 3e-5 * sc.length;
    const ContactProblem next(moved);
    ContactSolution w = sol, c;
    ContactOptions warm = options;
    warm.warm_start = true;
    const ContactReport rw = solver->Solve(next, warm, &w);
    const ContactReport rc = MakeContactSolver(Backend::kActiveSetNewton)->Solve(next, options, &c);
    INFO("warm: " << rw.message << " / cold: " << rc.message);
    CHECK(rw.status == ContactStatus::kConverged);
    CHECK(rw.message.find("direct path") != std::string::npos);
    CHECK(rw.iterations == 1);
    const double d = CompareSolutions(next, w, c).force;
    CHECK(d <= 1e-6);
    worst = std::max(worst, d);
    ++tested;
  }
  // The collection's gear problems carry local terms; enough of them are strictly complementary.
  CHECK(tested >= 5);
  epicycle::test::VerifyRow("contact direct path, warm one time step away with local terms (" +
                                std::to_string(tested) + " collection problems)",
                            "cold solve of the moved problem; one step (third order)",
                            "1 iteration each, forces " + epicycle::test::Sci(worst),
                            epicycle::test::Sci(worst), "1e-6", tested >= 5 && worst <= 1e-6);
}

TEST_CASE("direct path: when it gives up the general path runs and the message says so",
          "[crosscheck][solvers]") {
  const ContactProblemFile file = ReadContactProblemFile(test::CaseFile("gear_p5_n60_m8_s1"));
  const ContactProblem problem(WithoutEqualities(file.data));
  auto solver = MakeContactSolver(Backend::kActiveSetNewton);
  ContactOptions options;
  ContactSolution sol;
  const ContactReport full = solver->Solve(problem, options, &sol);
  REQUIRE(full.status == ContactStatus::kConverged);
  REQUIRE(full.iterations >= 2);  // a cold start needs more than one step
  options.max_iterations = 1;
  ContactSolution one;
  const ContactReport r = solver->Solve(problem, options, &one);
  INFO(r.message);
  CHECK(r.message.find("direct path gave up") != std::string::npos);
  // The globalised Newton (its phase 2 has no use for the phase-1 budget) finishes the job.
  CHECK(r.status == ContactStatus::kConverged);
  CHECK(r.residual.total <= options.tolerance);
  CHECK(CompareSolutions(problem, one, sol).force <= 1e-6);
}

namespace {

// A direct path whose idea of convergence is wrong: it solves each contact alone,
// C_jj x_j = δ0_j, and proposes that answer at every step. By its own gap (g_j = C_jj x_j − δ0_j
// = 0) the answer is exact; by the problem's (g = C x − δ0, the coupling included) it is not
// unless C is diagonal. The driver computes the gap itself, so only the driver's residual can
// accept it.
class UncoupledPath final : public internal::DirectPath {
 public:
  void Begin(bool) override {}
  bool Step(const internal::ScaledProblem& p, const Eigen::VectorXd&, const Eigen::VectorXd&, int,
            double, Eigen::VectorXd* x) override {
    *x = p.delta0.cwiseQuotient(p.C.diagonal()).cwiseMax(0.0);
    ++steps;
    return true;
  }
  int steps = 0;
};

}  // namespace

TEST_CASE("direct path: the driver judges its answer by the driver's own residual",
          "[unit][solvers]") {
  // Two contacts, both closed, no local terms: F = C⁻¹ δ0 in closed form (2×2 inverse).
  const double c11 = 2e-9, c22 = 1e-9, c12 = 0.5e-9, d1 = 1e-6, d2 = 1.5e-6;
  const double det = c11 * c22 - c12 * c12;
  const Eigen::Vector2d exact((c22 * d1 - c12 * d2) / det, (c11 * d2 - c12 * d1) / det);
  REQUIRE(exact.minCoeff() > 0);
  auto problem = [&](double coupling) {
    ContactProblemData d;
    d.name = "two coupled contacts";
    d.compliance.resize(2, 2);
    d.compliance << c11, coupling, coupling, c22;
    d.overlap = Eigen::Vector2d(d1, d2);
    d.equality_matrix.resize(0, 2);
    return ContactProblem(d);
  };
  ContactOptions options;
  options.tolerance = 1e-10;
  auto path = std::make_unique<UncoupledPath>();
  UncoupledPath* seen = path.get();
  auto solver = internal::MakeDriverSolver(Backend::kActiveSetNewton, std::move(path));

  SECTION("coupled: the path's converged-looking answer is rejected, the general path solves") {
    const ContactProblem p = problem(c12);
    ContactSolution s;
    const ContactReport r = solver->Solve(p, options, &s);
    // The first proposal improves on the start x = 0; proposed again and again it never improves
    // the driver's residual: three more iterates without a new best, and the driver gives up.
    CHECK(seen->steps == 4);
    INFO(r.message);
    CHECK(r.message.find("missed the tolerance by the driver's residual") != std::string::npos);
    CHECK(r.message.find("direct path: no equalities") == std::string::npos);
    REQUIRE(r.status == ContactStatus::kConverged);
    // The answer is the closed form to the tolerance's relative size (residual 1e-10 of the
    // force scale, which is of the order of the largest force).
    CHECK((s.force - exact).cwiseAbs().maxCoeff() <= 1e-9 * exact.maxCoeff());
    // The uncoupled answer the path proposed is far from it (so the check above could fail).
    const Eigen::Vector2d uncoupled(d1 / c11, d2 / c22);
    CHECK((uncoupled - exact).cwiseAbs().maxCoeff() > 0.1 * exact.maxCoeff());
  }
  SECTION("uncoupled: the same path is right, and its answer is accepted as it is") {
    const ContactProblem p = problem(0.0);
    ContactSolution s;
    const ContactReport r = solver->Solve(p, options, &s);
    CHECK(seen->steps == 1);
    INFO(r.message);
    CHECK(r.status == ContactStatus::kConverged);
    CHECK(r.message.find("direct path: no equalities, 1 iterations") != std::string::npos);
    CHECK(std::abs(s.force(0) - d1 / c11) <= 1e-12 * d1 / c11);
    CHECK(std::abs(s.force(1) - d2 / c22) <= 1e-12 * d2 / c22);
  }
}

}  // namespace epicycle::solvers
