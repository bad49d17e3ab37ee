// Bad input → std::invalid_argument naming the field, the value and the rule (must-show 5);
// options validation; names of back ends and statuses.
#include <catch2/catch.hpp>

#include <limits>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/solvers/local_term.hpp"

namespace epicycle::solvers {
namespace {

ContactProblemData Good() {
  ContactProblemData d;
  d.name = "good";
  d.compliance.resize(2, 2);
  d.compliance << 4e-9, 1e-9, 1e-9, 3e-9;
  d.overlap = Eigen::Vector2d(1e-6, -2e-6);
  d.equality_matrix = Eigen::MatrixXd::Ones(1, 2);
  d.equality_rhs = Eigen::VectorXd::Constant(1, 1000.0);
  LocalTermParameters p;
  p.face_width = 0.025;
  p.reduced_radius = 0.01;
  p.body[0] = p.body[1] = {207e9, 0.3, 2e-3};
  d.local = {p, p};
  return d;
}

}  // namespace

TEST_CASE("a valid problem is accepted and stored symmetric", "[unit][solvers]") {
  const ContactProblem p(Good());
  CHECK(p.num_contacts() == 2);
  CHECK(p.num_equalities() == 1);
  CHECK(p.has_local());
  CHECK_FALSE(p.has_support());
}

TEST_CASE("bad contact problems are rejected with named fields", "[unit][solvers]") {
  {
    auto d = Good();
    d.compliance(0, 1) = 2e-9;  // non-symmetric
    CHECK_THROWS_WITH(ContactProblem(d), Catch::Contains("compliance is not symmetric") &&
                                             Catch::Contains("compliance(0,1) = 2e-09") &&
                                             Catch::Contains("|A_ij - A_ji| <="));
  }
  {
    auto d = Good();
    d.compliance << 1e-9, 2e-9, 2e-9, 1e-9;  // indefinite (eigenvalues 3e-9, −1e-9)
    CHECK_THROWS_WITH(ContactProblem(d), Catch::Contains("compliance is not positive definite") &&
                                             Catch::Contains("-1e-09") && Catch::Contains("SPD"));
  }
  {
    auto d = Good();
    d.overlap = Eigen::Vector3d(0, 0, 0);  // size mismatch
    CHECK_THROWS_WITH(ContactProblem(d), Catch::Contains("compliance is 2x2: must be 3x3"));
  }
  {
    auto d = Good();
    d.equality_matrix = Eigen::MatrixXd::Ones(1, 3);
    CHECK_THROWS_WITH(ContactProblem(d), Catch::Contains("equality_matrix is 1x3: must be 1x2"));
  }
  {
    auto d = Good();
    d.overlap(1) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(ContactProblem(d),
                      Catch::Contains("overlap[1] = nan") && Catch::Contains("must be finite"));
  }
  {
    auto d = Good();
    d.compliance(1, 1) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(ContactProblem(d), Catch::Contains("compliance(1,1) = inf"));
  }
  {
    auto d = Good();
    d.local[1].face_width = -0.025;
    CHECK_THROWS_WITH(ContactProblem(d), Catch::Contains("local[1].face_width = -0.025") &&
                                             Catch::Contains("must be finite and > 0"));
  }
  {
    auto d = Good();
    d.local.pop_back();
    CHECK_THROWS_WITH(ContactProblem(d),
                      Catch::Contains("local has 1 entries: must be empty or N = 2"));
  }
  {
    auto d = Good();
    d.support_stiffness = Eigen::MatrixXd::Constant(1, 1, -1e-9);
    CHECK_THROWS_WITH(ContactProblem(d),
                      Catch::Contains("support_stiffness is not positive semidefinite"));
  }
}

TEST_CASE("positive definiteness is judged alike for small and large problems", "[unit][solvers]") {
  // C = Q diag(λ) Qᵀ with Q orthogonal and the smallest eigenvalue λ_min: accepted for λ_min > 0
  // (ill-conditioned, 1e-6), rejected for λ_min < 0, with N = 12 (the factor on the stack) and
  // N = 40 (Eigen's LLT).
  for (const int n : {12, 40}) {
    const Eigen::MatrixXd q =
        Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Random(n, n)).householderQ();
    for (const double lambda_min : {1e-6, -1e-3}) {
      Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
      lambda(n / 2) = lambda_min;
      Eigen::MatrixXd c = 1e-9 * q * lambda.asDiagonal() * q.transpose();
      c = (0.5 * (c + c.transpose())).eval();
      ContactProblemData d;
      d.compliance = c;
      d.overlap = Eigen::VectorXd::Zero(n);
      INFO("N = " << n << ", smallest eigenvalue " << lambda_min << "e-9");
      if (lambda_min > 0) {
        CHECK_NOTHROW(ContactProblem(d));
      } else {
        CHECK_THROWS_WITH(ContactProblem(d),
                          Catch::Contains("compliance is not positive definite"));
      }
    }
  }
}

