#include "epicycle/compliance/elastic_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/LU>

namespace epicycle::compliance {
namespace {

Mesh ValidatedMesh(Mesh mesh, const ElasticMaterial& material) {
  material.Validate();
  mesh.Validate();
  return mesh;
}

const char* ComponentName(int c) { return c == 0 ? "x" : "y"; }

}  // namespace

LinearElasticModel::LinearElasticModel(Mesh mesh, const ElasticMaterial& material)
    : mesh_(ValidatedMesh(std::move(mesh), material)), material_(material) {
  const Eigen::Matrix3d d = material_.ElasticityMatrix();
  const int n = num_dofs();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(mesh_.num_elements()) * 4 * kQ8Nodes * kQ8Nodes);
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    const Q8Stiffness ke = Q8ElementStiffness(mesh_.ElementCoordinates(e), d, material_.thickness);
    const auto& el = mesh_.elements[e];
    for (int a = 0; a < 2 * kQ8Nodes; ++a) {
      const int row = Dof(el[a / 2], a % 2);
      for (int c = 0; c < 2 * kQ8Nodes; ++c) {
        triplets.emplace_back(row, Dof(el[c / 2], c % 2), ke(a, c));
      }
    }
  }
  k_.resize(n, n);
  k_.setFromTriplets(triplets.begin(), triplets.end());
  k_.makeCompressed();
  constrained_.assign(static_cast<std::size_t>(n), 0);
  prescribed_.assign(static_cast<std::size_t>(n), 0.0);
}

long LinearElasticModel::factor_nonzeros() const {
  RequireFactorized();
  return static_cast<long>(ldlt_.matrixL().nestedExpression().nonZeros());
}

void LinearElasticModel::PrescribeDof(int node, int component, double value) {
  if (node < 0 || node >= mesh_.num_nodes() || (component != 0 && component != 1) ||
      !std::isfinite(value)) {
    std::ostringstream msg;
    msg << "PrescribeDof(node " << node << ", component " << component << ", value " << value
        << "): the rule is 0 <= node < " << mesh_.num_nodes()
        << ", component 0 (x) or 1 (y), finite value [m]";
    throw std::invalid_argument(msg.str());
  }
  constrained_[Dof(node, component)] = 1;
  prescribed_[Dof(node, component)] = value;
  factorized_ = false;
}

void LinearElasticModel::FixNodeSet(const std::string& set, Components which) {
  PrescribeNodeSet(
      set, [](const Eigen::Vector2d&) { return Eigen::Vector2d::Zero().eval(); }, which);
}

void LinearElasticModel::PrescribeNodeSet(
    const std::string& set, const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& g,
    Components which) {
  for (int v : mesh_.NodeSet(set)) {
    const Eigen::Vector2d value = g(mesh_.nodes[v]);
    if (which != Components::kY) PrescribeDof(v, 0, value.x());
    if (which != Components::kX) PrescribeDof(v, 1, value.y());
  }
}

void LinearElasticModel::ClearConstraints() {
  std::fill(constrained_.begin(), constrained_.end(), 0);
  std::fill(prescribed_.begin(), prescribed_.end(), 0.0);
  factorized_ = false;
}

void LinearElasticModel::Factorize() {
  const int n = num_dofs();
  std::vector<int> index(static_cast<std::size_t>(n));
  free_dofs_.clear();
  constrained_dofs_.clear();
  for (int i = 0; i < n; ++i) {
    if (constrained_[i]) {
      index[i] = static_cast<int>(constrained_dofs_.size());
      constrained_dofs_.push_back(i);
    } else {
      index[i] = static_cast<int>(free_dofs_.size());
      free_dofs_.push_back(i);
    }
  }
  if (free_dofs_.empty()) {
    throw std::invalid_argument(
        "LinearElasticModel::Factorize: every DOF is constrained; nothing to solve");
  }
  const int nf = static_cast<int>(free_dofs_.size());
  const int nc = static_cast<int>(constrained_dofs_.size());
  std::vector<Eigen::Triplet<double>> ff, fc;
  ff.reserve(static_cast<std::size_t>(k_.nonZeros()));
  for (int col = 0; col < k_.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(k_, col); it; ++it) {
      const int row = static_cast<int>(it.row());
      if (constrained_[row]) continue;
      if (constrained_[col]) {
        fc.emplace_back(index[row], index[col], it.value());
      } else {
        ff.emplace_back(index[row], index[col], it.value());
      }
    }
  }
  Eigen::SparseMatrix<double> k_ff(nf, nf);
  k_ff.setFromTriplets(ff.begin(), ff.end());
  ff.clear();
  ff.shrink_to_fit();
  k_fc_.resize(nf, nc);
  k_fc_.setFromTriplets(fc.begin(), fc.end());
  ldlt_.compute(k_ff);
  // A rigid-body mode left free shows up as a pivot at round-off level of its diagonal entry.
  const Eigen::VectorXd pivots = ldlt_.vectorD();
  const auto& pinv = ldlt_.permutationPinv().indices();
  const Eigen::VectorXd diag = k_ff.diagonal();
  for (int k = 0; k < nf; ++k) {
    const int free_index = pinv(k);
    const double kk = diag(free_index);
    if (ldlt_.info() != Eigen::Success || !(pivots(k) > kSingularPivot * kk)) {
      const int dof = free_dofs_[free_index];
      std::ostringstream msg;
      msg << "LinearElasticModel::Factorize: the constrained stiffness is singular: pivot "
          << pivots(k) << " N/m at node " << dof / 2 << " component " << ComponentName(dof % 2)
          << " (diagonal " << kk << " N/m; the rule is pivot > " << kSingularPivot
          << " x diagonal): rigid-body motion is not removed; constrain more DOFs";
      throw std::invalid_argument(msg.str());
    }
  }
  factorized_ = true;
}

