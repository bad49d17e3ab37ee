// The slice model of the 3D full-FE reference's contact (docs/fe_reference.md, "3D reference
// across the face width"), shared by its crosscheck (crosscheck/transmission_face_width_fe3d.cpp)
// and its figure (`fe_reference fe3d-slices`): the ISO 20/40 pair at gear-1 angle 13.5°, tooth
// pair 19/21 alone, the plane model's structural compliance C and local term split into S slices
// across b (C ⊗ W, docs/model.md §10), the rigid gap g(z) = F_β (z/b − 1/2) of the reference's
// gear-2 tilt (z from the face that F_β > 0 loads), gear 1's moment balance.
//
// The reference's contact is one tooth pair at one pose under its own gap, not a scene's sweep,
// so the problem is built here through the library. One contact solve at the kinematic pose: gear
// 1's rotation (≈ 0.5 mrad) moves the contact ≈ 20 µm along a 12 mm path of contact, which changes
// C by a few 1e-4, below what the comparisons see.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "csv_rows.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::test {

/// The slices' answer: the line load per slice [N/m] and the mid-face approach δ = |θ| r_b1 [m].
struct SliceLoads {
  std::vector<double> line_load;
  double approach = 0;
  /// The means over `stations` equal stations [N/m] (S a multiple of it).
  std::vector<double> Stations(int stations) const {
    const int per = static_cast<int>(line_load.size()) / stations;
    std::vector<double> out(static_cast<std::size_t>(stations), 0.0);
    for (std::size_t s = 0; s < line_load.size(); ++s)
      out[s / static_cast<std::size_t>(per)] += line_load[s] / per;
    return out;
  }
};

/// The 3D structural compliance along the face as the slices' kernel (docs/fe_reference.md,
/// "The structural compliance along the face"): from the influence rows of `csv` (written by
/// `fe_reference fe3d --influence`), W_ij = G_ij / G_ps with G_ij [m/N] of case `name` at
/// `layers` layers and in-plane `refinement` and G_ps the one-layer plane-strain deck's compliance of the
/// same mesh and read-out (case "plane_strain"): the kernel relative to the plane model the
/// slices' C stands for, so that the deck's own in-plane discretisation error cancels; its
/// symmetric part.
/// @throws std::runtime_error when a row is missing.
inline Eigen::MatrixXd StructureKernel(const std::string& csv, const std::string& name,
                                       int layers, const std::string& refinement = "1") {
  Eigen::MatrixXd g = Eigen::MatrixXd::Constant(layers, layers, std::nan(""));
  double plane = 0;
  for (const auto& r : ReadCsvRows(csv)) {
    if (r.size() != 15 || r[4] != refinement) continue;
    if (r[0] == "plane_strain" && r[3] == "1") plane = std::stod(r[14]);
    if (r[0] == name && std::stoi(r[3]) == layers)
      g(std::stoi(r[10]), std::stoi(r[11])) = std::stod(r[14]);
  }
  if (!(plane > 0) || g.hasNaN())
    throw std::runtime_error(csv + ": no plane_strain row or an incomplete " + name + " at " +
                             std::to_string(layers) + " layers, refinement " + refinement);
  // Maxwell–Betti: G is symmetric but for the read-out's interpolation (0.3 % of the
  // largest entry on the ISO pair's deck); the slices take its symmetric part.
  return 0.5 * (g + g.transpose()) / plane;
}

class Fe3dSlicePair {
 public:
  /// `scene` the ISO 20/40 pair's (scenes/iso_pair_20_40.toml).
  Fe3dSlicePair(const transmission::Scene& scene, const transmission::FeComplianceOptions& tables)
      : scene_(scene),
        setup_(transmission::MakeMeshPair(scene_, nullptr, "")),
        pair_(setup_.spec),
        compliance_(scene_, pair_, tables),
        poses_(pair_.Poses(13.5 * geometry::kPi / 180.0)) {
    geometry::ContactSearchOptions search;
    search.gap_window = setup_.gap_window;
    int found = 0;
    for (const geometry::PotentialContact& c : pair_.Contacts(poses_, search))
      if (c.tooth_a == 19 && c.tooth_b == 21 && c.side_a == 1) {
        contact_ = c;
        ++found;
      }
    if (found != 1)
      throw std::runtime_error("fe3d slices: " + std::to_string(found) +
                               " contacts of tooth pair 19/21 at 13.5 deg: must be 1");
    structural_ = compliance_.Matrix(pair_, poses_, {contact_})(0, 0);
    const transmission::StageOutcome o = transmission::ContactLocalTerm(
        contact_, pair_.gear1(), pair_.gear2(), compliance_.material(), compliance_.plane(),
        compliance_.JoiningDepth(0), compliance_.JoiningDepth(1), "gear1-gear2 19/21", &local_);
    if (!o.ok()) throw std::runtime_error("fe3d slices: " + o.message);
  }
  double width() const { return pair_.gear1().spec().face_width; }  ///< b [m]
  double torque() const { return setup_.torque; }                   ///< on gear 1 [N·m]
  double base_radius() const { return pair_.gear1().base_radius(); }
  double structural() const { return structural_; }  ///< C [m/N]
  /// The plane model's joining depth h of gear 1 (0) or gear 2 (1) [m] (docs/model.md §4).
  double JoiningDepth(int gear) const { return compliance_.JoiningDepth(gear); }
  /// φ of the reference's contact (transmission::ContactBodyShare).
  double BodyShare() const {
    return transmission::ContactBodyShare(compliance_, pair_, poses_, contact_);
  }
  /// The slices under coupling `w` (S×S) and misalignment F_β [m].
  SliceLoads Solve(const Eigen::MatrixXd& w, double f_beta) const {
    const int n = static_cast<int>(w.rows());
    const double b = width();
    solvers::ContactProblemData d;
    d.compliance = structural_ * w;
    d.overlap.resize(n);
    d.equality_matrix.resize(1, n);
    d.equality_rhs = Eigen::VectorXd::Constant(1, setup_.torque);
    for (int s = 0; s < n; ++s) {
      const double z = (s + 0.5) * b / n;
      d.overlap(s) = contact_.overlap - f_beta * (z / b - 0.5);
      d.equality_matrix(0, s) = -contact_.lever_a;  // gear 1's balance, as the stiffness driver
      d.local.push_back(local_);
      d.local.back().face_width /= n;
    }
    const solvers::ContactProblem problem(d);
    auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
    solvers::ContactSolution solution;
    const solvers::ContactReport report =
        solver->Solve(problem, solvers::ContactOptions{}, &solution);
    if (report.status != solvers::ContactStatus::kConverged)
      throw std::runtime_error("fe3d slices: the contact solve ended " +
                               solvers::StatusName(report.status));
    SliceLoads out;
    for (int s = 0; s < n; ++s) out.line_load.push_back(solution.force(s) * n / b);
    out.approach = std::abs(solution.multiplier(0)) * base_radius();
    return out;
  }

 private:
  transmission::Scene scene_;
  transmission::MeshPairSetup setup_;
  geometry::GearPair pair_;
  transmission::FePairCompliance compliance_;
  geometry::PairPoses poses_;
  geometry::PotentialContact contact_;
  double structural_ = 0;
  solvers::LocalTermParameters local_;
};

}  // namespace epicycle::test