TEST_CASE("Release gives the validated data back without a copy", "[unit][solvers]") {
  ContactProblemData d = Good();
  const double* c = d.compliance.data();
  const double* o = d.overlap.data();
  ContactProblem p(std::move(d));
  const ContactProblemData back = std::move(p).Release();
  CHECK(back.compliance.data() == c);
  CHECK(back.overlap.data() == o);
  CHECK(back.compliance == Good().compliance);  // symmetric already: unchanged
  CHECK(back.local.size() == 2);
  CHECK(back.name == "good");
}

TEST_CASE("options and names are validated", "[unit][solvers]") {
  ContactOptions o;
  o.tolerance = -1;
  CHECK_THROWS_WITH(o.Validate(),
                    Catch::Contains("ContactOptions.tolerance = -1") && Catch::Contains("> 0"));
  o = ContactOptions();
  o.backend_options.emplace("newton.no_such_knob", std::string(1, '1'));
  CHECK_THROWS_WITH(o.Validate(), Catch::Contains("backend_options[newton.no_such_knob]") &&
                                      Catch::Contains("unknown key"));
  o = ContactOptions();
  o.backend_options.emplace("newton.ls_beta", std::string("0.3"));
  CHECK_NOTHROW(o.Validate());
  for (Backend b : AllBackends()) CHECK(BackendFromName(BackendName(b)) == b);
  CHECK_THROWS_WITH(BackendFromName("simplex"),
                    Catch::Contains("backend = 'simplex'") && Catch::Contains("newton"));
  CHECK(StatusName(ContactStatus::kConverged) == "converged");
  CHECK(!AvailableBackends().empty());
  CHECK(AvailableBackends().front() == Backend::kActiveSetNewton);
}

TEST_CASE("the driver judges by its own residual and scales back", "[unit][solvers]") {
  const ContactProblem p(Good());
  auto solver = MakeContactSolver(Backend::kActiveSetNewton);
  ContactOptions o;
  ContactSolution s;
  const ContactReport r = solver->Solve(p, o, &s);
  REQUIRE(r.status == ContactStatus::kConverged);
  // Recompute the residual here, in SI, and compare with the report's nondimensional one.
  const ContactScales sc = ComputeContactScales(p);
  const Eigen::VectorXd g = p.Gap(s.force, s.multiplier) / sc.length;
  const Eigen::VectorXd x = s.force / sc.force;
  const double comp = x.cwiseMin(g).cwiseAbs().maxCoeff();
  const double equi = std::abs((p.equality_matrix() * s.force - p.equality_rhs())(0)) / sc.force;
  CHECK(comp <= o.tolerance);
  CHECK(equi <= o.tolerance);
  CHECK(std::abs(s.force.sum() - 1000.0) <= 1e-9 * 1000.0);
  // A warm start of the wrong size is misuse.
  o.warm_start = true;
  ContactSolution bad;
  bad.force = Eigen::VectorXd::Zero(3);
  CHECK_THROWS_WITH(solver->Solve(p, o, &bad), Catch::Contains("must have N = 2"));
  CHECK_THROWS_WITH(solver->Solve(p, o, nullptr), Catch::Contains("in_out = null"));
}

