// Generalised eigen-solve of the linearised stage and Lin & Parker's classification (modes.hpp).
#include "epicycle/dynamics/modes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "epicycle/io/number_format.hpp"

namespace epicycle::dynamics {
namespace {

using io::Num;

constexpr double kPi = 3.14159265358979323846;
constexpr double kSymmetryTolerance = 1e-10;

void CheckMatrix(const Eigen::MatrixXd& a, const std::string& field) {
  if (a.rows() != a.cols() || a.rows() == 0)
    throw std::invalid_argument(field + " is " + std::to_string(a.rows()) + "x" +
                                std::to_string(a.cols()) + ": must be square and not empty");
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      if (!std::isfinite(a(i, j)))
        throw std::invalid_argument(field + "(" + std::to_string(i) + "," + std::to_string(j) +
                                    ") = " + Num(a(i, j)) + ": every entry must be finite");
  const double scale = a.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < j; ++i)
      if (std::abs(a(i, j) - a(j, i)) > kSymmetryTolerance * scale)
        throw std::invalid_argument(
            field + "(" + std::to_string(i) + "," + std::to_string(j) + ") = " + Num(a(i, j)) +
            " but " + field + "(" + std::to_string(j) + "," + std::to_string(i) +
            ") = " + Num(a(j, i)) +
            ": must be symmetric, |A_ij - A_ji| <= " + Num(kSymmetryTolerance) + " * max|A|");
}

// owner[d] = index of the member that holds DOF d.
std::vector<int> DofOwners(const std::vector<MemberDofs>& layout, Eigen::Index n) {
  std::vector<int> owner(static_cast<size_t>(n), -1);
  for (size_t m = 0; m < layout.size(); ++m) {
    const MemberDofs& member = layout[m];
    const std::pair<const char*, int> dofs[] = {
        {"x", member.x}, {"y", member.y}, {"theta", member.theta}};
    for (const auto& [what, d] : dofs) {
      if (d == -1) continue;
      const std::string field = "layout[" + std::to_string(m) + "] (" + member.name + ")." + what;
      if (d < -1 || d >= n)
        throw std::invalid_argument(field + " = " + std::to_string(d) +
                                    ": must be -1 or a DOF index in [0, " + std::to_string(n) +
                                    ")");
      if (owner[static_cast<size_t>(d)] != -1)
        throw std::invalid_argument(
            field + " = " + std::to_string(d) + ": DOF already belongs to layout[" +
            std::to_string(owner[static_cast<size_t>(d)]) + "] (" +
            layout[static_cast<size_t>(owner[static_cast<size_t>(d)])].name +
            "); each DOF belongs to exactly one member");
      owner[static_cast<size_t>(d)] = static_cast<int>(m);
    }
  }
  for (Eigen::Index d = 0; d < n; ++d)
    if (owner[static_cast<size_t>(d)] == -1)
      throw std::invalid_argument("layout: DOF " + std::to_string(d) +
                                  " belongs to no member; each of the " + std::to_string(n) +
                                  " DOFs of M, K must belong to exactly one member");
  return owner;
}

// Energy fractions and type of one group of modes (columns of `shapes`).
void Classify(const Eigen::MatrixXd& M, const std::vector<MemberDofs>& layout,
              const std::vector<int>& owner, Mode* mode) {
  const Eigen::MatrixXd m_shapes = M * mode->shapes;
  const double m = static_cast<double>(mode->multiplicity);
  mode->member_energy.assign(layout.size(), 0.0);
  mode->central_translation = mode->central_rotation = mode->planets = 0;
  for (Eigen::Index d = 0; d < M.rows(); ++d) {
    const double e = mode->shapes.row(d).dot(m_shapes.row(d)) / m;
    const MemberDofs& member = layout[static_cast<size_t>(owner[static_cast<size_t>(d)])];
    mode->member_energy[static_cast<size_t>(owner[static_cast<size_t>(d)])] += e;
    if (!member.central)
      mode->planets += e;
    else if (d == member.theta)
      mode->central_rotation += e;
    else
      mode->central_translation += e;
  }
  // Off-diagonal mass coupling can make single entries negative; a class is absent when its
  // magnitude is below the tolerance.
  const double translation = std::abs(mode->central_translation);
  const double rotation = std::abs(mode->central_rotation);
  if (translation + rotation <= kModeEnergyTolerance)
    mode->type = ModeType::kPlanet;
  else if (translation <= kModeEnergyTolerance)
    mode->type = ModeType::kRotational;
  else if (rotation <= kModeEnergyTolerance)
    mode->type = ModeType::kTranslational;
  else
    mode->type = ModeType::kOther;
}

}  // namespace