void LinearElasticModel::RequireFactorized() const {
  if (!factorized_) {
    throw std::invalid_argument(
        "LinearElasticModel: not factorised; call Factorize() after setting the constraints");
  }
}

void LinearElasticModel::AddNodalForce(int node, const Eigen::Vector2d& force,
                                       Eigen::VectorXd* f) const {
  if (node < 0 || node >= mesh_.num_nodes() || f == nullptr || f->size() != num_dofs() ||
      !force.allFinite()) {
    std::ostringstream msg;
    msg << "AddNodalForce(node " << node << "): the rule is 0 <= node < " << mesh_.num_nodes()
        << ", a finite force and a load vector of length " << num_dofs();
    throw std::invalid_argument(msg.str());
  }
  (*f)(Dof(node, 0)) += force.x();
  (*f)(Dof(node, 1)) += force.y();
}

void LinearElasticModel::AddEdgePointForce(const std::string& set, const EdgePoint& at,
                                           const Eigen::Vector2d& force, Eigen::VectorXd* f) const {
  mesh_.EdgePosition(set, at);  // validates the set and the point
  const BoundaryEdge& edge = mesh_.EdgeSet(set)[at.edge];
  const Eigen::Vector3d n = EdgeShapeFunctions(at.xi);
  for (int a = 0; a < 3; ++a) AddNodalForce(edge.nodes[a], n(a) * force, f);
}

void LinearElasticModel::AddEdgeTraction(const std::string& set, const TractionField& traction,
                                         Eigen::VectorXd* f, int gauss_points) const {
  const auto& edges = mesh_.EdgeSet(set);
  const GaussRule g = GaussLegendre(gauss_points);
  if (f == nullptr || f->size() != num_dofs()) {
    throw std::invalid_argument("AddEdgeTraction: the load vector must have length " +
                                std::to_string(num_dofs()));
  }
  for (const BoundaryEdge& edge : edges) {
    Eigen::Matrix<double, 2, 3> x;
    for (int a = 0; a < 3; ++a) x.col(a) = mesh_.nodes[edge.nodes[a]];
    for (int q = 0; q < g.size; ++q) {
      const Eigen::Vector3d n = EdgeShapeFunctions(g.points[q]);
      const Eigen::Vector2d t = x * EdgeShapeDerivatives(g.points[q]);
      const double jac = t.norm();
      const Eigen::Vector2d normal(t.y() / jac, -t.x() / jac);
      const Eigen::Vector2d p = traction(x * n, normal);
      for (int a = 0; a < 3; ++a) {
        const Eigen::Vector2d fa = (g.weights[q] * n(a) * jac * material_.thickness) * p;
        (*f)(Dof(edge.nodes[a], 0)) += fa.x();
        (*f)(Dof(edge.nodes[a], 1)) += fa.y();
      }
    }
  }
}

