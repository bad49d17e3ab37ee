// Validation of the contact problem: every rule names the field, the value and the rule.
#include "epicycle/solvers/contact_problem.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include "epicycle/io/number_format.hpp"

namespace epicycle::solvers {
namespace {

using io::Num;

// One vectorised test for the common case; the entries are searched for the message only when it
// fails.
void CheckFinite(const Eigen::MatrixXd& m, const char* field) {
  if (std::isfinite((m.array() - m.array()).sum())) return;  // x − x = 0 unless x is ±∞ or NaN
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j)))
        throw std::invalid_argument(std::string(field) + "(" + std::to_string(i) + "," +
                                    std::to_string(j) + ") = " + Num(m(i, j)) +
                                    ": every entry must be finite");
}

void CheckFinite(const Eigen::VectorXd& v, const char* field) {
  if (std::isfinite((v.array() - v.array()).sum())) return;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v(i)))
      throw std::invalid_argument(std::string(field) + "[" + std::to_string(i) +
                                  "] = " + Num(v(i)) + ": every entry must be finite");
}

// `why()` builds the rule's explanation, only for the message.
template <typename Why>
void CheckSize(Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows, Eigen::Index want_cols,
               const char* field, Why why) {
  if (rows != want_rows || cols != want_cols)
    throw std::invalid_argument(std::string(field) + " is " + std::to_string(rows) + "x" +
                                std::to_string(cols) + ": must be " + std::to_string(want_rows) +
                                "x" + std::to_string(want_cols) + " (" + why() + ")");
}

void CheckSymmetric(const Eigen::MatrixXd& m, const char* field) {
  const double scale = m.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < j; ++i) {
      const double d = std::abs(m(i, j) - m(j, i));
      if (d > ContactProblem::kSymmetryTolerance * scale) {
        const std::string f(field);
        throw std::invalid_argument(
            f + " is not symmetric: " + f + "(" + std::to_string(i) + "," + std::to_string(j) +
            ") = " + Num(m(i, j)) + " but " + f + "(" + std::to_string(j) + "," +
            std::to_string(i) + ") = " + Num(m(j, i)) +
            "; rule: |A_ij - A_ji| <= " + Num(ContactProblem::kSymmetryTolerance) +
            " * max|A| = " + Num(ContactProblem::kSymmetryTolerance * scale));
      }
    }
}

// Whether the Cholesky factorisation C = L Lᵀ of the symmetric `c` succeeds (c positive definite):
// column by column,
//
//   L_jj = √(C_jj − Σ_{k<j} L_jk²),   L_ij = (C_ij − Σ_{k<j} L_ik L_jk) / L_jj   (i > j),
//
// failing at the first pivot C_jj − Σ L_jk² ≤ 0 (Eigen's LLT rule). Up to kSmall contacts on the
// stack with L by rows (no allocation per problem: the dynamic model builds one per right-hand
// side), beyond with Eigen's blocked LLT.
bool CholeskySucceeds(const Eigen::MatrixXd& c) {
  constexpr Eigen::Index kSmall = 32;
  const Eigen::Index n = c.rows();
  if (n > kSmall) return Eigen::LLT<Eigen::MatrixXd>(c).info() == Eigen::Success;
  std::array<double, kSmall * kSmall> l;  // L_ik at l[i·n + k], k ≤ i
  for (Eigen::Index j = 0; j < n; ++j) {
    const double* lj = &l[static_cast<std::size_t>(j * n)];
    double pivot = c(j, j);
    for (Eigen::Index k = 0; k < j; ++k) pivot -= lj[k] * lj[k];
    if (!(pivot > 0)) return false;
    const double ljj = std::sqrt(pivot);
    l[static_cast<std::size_t>(j * n + j)] = ljj;
    for (Eigen::Index i = j + 1; i < n; ++i) {
      double* li = &l[static_cast<std::size_t>(i * n)];
      double v = c(i, j);
      for (Eigen::Index k = 0; k < j; ++k) v -= li[k] * lj[k];
      li[j] = v / ljj;
    }
  }
  return true;
}

// Positive definite (Cholesky succeeds) or, failing that, positive semidefinite within the
// tolerance (eigenvalues ≥ −kSymmetryTolerance·max|A|); returns 2, 1 or 0 for definite,
// semidefinite, neither. Factors are n×n or S×S, small next to C.
int Definiteness(const Eigen::MatrixXd& a) {
  if (CholeskySucceeds(a)) return 2;
  const double scale = a.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return 1;  // the zero matrix
  const double min_eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly)
                             .eigenvalues()
                             .minCoeff();
  return min_eig >= -ContactProblem::kSymmetryTolerance * scale ? 1 : 0;
}

