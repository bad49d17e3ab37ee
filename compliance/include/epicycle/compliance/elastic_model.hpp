// Linear elastic FE model of one 2D body: assembly of Q8 elements into a sparse stiffness,
// Dirichlet constraints by elimination, one sparse LDLᵀ factorisation, many right-hand sides.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "epicycle/compliance/material.hpp"
#include "epicycle/compliance/mesh.hpp"

namespace epicycle::compliance {

/// Which displacement components a constraint acts on.
enum class Components { kX, kY, kXY };

/// A point inside an element: element index and reference coordinates (ξ, η) ∈ [−1, 1]².
struct ElementPoint {
  int element = -1;  ///< element index
  double xi = 0.0;   ///< ξ [-]
  double eta = 0.0;  ///< η [-]
};

/// The discrete problem K u = f of linear elasticity on a Q8 mesh:
///
///   K = Σ_e b ∫∫ Bᵀ D B det J dξ dη   (3×3 Gauss, see q8_element.hpp), DOF 2·node + {0: x, 1: y}
///
/// Constrained DOFs c (prescribed u_c) are eliminated: K_ff u_f = f_f − K_fc u_c. K_ff is
/// symmetric positive definite once rigid-body motion is removed; it is factorised once with
/// Eigen::SimplicialLDLT (sparse LDLᵀ, AMD fill-reducing ordering), after which each load case
/// costs two sparse triangular solves. LDLᵀ rather than LLᵀ because its pivots D_kk expose a
/// missing constraint as a near-zero pivot (checked, see Factorize) instead of a silent result.
///
/// Loads are full-length vectors f [N] (num_dofs()); displacements are full-length u [m] with the
/// prescribed values in place.
class LinearElasticModel {
 public:
  /// Validates material and mesh (Mesh::Validate, including every element's Jacobian) and
  /// assembles K. @throws std::invalid_argument on bad input (message names the item and rule).
  LinearElasticModel(Mesh mesh, const ElasticMaterial& material);

  const Mesh& mesh() const { return mesh_; }
  const ElasticMaterial& material() const { return material_; }
  int num_dofs() const { return 2 * mesh_.num_nodes(); }
  /// Number of unconstrained DOFs (after the last Factorize).
  int num_free_dofs() const { return static_cast<int>(free_dofs_.size()); }
  /// Global stiffness K [N/m], all DOFs (constraints not applied).
  const Eigen::SparseMatrix<double>& stiffness() const { return k_; }
  /// Non-zeros of the factor L (after Factorize), a measure of fill and memory.
  long factor_nonzeros() const;
  /// DOF index of (node, component), component 0 = x, 1 = y.
  static int Dof(int node, int component) { return 2 * node + component; }

  /// u = 0 on the named node set (components `which`). Invalidates the factorisation.
  /// @throws std::invalid_argument if the set does not exist.
  void FixNodeSet(const std::string& set, Components which = Components::kXY);
  /// u = g(x) [m] on the named node set (components `which`), x the node position [m].
  void PrescribeNodeSet(const std::string& set,
                        const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& g,
                        Components which = Components::kXY);
  /// u_component(node) = value [m]. @throws std::invalid_argument for a bad node or component.
  void PrescribeDof(int node, int component, double value);
  /// Removes all constraints. Invalidates the factorisation.
  void ClearConstraints();

  /// Eliminates the constrained DOFs and factorises K_ff.
  /// @throws std::invalid_argument if no DOF is free, or if K_ff is singular: a pivot
  ///         D_kk ≤ kSingularPivot · K_kk (rigid-body motion left free); the message names the
  ///         node and component of that pivot.
  void Factorize();
  static constexpr double kSingularPivot = 1e-12;
  bool factorized() const { return factorized_; }

  /// A zero load vector of length num_dofs() [N].
  Eigen::VectorXd ZeroLoads() const { return Eigen::VectorXd::Zero(num_dofs()); }
  /// f += force [N] at a node.
  void AddNodalForce(int node, const Eigen::Vector2d& force, Eigen::VectorXd* f) const;
  /// A point force [N] at a point of an edge set, distributed consistently by the edge shape
  /// functions: f_a += N_a(ξ) · force for the edge's three nodes (the work-equivalent loads of a
  /// concentrated force; exactly the nodal force when the point is a node).
  void AddEdgePointForce(const std::string& set, const EdgePoint& at, const Eigen::Vector2d& force,
                         Eigen::VectorXd* f) const;
  /// Traction t(x, n) [Pa] on an edge set (n the outward unit normal), consistent nodal loads
  ///   f_a += b ∫ N_a(ξ) t(x(ξ), n(ξ)) |dx/dξ| dξ
  /// with `gauss_points` Gauss points per edge (1..5; 5 integrates a quadratic traction times the
  /// quadratic shape functions and a curved edge's |dx/dξ| to high accuracy).
  using TractionField =
      std::function<Eigen::Vector2d(const Eigen::Vector2d& x, const Eigen::Vector2d& normal)>;
  void AddEdgeTraction(const std::string& set, const TractionField& traction, Eigen::VectorXd* f,
                       int gauss_points = 5) const;