Eigen::MatrixXd LinearElasticModel::SolveMany(const Eigen::MatrixXd& f) const {
  RequireFactorized();
  if (f.rows() != num_dofs()) {
    throw std::invalid_argument("LinearElasticModel::Solve: load vectors have " +
                                std::to_string(f.rows()) +
                                " rows; the rule is num_dofs() = " + std::to_string(num_dofs()));
  }
  const int nf = num_free_dofs();
  const int nc = static_cast<int>(constrained_dofs_.size());
  const Eigen::Index m = f.cols();
  Eigen::VectorXd uc(nc);
  for (int i = 0; i < nc; ++i) uc(i) = prescribed_[constrained_dofs_[i]];
  const Eigen::VectorXd kuc = k_fc_ * uc;
  Eigen::MatrixXd u(num_dofs(), m);
  for (int i = 0; i < nc; ++i) u.row(constrained_dofs_[i]).setConstant(uc(i));
  if (m == 1) {
    Eigen::VectorXd rhs(nf);
    for (int i = 0; i < nf; ++i) rhs(i) = f(free_dofs_[i], 0) - kuc(i);
    const Eigen::VectorXd uf = ldlt_.solve(rhs);
    for (int i = 0; i < nf; ++i) u(free_dofs_[i], 0) = uf(i);
    return u;
  }
  // Eigen's solve runs the two sparse triangular sweeps once per column, streaming the whole
  // factor from memory each time. Here each sweep reads L once for all columns: the right-hand
  // sides are held row-major so that every update L(i,j)·y_j is one contiguous row operation.
  // P K_ff Pᵀ = L D Lᵀ, L unit lower triangular stored by columns without its diagonal; the
  // permuted right-hand side is gathered straight from f and scattered straight into u (one
  // working copy).
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const auto& l = ldlt_.matrixL().nestedExpression();
  const auto& p = ldlt_.permutationP().indices();
  const Eigen::VectorXd& d = ldlt_.vectorD();
  RowMajor y(nf, m);
  for (int i = 0; i < nf; ++i) y.row(p(i)) = f.row(free_dofs_[i]).array() - kuc(i);
  const auto* outer = l.outerIndexPtr();
  const auto* inner = l.innerIndexPtr();
  const double* value = l.valuePtr();
  for (Eigen::Index j = 0; j < nf; ++j) {  // L z = P b
    for (auto k = outer[j]; k < outer[j + 1]; ++k) y.row(inner[k]) -= value[k] * y.row(j);
  }
  for (Eigen::Index j = 0; j < nf; ++j) y.row(j) /= d(j);  // D w = z
  for (Eigen::Index j = nf - 1; j >= 0; --j) {             // Lᵀ v = w
    for (auto k = outer[j]; k < outer[j + 1]; ++k) y.row(j) -= value[k] * y.row(inner[k]);
  }
  for (int i = 0; i < nf; ++i) u.row(free_dofs_[i]) = y.row(p(i));  // u_f = Pᵀ v
  return u;
}

Eigen::VectorXd LinearElasticModel::Solve(const Eigen::VectorXd& f) const {
  return SolveMany(f).col(0);
}

Eigen::VectorXd LinearElasticModel::Reactions(const Eigen::VectorXd& u,
                                              const Eigen::VectorXd& f) const {
  return k_ * u - f;
}

Eigen::Vector2d LinearElasticModel::NodeDisplacement(const Eigen::VectorXd& u, int node) const {
  return {u(Dof(node, 0)), u(Dof(node, 1))};
}

Eigen::Vector2d LinearElasticModel::EdgeDisplacement(const Eigen::VectorXd& u,
                                                     const std::string& set,
                                                     const EdgePoint& at) const {
  mesh_.EdgePosition(set, at);  // validates
  const BoundaryEdge& edge = mesh_.EdgeSet(set)[at.edge];
  const Eigen::Vector3d n = EdgeShapeFunctions(at.xi);
  Eigen::Vector2d r = Eigen::Vector2d::Zero();
  for (int a = 0; a < 3; ++a) r += n(a) * NodeDisplacement(u, edge.nodes[a]);
  return r;
}

ElementPoint LinearElasticModel::LocatePoint(const Eigen::Vector2d& x) const {
  constexpr double kInside = 1e-9;
  for (int e = 0; e < mesh_.num_elements(); ++e) {
    const Q8Coordinates c = mesh_.ElementCoordinates(e);
    const Eigen::Vector2d lo = c.rowwise().minCoeff();
    const Eigen::Vector2d hi = c.rowwise().maxCoeff();
    const double pad = 0.25 * (hi - lo).maxCoeff();  // curved sides may bulge past the nodes
    if ((x.array() < lo.array() - pad).any() || (x.array() > hi.array() + pad).any()) continue;
    Eigen::Vector2d xi = Eigen::Vector2d::Zero();
    for (int it = 0; it < 50; ++it) {
      const Eigen::Matrix2d j = Q8ShapeDerivatives(xi.x(), xi.y()) * c.transpose();
      const Eigen::Vector2d r = x - Q8Position(c, xi.x(), xi.y());
      const Eigen::Vector2d step = j.transpose().fullPivLu().solve(r);
      xi = (xi + step).cwiseMax(-2.0).cwiseMin(2.0);
      if (step.norm() < 1e-14) break;
    }
    if (xi.cwiseAbs().maxCoeff() <= 1.0 + kInside &&
        (Q8Position(c, xi.x(), xi.y()) - x).norm() <= 1e-9 * (hi - lo).norm()) {
      return ElementPoint{e, std::clamp(xi.x(), -1.0, 1.0), std::clamp(xi.y(), -1.0, 1.0)};
    }
  }
  std::ostringstream msg;
  msg.precision(9);
  msg << "LocatePoint: the point (" << x.x() << ", " << x.y() << ") m lies in no element";
  throw std::invalid_argument(msg.str());
}