std::string ModeTypeName(ModeType type) {
  switch (type) {
    case ModeType::kRotational:
      return "rotational";
    case ModeType::kTranslational:
      return "translational";
    case ModeType::kPlanet:
      return "planet";
    case ModeType::kOther:
      return "other";
  }
  return "other";
}

std::vector<Mode> SolveModes(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K,
                             const std::vector<MemberDofs>& layout, double degeneracy_tolerance) {
  CheckMatrix(M, "M");
  CheckMatrix(K, "K");
  if (K.rows() != M.rows())
    throw std::invalid_argument("K is " + std::to_string(K.rows()) + "x" +
                                std::to_string(K.cols()) + ": must be of the size of M, " +
                                std::to_string(M.rows()) + "x" + std::to_string(M.cols()));
  if (!(degeneracy_tolerance > 0 && degeneracy_tolerance < 1))
    throw std::invalid_argument("degeneracy_tolerance = " + Num(degeneracy_tolerance) +
                                ": must be in (0, 1)");
  const std::vector<int> owner = DofOwners(layout, M.rows());
  if (Eigen::LLT<Eigen::MatrixXd>(M).info() != Eigen::Success)
    throw std::invalid_argument("M is not positive definite: every DOF needs mass or inertia");

  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      K, M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (solver.info() != Eigen::Success)
    throw std::domain_error("SolveModes: the generalised eigensolver did not converge");
  const Eigen::VectorXd& lambda = solver.eigenvalues();  // ascending
  const Eigen::MatrixXd& phi = solver.eigenvectors();    // φᵀMφ = I
  const double lambda_max = lambda.cwiseAbs().maxCoeff();
  const double rigid_limit = kRigidEigenvalueTolerance * lambda_max;
  if (lambda(0) < -rigid_limit)
    throw std::domain_error("K has the eigenvalue omega^2 = " + Num(lambda(0)) + " 1/s^2 < -" +
                            Num(kRigidEigenvalueTolerance) +
                            " * max|omega^2|: the linearisation is unstable (no real frequency)");

  const Eigen::Index n = lambda.size();
  std::vector<double> frequency(static_cast<size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k)
    frequency[static_cast<size_t>(k)] =
        lambda(k) <= rigid_limit ? 0.0 : std::sqrt(lambda(k)) / (2 * kPi);

  std::vector<Mode> modes;
  for (Eigen::Index first = 0; first < n;) {
    const double f0 = frequency[static_cast<size_t>(first)];
    Eigen::Index last = first + 1;
    while (last < n) {
      const double f = frequency[static_cast<size_t>(last)];
      if (f0 == 0.0 ? f != 0.0 : std::abs(f - f0) > degeneracy_tolerance * f) break;
      ++last;
    }
    Mode mode;
    // The group's mean: the split inside a degenerate group is round-off, the mean its best value.
    double sum = 0;
    for (Eigen::Index k = first; k < last; ++k) sum += frequency[static_cast<size_t>(k)];
    mode.frequency = sum / static_cast<double>(last - first);
    mode.rigid = f0 == 0.0;
    mode.multiplicity = static_cast<int>(last - first);
    mode.shapes = phi.middleCols(first, last - first);
    mode.shape = mode.shapes.col(0);
    Classify(M, layout, owner, &mode);
    modes.push_back(std::move(mode));
    first = last;
  }
  return modes;
}

}  // namespace epicycle::dynamics