  /// Displacements u [m] for one load vector f [N]. @throws std::invalid_argument if not
  /// factorised or f has the wrong length.
  Eigen::VectorXd Solve(const Eigen::VectorXd& f) const;
  /// Displacements for many load cases at once: column j of the result answers column j of f.
  Eigen::MatrixXd SolveMany(const Eigen::MatrixXd& f) const;
  /// Reactions r = K u − f [N] (non-zero only at constrained DOFs, up to round-off).
  Eigen::VectorXd Reactions(const Eigen::VectorXd& u, const Eigen::VectorXd& f) const;

  /// Displacement [m] of a node.
  Eigen::Vector2d NodeDisplacement(const Eigen::VectorXd& u, int node) const;
  /// Displacement [m] at a point of an edge set, u(ξ) = Σ N_a(ξ) u_a over the edge's nodes.
  Eigen::Vector2d EdgeDisplacement(const Eigen::VectorXd& u, const std::string& set,
                                   const EdgePoint& at) const;
  /// The element and (ξ, η) holding a point x [m] (inverse isoparametric map by Newton).
  /// @throws std::invalid_argument if no element contains x.
  ElementPoint LocatePoint(const Eigen::Vector2d& x) const;
  /// Displacement [m] at any point of an element, u = Σ N_a(ξ, η) u_a.
  Eigen::Vector2d Displacement(const Eigen::VectorXd& u, const ElementPoint& at) const;
  /// Displacement [m] at depth `depth` [m] ≥ 0 below a point of an edge set, i.e. at
  /// x(ξ) − depth · n(ξ) with n the outward normal: the read-out of the join between the FE
  /// structural term and the local contact term (docs/model.md §4).
  /// @throws std::invalid_argument for a negative or non-finite depth, or a point outside the body.
  Eigen::Vector2d DisplacementAtDepth(const Eigen::VectorXd& u, const std::string& set,
                                      const EdgePoint& at, double depth) const;
  /// In-plane stress (σxx, σyy, τxy) [Pa] = D B(ξ, η) u_e at a point of an element. (Plane strain
  /// also carries σzz = ν(σxx + σyy).)
  Eigen::Vector3d Stress(const Eigen::VectorXd& u, const ElementPoint& at) const;
  /// The point of the edge's own element at a point of an edge set (the side's local coordinate
  /// mapped to (ξ, η) of that element). @throws std::invalid_argument if the edge is not a side of
  /// its element.
  ElementPoint EdgeElementPoint(const std::string& set, const EdgePoint& at) const;
  /// Surface tangential stress σ_tt = tᵀ σ t [Pa] at a point of an edge set, t the unit tangent of
  /// the edge there, σ from the edge's own element (Stress at EdgeElementPoint). On a free surface
  /// (σ·n = 0) it is the in-plane principal stress that is not zero, the stress a root fillet is
  /// rated by; in plane strain |σzz| = ν|σ_tt| is smaller.
  double SurfaceStress(const Eigen::VectorXd& u, const std::string& set, const EdgePoint& at) const;
  /// SurfaceStress as a linear functional of the displacements: σ_tt = Σ coefficient · u[dof]
  /// over the pairs (dof, coefficient [Pa/m]) returned, for many displacement fields at once.
  std::vector<std::pair<int, double>> SurfaceStressFunctional(const std::string& set,
                                                              const EdgePoint& at) const;

 private:
  void RequireFactorized() const;

  Mesh mesh_;
  ElasticMaterial material_;
  Eigen::SparseMatrix<double> k_;
  std::vector<char> constrained_;      // per DOF
  std::vector<double> prescribed_;     // per DOF [m]
  std::vector<int> free_dofs_;         // free index → DOF
  std::vector<int> constrained_dofs_;  // constrained index → DOF
  Eigen::SparseMatrix<double> k_fc_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  bool factorized_ = false;
};

}  // namespace epicycle::compliance