Eigen::Vector2d LinearElasticModel::Displacement(const Eigen::VectorXd& u,
                                                 const ElementPoint& at) const {
  const Eigen::Matrix<double, kQ8Nodes, 1> n = Q8ShapeFunctions(at.xi, at.eta);
  Eigen::Vector2d r = Eigen::Vector2d::Zero();
  for (int a = 0; a < kQ8Nodes; ++a) r += n(a) * NodeDisplacement(u, mesh_.elements[at.element][a]);
  return r;
}

Eigen::Vector2d LinearElasticModel::DisplacementAtDepth(const Eigen::VectorXd& u,
                                                        const std::string& set, const EdgePoint& at,
                                                        double depth) const {
  if (!std::isfinite(depth) || depth < 0.0) {
    std::ostringstream msg;
    msg << "DisplacementAtDepth: depth = " << depth << " m on edge set '" << set
        << "': the rule is a finite depth >= 0";
    throw std::invalid_argument(msg.str());
  }
  if (depth == 0.0) return EdgeDisplacement(u, set, at);
  const Eigen::Vector2d x = mesh_.EdgePosition(set, at) - depth * mesh_.EdgeNormal(set, at);
  return Displacement(u, LocatePoint(x));
}

Eigen::Vector3d LinearElasticModel::Stress(const Eigen::VectorXd& u, const ElementPoint& at) const {
  const auto b = Q8StrainDisplacement(mesh_.ElementCoordinates(at.element), at.xi, at.eta, nullptr);
  Eigen::Matrix<double, 2 * kQ8Nodes, 1> ue;
  for (int a = 0; a < kQ8Nodes; ++a) {
    ue.segment<2>(2 * a) = NodeDisplacement(u, mesh_.elements[at.element][a]);
  }
  return material_.ElasticityMatrix() * (b * ue);
}

ElementPoint LinearElasticModel::EdgeElementPoint(const std::string& set,
                                                  const EdgePoint& at) const {
  const std::vector<BoundaryEdge>& edges = mesh_.EdgeSet(set);
  if (at.edge < 0 || at.edge >= static_cast<int>(edges.size()))
    throw std::invalid_argument("elastic model: edge " + std::to_string(at.edge) +
                                " outside edge set '" + set + "'");
  const BoundaryEdge& edge = edges[static_cast<std::size_t>(at.edge)];
  const auto& element = mesh_.elements[static_cast<std::size_t>(edge.element)];
  for (int side = 0; side < 4; ++side) {
    const auto& local = kQ8Sides[static_cast<std::size_t>(side)];
    if (element[local[0]] != edge.nodes[0] || element[local[1]] != edge.nodes[1] ||
        element[local[2]] != edge.nodes[2])
      continue;
    // The side runs from local node local[0] to local[2]; ξ_edge = ±1 at its ends.
    const auto& a = kQ8NodeXiEta[local[0]];
    const auto& b = kQ8NodeXiEta[local[2]];
    const double w = 0.5 * (1.0 + at.xi);
    return ElementPoint{edge.element, a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])};
  }
  throw std::invalid_argument("elastic model: edge " + std::to_string(at.edge) + " of set '" + set +
                              "' is not a side of its element " + std::to_string(edge.element));
}

std::vector<std::pair<int, double>> LinearElasticModel::SurfaceStressFunctional(
    const std::string& set, const EdgePoint& at) const {
  const ElementPoint p = EdgeElementPoint(set, at);
  const auto b = Q8StrainDisplacement(mesh_.ElementCoordinates(p.element), p.xi, p.eta, nullptr);
  const Eigen::Vector2d n = mesh_.EdgeNormal(set, at);
  const Eigen::Vector2d t(-n.y(), n.x());
  // σ_tt = tᵀσt = (t_x², t_y², 2 t_x t_y) · (σxx, σyy, τxy), σ = D B u_e.
  const Eigen::RowVector3d project(t.x() * t.x(), t.y() * t.y(), 2.0 * t.x() * t.y());
  const Eigen::Matrix<double, 1, 2 * kQ8Nodes> row = project * material_.ElasticityMatrix() * b;
  std::vector<std::pair<int, double>> out;
  for (int a = 0; a < kQ8Nodes; ++a)
    for (int c = 0; c < 2; ++c)
      out.emplace_back(Dof(mesh_.elements[p.element][a], c), row(2 * a + c));
  return out;
}

double LinearElasticModel::SurfaceStress(const Eigen::VectorXd& u, const std::string& set,
                                         const EdgePoint& at) const {
  double sigma = 0.0;
  for (const auto& [dof, coefficient] : SurfaceStressFunctional(set, at))
    sigma += coefficient * u(dof);
  return sigma;
}

}  // namespace epicycle::compliance