// Whether Σ source ⊗ kernel is proved positive definite by its factors: positive semidefinite
// factors make every term PSD, and one term of two definite factors makes the sum definite.
bool FactorsProveDefinite(const std::vector<KroneckerTerm>& terms) {
  bool definite_term = false;
  for (const KroneckerTerm& t : terms) {
    const int a = Definiteness(t.source), b = Definiteness(t.kernel);
    if (a == 0 || b == 0) return false;  // not proved: the dense test decides
    definite_term = definite_term || (a == 2 && b == 2);
  }
  return definite_term;
}

// Whether `c` (N×N) is exactly Σ source ⊗ kernel, bit for bit, of one or two terms whose factors
// have the rules' sizes and are finite and exactly symmetric, with no sum that can overflow. Such
// a C meets every rule on C as it stands: finite, exactly symmetric (so its own symmetric part)
// and the terms' sum, and only the factors' definiteness is left to prove. It is what the
// face-width model writes (its blocks source_jk · kernel, one term non-zero per block), so the
// O(N²) rules' three passes over C, one of them by transposed entries, become one pass in storage
// order. Anything else returns false, without a message, and the rules then run one by one and
// name what is wrong.
bool IsExactKronecker(const std::vector<KroneckerTerm>& terms, const Eigen::MatrixXd& c) {
  if (terms.empty() || terms.size() > 2) return false;
  const Eigen::Index n = terms[0].source.rows(), slices = terms[0].kernel.rows();
  if (n * slices != c.rows()) return false;
  // Every |sum| ≤ Σ_terms max|source| max|kernel| (1 + 2ε): below half the largest double, no
  // sum overflows, and finite factors give finite sums.
  double bound = 0.0;
  for (const KroneckerTerm& t : terms) {
    if (t.source.rows() != n || t.source.cols() != n || t.kernel.rows() != slices ||
        t.kernel.cols() != slices)
      return false;
    if (!t.source.allFinite() || !t.kernel.allFinite()) return false;
    if (!(t.source.array() == t.source.transpose().array()).all() ||
        !(t.kernel.array() == t.kernel.transpose().array()).all())
      return false;
    bound += t.source.cwiseAbs().maxCoeff() * t.kernel.cwiseAbs().maxCoeff();
  }
  if (!(bound < 0.5 * std::numeric_limits<double>::max())) return false;
  // Column k S + t of C holds, for every source row j, the run s = 0 … S − 1 of
  // Σ_terms source_jk kernel_st, summed in the terms' order. Compared by their bits, OR-ed
  // together so that the loops vectorise (a −0 against a +0 then counts as a difference and
  // sends C to the rules, which accept it).
  const KroneckerTerm& first = terms[0];
  const KroneckerTerm* second = terms.size() == 2 ? &terms[1] : nullptr;
  auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  std::uint64_t mismatches = 0;
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index t = 0; t < slices; ++t) {
      const double* col = c.data() + (k * slices + t) * c.rows();
      const double* k0 = first.kernel.data() + t * slices;
      if (second == nullptr) {
        for (Eigen::Index j = 0; j < n; ++j) {
          const double a0 = first.source(j, k);
          const double* run = col + j * slices;
          for (Eigen::Index s = 0; s < slices; ++s) mismatches |= bits(run[s]) ^ bits(a0 * k0[s]);
        }
      } else {
        const double* k1 = second->kernel.data() + t * slices;
        for (Eigen::Index j = 0; j < n; ++j) {
          const double a0 = first.source(j, k), a1 = second->source(j, k);
          const double* run = col + j * slices;
          for (Eigen::Index s = 0; s < slices; ++s)
            mismatches |= bits(run[s]) ^ bits(a0 * k0[s] + a1 * k1[s]);
        }
      }
      if (mismatches != 0) return false;
    }
  return true;
}

