// A compliance given as a sum of Kronecker terms, C = Σ source ⊗ kernel (contact_problem.hpp,
// docs/solvers.md §12): the validation's rules (each names the field, the value and the rule),
// definiteness proved from the factors, the slice groups the Newton factorises block by block,
// the Newton's Kronecker factorisation of its face system against a dense LU, and the structured
// Newton's answer against the dense Newton's within the bound derived in kkt_bound.hpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include <Eigen/LU>

#include "backend.hpp"  // ScaledProblem's slice groups
#include "face_solver.hpp"  // the Newton's face system (white box)
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "kkt_bound.hpp"
#include "thrown_message.hpp"

namespace epicycle::solvers {
namespace {

Eigen::MatrixXd Kron(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd k(a.rows() * b.rows(), a.cols() * b.cols());
  for (Eigen::Index j = 0; j < a.rows(); ++j)
    for (Eigen::Index i = 0; i < a.cols(); ++i)
      k.block(j * b.rows(), i * b.cols(), b.rows(), b.cols()) = a(j, i) * b;
  return k;
}

// n source contacts, SPD C_n [m/N] of a stage's order (1e-10…1e-9 m/N), with deterministic
// off-diagonal coupling.
Eigen::MatrixXd SourceCompliance(int n) {
  Eigen::MatrixXd a(n, n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) a(j, k) = std::sin(1.0 + 3.0 * j + 7.0 * k);
  return (a * a.transpose() + n * Eigen::MatrixXd::Identity(n, n)) * 1e-10;
}

// Uncoupled slices: W = S I.
Eigen::MatrixXd UncoupledKernel(int slices) {
  return slices * Eigen::MatrixXd::Identity(slices, slices);
}

// An exponential kernel S exp(−|s − t|/2): the covariance of an Ornstein–Uhlenbeck process,
// positive definite, dense (every slice coupled to every other).
Eigen::MatrixXd DenseKernel(int slices) {
  Eigen::MatrixXd w(slices, slices);
  for (int s = 0; s < slices; ++s)
    for (int t = 0; t < slices; ++t) w(s, t) = slices * std::exp(-0.5 * std::abs(s - t));
  return w;
}

// A problem of n contacts of S slices: a total load W on G = 1ᵀ (one member), every slice with
// the local term of a 25 mm face split in S, overlaps that fall across the face (a misalignment)
// so that the slices of one end lift off.
ContactProblemData SlicedProblem(int n, int slices, const std::vector<KroneckerTerm>& terms) {
  ContactProblemData d;
  d.name = "kronecker";
  const int big_n = n * slices;
  d.compliance = Eigen::MatrixXd::Zero(big_n, big_n);
  for (const KroneckerTerm& t : terms) d.compliance += Kron(t.source, t.kernel);
  d.compliance_terms = terms;
  d.overlap.resize(big_n);
  for (int j = 0; j < n; ++j)
    for (int s = 0; s < slices; ++s)
      d.overlap(j * slices + s) = 1e-6 * (1.0 - 0.2 * j) - 8e-6 * (s + 0.5) / slices;
  d.equality_matrix = Eigen::MatrixXd::Ones(1, big_n);
  d.equality_rhs = Eigen::VectorXd::Constant(1, 4e3);
  LocalTermParameters p;
  p.face_width = 0.025 / slices;
  p.reduced_radius = 0.01;
  p.body[0] = p.body[1] = {207e9, 0.3, 2e-3};
  d.local.assign(static_cast<std::size_t>(big_n), p);
  return d;
}


// The face system [H −Gᵀ; G S] [dx; dλ] = [r1; r2] (face_solver.hpp) of the scaled problem on the
// active contacts, solved by a full-pivoting LU of its own; *kappa receives κ∞(K) and *k_inv
// ‖K⁻¹‖∞ of that matrix.
void ReferenceFaceSolve(const internal::ScaledProblem& sp, const std::vector<int>& active,
                        const Eigen::VectorXd& du, const Eigen::VectorXd& r1,
                        const Eigen::VectorXd& r2, Eigen::VectorXd* dx, Eigen::VectorXd* dl,
                        double* kappa, double* k_inv) {
  const Eigen::Index na = static_cast<Eigen::Index>(active.size()), m = sp.num_equalities();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(na + m, na + m);
  k.topLeftCorner(na, na) = sp.C(active, active);
  k.topLeftCorner(na, na).diagonal() += du;
  k.topRightCorner(na, m) = -sp.G(Eigen::all, active).transpose();
  k.bottomLeftCorner(m, na) = sp.G(Eigen::all, active);
  k.bottomRightCorner(m, m) = sp.S;
  Eigen::VectorXd rhs(na + m);
  rhs << r1, r2;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(k);
  const Eigen::VectorXd sol = lu.solve(rhs);
  *dx = sol.head(na);
  *dl = sol.tail(m);
  *k_inv = lu.inverse().cwiseAbs().rowwise().sum().maxCoeff();
  *kappa = k.cwiseAbs().rowwise().sum().maxCoeff() * *k_inv;
}

TEST_CASE("Kronecker compliance: the Newton's face system factorised in the kernel's eigenbasis "
          "is the dense LU's solution",
          "[unit][solvers]") {
  const int n = 6, slices = 8, big_n = n * slices;
  const Eigen::MatrixXd cn = SourceCompliance(n);
  internal::ScaledProblem sp = internal::MakeScaledProblem(
      ContactProblem(SlicedProblem(n, slices, {{cn, DenseKernel(slices)}})));
  // One term whose kernel couples every slice: the factors are carried.
  REQUIRE(sp.slice_groups == 1);
  REQUIRE(sp.kron_source.rows() == n);
  REQUIRE(sp.kron_kernel.rows() == slices);
  const double c_top = sp.C.diagonal().maxCoeff();
  const int m = sp.num_equalities();
  const Eigen::VectorXd r2 = Eigen::VectorXd::Constant(m, 0.7);
  // Both answers are backward stable (LU with full pivoting; Cholesky with one refinement step on
  // the dense matrix): each is within c·(N+m)·ε·κ∞(K) of the exact solution relative to its
  // size, so they differ by at most twice that (c = 1: the growth of both factorisations is
  // small for these definite blocks).
  const double eps = std::numeric_limits<double>::epsilon();
  auto check = [&](const std::vector<int>& active, const Eigen::VectorXd& du, bool kronecker,
                   double extra) {
    const Eigen::Index na = static_cast<Eigen::Index>(active.size());
    Eigen::VectorXd r1(na);
    for (Eigen::Index a = 0; a < na; ++a) r1(a) = std::sin(0.3 + 1.7 * static_cast<double>(a));
    internal::FaceSolver face(sp);
    REQUIRE(face.Factor(active, du));
    CHECK(face.kronecker_factorisations() == (kronecker ? 1 : 0));
    Eigen::VectorXd dx, dl, ref_x, ref_l;
    face.Solve(r1, r2, &dx, &dl);
    double kappa = 0, k_inv = 0;
    ReferenceFaceSolve(sp, active, du, r1, r2, &ref_x, &ref_l, &kappa, &k_inv);
    Eigen::VectorXd got(na + m), want(na + m);
    got << dx, dl;
    want << ref_x, ref_l;
    const double error = (got - want).cwiseAbs().maxCoeff() / want.cwiseAbs().maxCoeff();
    const double bound = 2.0 * static_cast<double>(na + m) * eps * kappa + extra * k_inv * k_inv;
    INFO("relative difference " << error << ", bound " << bound << ", kappa " << kappa);
    CHECK(error <= bound);
  };
  std::vector<int> all(static_cast<std::size_t>(big_n));
  for (int i = 0; i < big_n; ++i) all[static_cast<std::size_t>(i)] = i;
  // The cold start: every contact active, u' uniform over each contact's slices.
  Eigen::VectorXd du(big_n);
  for (int i = 0; i < big_n; ++i) du(i) = c_top * (0.2 + 0.1 * (i / slices));
  check(all, du, true, 0.0);
  // Whole contacts {0, 2, 3, 5} active: C_n,JJ ⊗ W.
  std::vector<int> some;
  for (int j : {0, 2, 3, 5})
    for (int s = 0; s < slices; ++s) some.push_back(j * slices + s);
  Eigen::VectorXd du_some(static_cast<Eigen::Index>(some.size()));
  for (std::size_t a = 0; a < some.size(); ++a) du_some(static_cast<Eigen::Index>(a)) = du(some[a]);
  check(some, du_some, true, 0.0);
  // u' that varies along the face, or a slice of a contact off: the dense path.
  Eigen::VectorXd du_varying = du;
  du_varying(3) *= 1.5;
  check(all, du_varying, false, 0.0);
  std::vector<int> partial = all;
  partial.erase(partial.begin() + 5);
  Eigen::VectorXd du_partial(big_n - 1);
  du_partial << du.head(5), du.tail(big_n - 6);
  check(partial, du_partial, false, 0.0);
  // C off source ⊗ kernel by validation's limit, 1e-10·max|C|, in one symmetric pair: the
  // Kronecker solve has the error ρ/(1 − ρ), ρ ≤ ‖K⁻¹‖∞‖ΔC‖∞ with ‖ΔC‖∞ = 1e-10·max|C|, and the
  // refinement on the dense matrix multiplies it by ρ again: ρ² = ‖K⁻¹‖∞²·(1e-10·max|C|)² (to
  // first order), the second term of the bound.
  const double delta = 1e-10 * sp.C.cwiseAbs().maxCoeff();
  sp.C(7, 20) += delta;
  sp.C(20, 7) += delta;
  check(all, du, true, 1.01 * delta * delta);
}
}  // namespace

TEST_CASE("Kronecker compliance: validation proves definiteness from the factors and names what "
          "does not match",
          "[unit][solvers]") {
  const int n = 3, slices = 4;
  const Eigen::MatrixXd cn = SourceCompliance(n), identity = UncoupledKernel(slices);
  {
    const ContactProblem p(SlicedProblem(n, slices, {{cn, identity}}));
    CHECK(p.definite_by_structure());
    CHECK(p.slices() == slices);
  }
  {
    // Without the structure the same problem is tested densely.
    ContactProblemData d = SlicedProblem(n, slices, {{cn, identity}});
    d.compliance_terms.clear();
    CHECK_FALSE(ContactProblem(d).definite_by_structure());
  }
  {
    // An entry that differs from Σ source ⊗ kernel by 1e-6 of max|C| (beyond 1e-10).
    ContactProblemData d = SlicedProblem(n, slices, {{cn, identity}});
    const double top = d.compliance.cwiseAbs().maxCoeff();
    d.compliance(5, 1) += 1e-6 * top;
    d.compliance(1, 5) += 1e-6 * top;
    const std::string m = test::ThrownMessage([&] { ContactProblem{d}; });
    CHECK_THAT(m, Catch::Contains("compliance(5,1) = ") &&
                      Catch::Contains("rule: |C - sum source (x) kernel| <= 1e-10 * max|C|"));
  }
  {
    // Every term's kernel has the first term's S.
    ContactProblemData d = SlicedProblem(n, slices, {{cn, identity}});
    d.compliance_terms.push_back({0.0 * cn, Eigen::MatrixXd::Identity(3, 3)});
    CHECK_THAT(test::ThrownMessage([&] { ContactProblem{d}; }),
               Catch::Contains("compliance_terms[1].kernel is 3x3: must be 4x4"));
  }
  {
    ContactProblemData d = SlicedProblem(n, slices, {{cn, identity}});
    d.compliance_terms[0].source = SourceCompliance(2);
    d.compliance_terms[0].kernel = Eigen::MatrixXd::Identity(4, 4);
    CHECK_THAT(test::ThrownMessage([&] { ContactProblem{d}; }),
               Catch::Contains("n*S = 8 must equal N = 12"));
  }
  {
    // A source that is not positive semidefinite: nothing is proved, the dense test decides
    // (the sum is definite: cn ⊗ (S I) dominates).
    Eigen::MatrixXd indefinite = Eigen::MatrixXd::Zero(n, n);
    indefinite(0, 1) = indefinite(1, 0) = 0.1 * cn(0, 0);
    const ContactProblem p(SlicedProblem(n, slices, {{cn, identity}, {indefinite, identity}}));
    CHECK_FALSE(p.definite_by_structure());
  }
  {
    // Definite, semidefinite: C_tooth ⊗ (S I) + C_body ⊗ 1 1ᵀ (a rank-one kernel) is proved.
    const Eigen::MatrixXd ones = Eigen::MatrixXd::Ones(slices, slices);
    const ContactProblem p(SlicedProblem(n, slices, {{cn, identity}, {0.5 * cn, ones}}));
    CHECK(p.definite_by_structure());
  }
}

TEST_CASE(
    "Kronecker compliance: a C that is exactly the terms' sum is taken as it stands, one "
    "off by round-off or with an overflowed sum goes through the rules",
    "[unit][solvers]") {
  const int n = 3, slices = 4;
  const Eigen::MatrixXd cn = SourceCompliance(n), w = DenseKernel(slices);
  {
    // Exactly C_n ⊗ W: C stored bit for bit, definite by its factors.
    const ContactProblemData d = SlicedProblem(n, slices, {{cn, w}});
    const ContactProblem p(d);
    CHECK(p.compliance() == d.compliance);
    CHECK(p.definite_by_structure());
    // C_n split into two terms as the face-width model splits its meshes (each block from one
    // term, the other's source entry 0; the first source is then indefinite, and C is tested
    // densely): C stored bit for bit.
    Eigen::MatrixXd first = cn, second = Eigen::MatrixXd::Zero(n, n);
    second(2, 2) = first(2, 2);
    first(2, 2) = 0.0;
    const ContactProblemData split = SlicedProblem(n, slices, {{first, w}, {second, 2.0 * w}});
    CHECK(ContactProblem(split).compliance() == split.compliance);
  }
  {
    // One entry one ulp off its transposed entry: symmetric within the rule, stored as the
    // symmetric part, and within the rule of the terms' sum.
    ContactProblemData d = SlicedProblem(n, slices, {{cn, w}});
    const double lower = d.compliance(5, 1), upper = d.compliance(1, 5);
    d.compliance(5, 1) = std::nextafter(lower, 1.0);
    const ContactProblem p(d);
    CHECK(p.compliance()(5, 1) == 0.5 * (d.compliance(5, 1) + upper));
    CHECK(p.compliance()(1, 5) == p.compliance()(5, 1));
    CHECK(p.definite_by_structure());
  }
  {
    // A source one ulp off symmetric, C its exact Kronecker product: the source is within the
    // rule, and C is stored as its (exactly symmetric) symmetric part.
    Eigen::MatrixXd skew = cn;
    skew(0, 1) = std::nextafter(cn(0, 1), 1.0);
    const ContactProblem p(SlicedProblem(n, slices, {{skew, w}}));
    CHECK((p.compliance() - p.compliance().transpose()).cwiseAbs().maxCoeff() == 0.0);
    CHECK(p.definite_by_structure());
  }
  {
    // Finite factors whose products overflow: C's entries are the products (inf), refused by
    // the rule on C's entries.
    const ContactProblemData d = SlicedProblem(n, slices, {{1e300 * cn, 1e30 * w}});
    REQUIRE(std::isinf(d.compliance(0, 0)));
    CHECK_THAT(test::ThrownMessage([&] { ContactProblem{d}; }),
               Catch::Contains("compliance(0,0) = inf: every entry must be finite"));
  }
}

TEST_CASE("Kronecker compliance: the slice groups that the Newton factorises on their own",
          "[unit][solvers]") {
  const int n = 3, slices = 5;
  const Eigen::MatrixXd cn = SourceCompliance(n), identity = UncoupledKernel(slices);
  // S I: every slice its own group. A tridiagonal kernel: one group (a chain). 1 1ᵀ: one group.
  CHECK(internal::MakeScaledProblem(ContactProblem(SlicedProblem(n, slices, {{cn, identity}})))
            .slice_groups == slices);
  Eigen::MatrixXd chain = identity;
  for (int s = 0; s + 1 < slices; ++s) chain(s, s + 1) = chain(s + 1, s) = 1.0;
  CHECK(internal::MakeScaledProblem(ContactProblem(SlicedProblem(n, slices, {{cn, chain}})))
            .slice_groups == 1);
  // Slices {0, 2, 4} and {1, 3} coupled among themselves only: two groups.
  Eigen::MatrixXd two = identity;
  two(0, 2) = two(2, 0) = two(2, 4) = two(4, 2) = 1.0;
  two(1, 3) = two(3, 1) = 1.0;
  const internal::ScaledProblem sp =
      internal::MakeScaledProblem(ContactProblem(SlicedProblem(n, slices, {{cn, two}})));
  CHECK(sp.slice_groups == 2);
  CHECK(sp.slice_group == std::vector<int>{0, 1, 0, 1, 0});
  CHECK(internal::MakeScaledProblem(ContactProblem(SlicedProblem(n, slices, {{cn, identity}})))
            .slices == slices);
}

TEST_CASE("Kronecker compliance: the structured Newton's answer is the dense Newton's within the "
          "KKT bound",
          "[unit][solvers]") {
  const int n = 6, slices = 8;
  const Eigen::MatrixXd cn = SourceCompliance(n), identity = UncoupledKernel(slices);
  const Eigen::MatrixXd ones = Eigen::MatrixXd::Ones(slices, slices);
  const std::vector<std::pair<std::string, std::vector<KroneckerTerm>>> kinds = {
      {"identity kernel (block path)", {{cn, identity}}},
      {"dense kernel", {{cn, DenseKernel(slices)}}},
      {"identity + rank-one body kernel", {{cn, identity}, {0.3 * cn, ones}}},
  };
  constexpr double kTolerance = 1e-10;
  for (const auto& [label, terms] : kinds) {
    CAPTURE(label);
    const ContactProblem structured(SlicedProblem(n, slices, terms));
    ContactProblemData dense_data = SlicedProblem(n, slices, terms);
    dense_data.compliance_terms.clear();
    const ContactProblem dense(std::move(dense_data));
    ContactOptions o;
    o.tolerance = kTolerance;
    ContactSolution a, b;
    const ContactReport ra = MakeContactSolver(Backend::kActiveSetNewton)->Solve(dense, o, &a);
    const ContactReport rb =
        MakeContactSolver(Backend::kActiveSetNewton)->Solve(structured, o, &b);
    REQUIRE(ra.status == ContactStatus::kConverged);
    REQUIRE(rb.status == ContactStatus::kConverged);
    const test::KktBound kb = test::ScaledKktBound(dense, a, kTolerance);
    // The misalignment lifts some slices off and keeps others loaded: the active set matters.
    CHECK(kb.active.size() > 0);
    CHECK(static_cast<int>(kb.active.size()) < n * slices);
    const double diff = (b.force / kb.force_scale - kb.scaled_force).cwiseAbs().maxCoeff();
    INFO("difference " << diff << " bound " << kb.bound);
    CHECK(diff <= kb.bound);
  }
}

}  // namespace epicycle::solvers
