// Validation of the contact problem: every rule names the field, the value and the rule.
#include "epicycle/solvers/contact_problem.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace epicycle::solvers {
namespace {

std::string Num(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

void CheckFinite(const Eigen::MatrixXd& m, const std::string& field) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j)))
        throw std::invalid_argument(field + "(" + std::to_string(i) + "," + std::to_string(j) +
                                    ") = " + Num(m(i, j)) + ": every entry must be finite");
}

void CheckFinite(const Eigen::VectorXd& v, const std::string& field) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v(i)))
      throw std::invalid_argument(field + "[" + std::to_string(i) + "] = " + Num(v(i)) +
                                  ": every entry must be finite");
}

void CheckSize(Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows, Eigen::Index want_cols,
               const std::string& field, const std::string& why) {
  if (rows != want_rows || cols != want_cols)
    throw std::invalid_argument(field + " is " + std::to_string(rows) + "x" + std::to_string(cols) +
                                ": must be " + std::to_string(want_rows) + "x" +
                                std::to_string(want_cols) + " (" + why + ")");
}

void CheckSymmetric(const Eigen::MatrixXd& m, const std::string& field) {
  const double scale = m.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < j; ++i) {
      const double d = std::abs(m(i, j) - m(j, i));
      if (d > ContactProblem::kSymmetryTolerance * scale)
        throw std::invalid_argument(
            field + " is not symmetric: " + field + "(" + std::to_string(i) + "," +
            std::to_string(j) + ") = " + Num(m(i, j)) + " but " + field + "(" + std::to_string(j) +
            "," + std::to_string(i) + ") = " + Num(m(j, i)) +
            "; rule: |A_ij - A_ji| <= " + Num(ContactProblem::kSymmetryTolerance) +
            " * max|A| = " + Num(ContactProblem::kSymmetryTolerance * scale));
    }
}

}  // namespace

ContactProblem::ContactProblem(ContactProblemData data) : data_(std::move(data)) {
  auto& d = data_;
  const Eigen::Index n = d.overlap.size();
  if (n < 1)
    throw std::invalid_argument("overlap has size 0: a problem needs at least one contact");
  CheckSize(d.compliance.rows(), d.compliance.cols(), n, n, "compliance",
            "N x N with N = size of overlap = " + std::to_string(n));
  const Eigen::Index m = d.equality_rhs.size();
  if (m == 0 && d.equality_matrix.size() == 0) d.equality_matrix.resize(0, n);
  CheckSize(d.equality_matrix.rows(), d.equality_matrix.cols(), m, n, "equality_matrix",
            "m x N with m = size of equality_rhs = " + std::to_string(m));
  if (d.support_stiffness.size() != 0)
    CheckSize(d.support_stiffness.rows(), d.support_stiffness.cols(), m, m, "support_stiffness",
              "empty or m x m");
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

  CheckFinite(d.compliance, "compliance");
  CheckFinite(d.overlap, "overlap");
  CheckFinite(d.equality_matrix, "equality_matrix");
  CheckFinite(d.equality_rhs, "equality_rhs");
  CheckFinite(d.support_stiffness, "support_stiffness");
  for (std::size_t j = 0; j < d.local.size(); ++j)  // names are built only for a message
    if (!IsValidLocalTerm(d.local[j]))
      ValidateLocalTerm(d.local[j], "local[" + std::to_string(j) + "]");

  CheckSymmetric(d.compliance, "compliance");
  for (Eigen::Index j = 0; j < n; ++j)  // the symmetric part, in place
    for (Eigen::Index i = 0; i < j; ++i)
      d.compliance(i, j) = d.compliance(j, i) = 0.5 * (d.compliance(i, j) + d.compliance(j, i));
  Eigen::LLT<Eigen::MatrixXd> llt(d.compliance);
  if (llt.info() != Eigen::Success) {
    const double min_eig =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(d.compliance, Eigen::EigenvaluesOnly)
            .eigenvalues()
            .minCoeff();
    throw std::invalid_argument("compliance is not positive definite: smallest eigenvalue " +
                                Num(min_eig) + " (Cholesky failed); rule: C must be SPD");
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

double ContactProblem::ValidityLimitForce(int contact) const {
  if (data_.local.empty()) return std::numeric_limits<double>::infinity();
  return solvers::ValidityLimitForce(data_.local.at(contact));
}

}  // namespace epicycle::solvers