// The rules of compliance_terms (contact_problem.hpp); returns whether they prove C positive
// definite. `c` is the symmetric compliance already validated as N×N and finite.
bool CheckComplianceTerms(const std::vector<KroneckerTerm>& terms, const Eigen::MatrixXd& c) {
  if (terms.empty()) return false;
  const Eigen::Index big_n = c.rows();
  const Eigen::Index n = terms[0].source.rows(), slices = terms[0].kernel.rows();
  for (std::size_t k = 0; k < terms.size(); ++k) {
    // The fields' names on the stack: the dynamic model validates a problem per right-hand side
    // and must not allocate.
    char source[48], kernel[48];
    std::snprintf(source, sizeof source, "compliance_terms[%zu].source", k);
    std::snprintf(kernel, sizeof kernel, "compliance_terms[%zu].kernel", k);
    const KroneckerTerm& t = terms[k];
    CheckSize(t.source.rows(), t.source.cols(), n, n, source,
              [] { return std::string("n x n, n the same for every term"); });
    CheckSize(t.kernel.rows(), t.kernel.cols(), slices, slices, kernel,
              [] { return std::string("S x S, S the same for every term"); });
    CheckFinite(t.source, source);
    CheckFinite(t.kernel, kernel);
    CheckSymmetric(t.source, source);
    CheckSymmetric(t.kernel, kernel);
  }
  if (n * slices != big_n)
    throw std::invalid_argument("compliance_terms have n = " + std::to_string(n) + " sources of S = " +
                                std::to_string(slices) + " slices: n*S = " +
                                std::to_string(n * slices) + " must equal N = " +
                                std::to_string(big_n));
  // C = Σ source ⊗ kernel, block (j, k) by block: C_jk,block − Σ_terms source_jk kernel.
  const double tol = ContactProblem::kSymmetryTolerance * c.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index j = 0; j < n; ++j) {
      const auto block = c.block(j * slices, k * slices, slices, slices);
      double worst = 0.0;
      if (terms.size() == 1) {
        worst = (block - terms[0].source(j, k) * terms[0].kernel).cwiseAbs().maxCoeff();
      } else if (terms.size() == 2) {
        worst = (block - terms[0].source(j, k) * terms[0].kernel -
                 terms[1].source(j, k) * terms[1].kernel)
                    .cwiseAbs()
                    .maxCoeff();
      } else {
        for (Eigen::Index t = 0; t < slices; ++t)
          for (Eigen::Index s = 0; s < slices; ++s) {
            double v = block(s, t);
            for (const KroneckerTerm& term : terms) v -= term.source(j, k) * term.kernel(s, t);
            worst = std::max(worst, std::abs(v));
          }
      }
      if (worst <= tol) continue;
      // The first entry beyond the rule, for the message.
      for (Eigen::Index t = 0; t < slices; ++t)
        for (Eigen::Index s = 0; s < slices; ++s) {
          double v = 0.0;
          for (const KroneckerTerm& term : terms) v += term.source(j, k) * term.kernel(s, t);
          const Eigen::Index row = j * slices + s, col = k * slices + t;
          if (std::abs(c(row, col) - v) > tol)
            throw std::invalid_argument(
                "compliance(" + std::to_string(row) + "," + std::to_string(col) + ") = " +
                Num(c(row, col)) + " but the sum of compliance_terms source(" +
                std::to_string(j) + "," + std::to_string(k) + ") * kernel(" + std::to_string(s) +
                "," + std::to_string(t) + ") gives " + Num(v) +
                "; rule: |C - sum source (x) kernel| <= " +
                Num(ContactProblem::kSymmetryTolerance) + " * max|C| = " + Num(tol));
        }
    }
  return FactorsProveDefinite(terms);
}

}  // namespace