// The warning for contacts loaded beyond the local term's validity, L > h, i.e. F > F_lim =
// π b E* h²/(4 R) (E* of plane strain), on the direct path (no equalities) and the general one.
TEST_CASE("contacts loaded past the local term's validity are counted in a warning",
          "[unit][solvers]") {
  ContactProblemData d = Good();
  const LocalTermParameters& p = d.local[0];
  const double k = (1 - 0.3 * 0.3) / 207e9;
  const double e_star = 1 / (2 * k);
  const double f_lim = 3.14159265358979323846 * p.face_width * e_star * 2e-3 * 2e-3 /
                       (4 * p.reduced_radius);  // ≈ 2.3e6 N for these numbers
  // Positions given: contact 0 at 1.5 F_lim, contact 1 at 0.5 F_lim (uncoupled compliance, so
  // δ0_j = C_jj F_j + u(F_j) puts each force where wanted).
  d.compliance(0, 1) = d.compliance(1, 0) = 0.0;
  const double f[2] = {1.5 * f_lim, 0.5 * f_lim};
  for (int j = 0; j < 2; ++j)
    d.overlap(j) = d.compliance(j, j) * f[j] + LocalApproach(d.local[j], f[j]);
  d.equality_matrix.resize(0, 2);
  d.equality_rhs.resize(0);
  auto solver = MakeContactSolver(Backend::kActiveSetNewton);
  ContactSolution s;
  ContactReport r = solver->Solve(ContactProblem(d), {}, &s);
  REQUIRE(r.status == ContactStatus::kConverged);
  CHECK(std::abs(s.force(0) - f[0]) <= 1e-6 * f[0]);
  CHECK_THAT(r.message, Catch::Contains("WARNING: 1 contact(s) beyond the local term's validity"));
  // Both below: no warning.
  d.overlap(0) = d.compliance(0, 0) * f[1] + LocalApproach(d.local[0], f[1]);
  r = solver->Solve(ContactProblem(d), {}, &s);
  REQUIRE(r.status == ContactStatus::kConverged);
  CHECK_THAT(r.message, !Catch::Contains("WARNING"));
  // The general path (one equality): a load of 3 F_lim shared by two equal contacts.
  ContactProblemData g = Good();
  g.compliance(0, 1) = g.compliance(1, 0) = 0.0;
  g.compliance(1, 1) = g.compliance(0, 0);
  g.overlap.setZero();
  g.equality_rhs(0) = 3 * f_lim;
  r = solver->Solve(ContactProblem(g), {}, &s);
  REQUIRE(r.status == ContactStatus::kConverged);
  CHECK_THAT(r.message, Catch::Contains("WARNING: 2 contact(s)"));
}

}  // namespace epicycle::solvers

namespace epicycle::solvers {

TEST_CASE("contacts sharing their rows of C are accepted only with local terms on every contact",
          "[unit][solvers]") {
  // Two strips of one contact (a pitted flank, docs/model.md §9): identical rows, C singular
  // (eigenvalues 0 and 8e-9). With both local terms, strictly increasing, the program stays
  // strictly convex: accepted, and the Newton solve splits the load so that both gaps close
  // (the strips' local approaches then differ by their overlaps' difference, 0.1 µm; the
  // solve's tolerance, 1e-10 of the nondimensional residual, leaves 1e-6 of it).
  auto d = Good();
  d.compliance << 4e-9, 4e-9, 4e-9, 4e-9;
  d.overlap = Eigen::Vector2d(5e-6, 4.9e-6);
  d.local[0].face_width = 0.0175;  // (1 − w) b, w = 0.3
  d.local[1].face_width = 0.0075;  // w b
  const ContactProblem p(d);
  auto solver = MakeContactSolver(Backend::kActiveSetNewton);
  ContactSolution s;
  const ContactReport r = solver->Solve(p, ContactOptions{}, &s);
  REQUIRE(r.status == ContactStatus::kConverged);
  CHECK(s.force.sum() == Approx(1000.0).epsilon(1e-9));
  const double du = LocalApproach(d.local[0], s.force(0)) - LocalApproach(d.local[1], s.force(1));
  REQUIRE(s.force(1) > 0);
  CHECK(du == Approx(1e-7).epsilon(1e-6));
  // Without local terms the same C is refused, with the rule.
  d.local.clear();
  CHECK_THROWS_WITH(ContactProblem(d), Catch::Contains("compliance is not positive definite") &&
                                           Catch::Contains("when every contact has a local term"));
}

}  // namespace epicycle::solvers