ContactProblem::ContactProblem(ContactProblemData data) : data_(std::move(data)) {
  auto& d = data_;
  const Eigen::Index n = d.overlap.size();
  if (n < 1)
    throw std::invalid_argument("overlap has size 0: a problem needs at least one contact");
  CheckSize(d.compliance.rows(), d.compliance.cols(), n, n, "compliance",
            [&] { return "N x N with N = size of overlap = " + std::to_string(n); });
  const Eigen::Index m = d.equality_rhs.size();
  if (m == 0 && d.equality_matrix.size() == 0) d.equality_matrix.resize(0, n);
  CheckSize(d.equality_matrix.rows(), d.equality_matrix.cols(), m, n, "equality_matrix",
            [&] { return "m x N with m = size of equality_rhs = " + std::to_string(m); });
  if (d.support_stiffness.size() != 0)
    CheckSize(d.support_stiffness.rows(), d.support_stiffness.cols(), m, m, "support_stiffness",
              [] { return std::string("empty or m x m"); });
  if (!d.local.empty() && static_cast<Eigen::Index>(d.local.size()) != n)
    throw std::invalid_argument("local has " + std::to_string(d.local.size()) +
                                " entries: must be empty or N = " + std::to_string(n));
  if (!d.contact_labels.empty() && static_cast<Eigen::Index>(d.contact_labels.size()) != n)
    throw std::invalid_argument("contact_labels has " + std::to_string(d.contact_labels.size()) +
                                " entries: must be empty or N = " + std::to_string(n));
  if (!d.multiplier_labels.empty() && static_cast<Eigen::Index>(d.multiplier_labels.size()) != m)
    throw std::invalid_argument("multiplier_labels has " +
                                std::to_string(d.multiplier_labels.size()) +
                                " entries: must be empty or m = " + std::to_string(m));

  // A compliance given exactly as Σ source ⊗ kernel meets the rules on C as it stands
  // (IsExactKronecker): they are not run again.
  const bool exact_terms = IsExactKronecker(d.compliance_terms, d.compliance);
  if (!exact_terms) CheckFinite(d.compliance, "compliance");
  CheckFinite(d.overlap, "overlap");
  CheckFinite(d.equality_matrix, "equality_matrix");
  CheckFinite(d.equality_rhs, "equality_rhs");
  CheckFinite(d.support_stiffness, "support_stiffness");
  for (std::size_t j = 0; j < d.local.size(); ++j)  // names are built only for a message
    if (!IsValidLocalTerm(d.local[j]))
      ValidateLocalTerm(d.local[j], "local[" + std::to_string(j) + "]");

  if (exact_terms) {
    definite_by_structure_ = FactorsProveDefinite(d.compliance_terms);
  } else {
    CheckSymmetric(d.compliance, "compliance");
    for (Eigen::Index j = 0; j < n; ++j)  // the symmetric part, in place
      for (Eigen::Index i = 0; i < j; ++i)
        d.compliance(i, j) = d.compliance(j, i) = 0.5 * (d.compliance(i, j) + d.compliance(j, i));
    definite_by_structure_ = CheckComplianceTerms(d.compliance_terms, d.compliance);
  }
  if (!definite_by_structure_ && !CholeskySucceeds(d.compliance)) {
    // Contacts that share their rows of C (the strips of a pitted contact) make C singular; with
    // a local term on every contact, strictly increasing (u' > 0), the program stays strictly
    // convex and every Newton matrix C_AA + diag u'_A positive definite. Semidefinite within the
    // tolerance: C + τ s I (s the largest |C_ij|) has a Cholesky factor exactly when every
    // eigenvalue of C exceeds −τ s, the eigenvalues' test at a factorisation's cost (the
    // eigenvalues are computed for the message only).
    const bool all_local = !d.local.empty() &&
                           std::all_of(d.local.begin(), d.local.end(),
                                       [](const LocalTermParameters& l) { return l.enabled; });
    const double scale = d.compliance.cwiseAbs().maxCoeff();
    Eigen::MatrixXd shifted = d.compliance;
    shifted.diagonal().array() += kSymmetryTolerance * scale;
    if (!all_local || !CholeskySucceeds(shifted)) {
      const double min_eig =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(d.compliance, Eigen::EigenvaluesOnly)
              .eigenvalues()
              .minCoeff();
      throw std::invalid_argument(
          "compliance is not positive definite: smallest eigenvalue " + Num(min_eig) +
          " (Cholesky failed); rule: C must be SPD, or positive semidefinite (eigenvalues >= " +
          Num(-kSymmetryTolerance * scale) + ") when every contact has a local term");
    }
  }

  support_ = Eigen::MatrixXd::Zero(m, m);
  if (d.support_stiffness.size() != 0) {
    CheckSymmetric(d.support_stiffness, "support_stiffness");
    support_ = 0.5 * (d.support_stiffness + d.support_stiffness.transpose());
    d.support_stiffness = support_;
    const double scale = support_.cwiseAbs().maxCoeff();
    if (scale > 0.0) {
      const double min_eig =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(support_, Eigen::EigenvaluesOnly)
              .eigenvalues()
              .minCoeff();
      if (min_eig < -kSymmetryTolerance * scale)
        throw std::invalid_argument(
            "support_stiffness is not positive semidefinite: smallest "
            "eigenvalue " +
            Num(min_eig) + "; rule: K must be PSD");
    }
  }
}

bool ContactProblem::has_local() const {
  for (const auto& p : data_.local)
    if (p.enabled) return true;
  return false;
}

bool ContactProblem::has_support() const {
  return support_.size() > 0 && support_.cwiseAbs().maxCoeff() > 0.0;
}

Eigen::VectorXd ContactProblem::LocalApproach(const Eigen::VectorXd& force) const {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(num_contacts());
  for (std::size_t j = 0; j < data_.local.size(); ++j)
    u(j) = solvers::LocalApproach(data_.local[j], force(j));
  return u;
}

Eigen::VectorXd ContactProblem::Gap(const Eigen::VectorXd& force,
                                    const Eigen::VectorXd& multiplier) const {
  Eigen::VectorXd g = data_.compliance * force + LocalApproach(force) - data_.overlap;
  if (num_equalities() > 0) g -= data_.equality_matrix.transpose() * multiplier;
  return g;
}

double ContactProblem::Potential(const Eigen::VectorXd& force) const {
  double phi = 0.5 * force.dot(data_.compliance * force) - data_.overlap.dot(force);
  for (std::size_t j = 0; j < data_.local.size(); ++j)
    phi += LocalApproachIntegral(data_.local[j], force(j));
  return phi;
}

ContactProblemData ContactProblem::Release() && {
  support_.resize(0, 0);
  definite_by_structure_ = false;
  return std::move(data_);
}

double ContactProblem::ValidityLimitForce(int contact) const {
  if (data_.local.empty()) return std::numeric_limits<double>::infinity();
  return solvers::ValidityLimitForce(data_.local.at(contact));
}

}  // namespace epicycle::solvers
