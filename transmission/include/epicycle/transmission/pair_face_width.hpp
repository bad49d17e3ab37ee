// Slices of the face width of one gear pair (a pair scene's [face_width], docs/model.md §10): the
// stage model's slices without its bodies' axis slopes. Each contact j of the plane problem
// becomes S slices s of width b/S at z_s, with the gap
//   δ_js = δ_j − z_s (ℓ_1 h_1 + ℓ_2 h_2) − c_1(z_s) − c_2(z_s)
// (ℓ the levers of the unit force, h = f_Hβ/(b r_b) each gear's lead slope as a turn of its
// sections [rad/m], c the lead modifications: face_width.hpp) and the structural compliance
// C_jk W_st. The mesh-stiffness driver solves the sliced problem with the same equilibrium.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/transmission/face_width.hpp"

namespace epicycle::transmission {

class PairFaceWidth {
 public:
  PairFaceWidth() = default;
  /// `spec`'s leads name "gear1" and "gear2"; pin tilts and the carrier belong to stages.
  /// @throws std::invalid_argument for a lead of another gear, a pin tilt or a carrier stiffness.
  PairFaceWidth(const FaceWidthSpec& spec, const geometry::GearPair& pair);
  bool active() const { return slices_ > 1; }
  int slices() const { return slices_; }
  double width() const { return width_; }  ///< b [m], the narrower gear's

  /// The gap change [m] of slice s of a contact (the terms of the header's equation but δ_j).
  double GapChange(const geometry::PotentialContact& contact, int s) const;
  /// Splits `contacts` and their compliance into slices: contact j's slice s at j·S + s, its
  /// overlap changed by GapChange, the compliance C ⊗ W.
  void Expand(std::vector<geometry::PotentialContact>* contacts, Eigen::MatrixXd* compliance) const;
  /// The load per unit width w_s [N/m] across the face of forces F [N] of expanded contacts, with
  /// its K_Hβ and where the largest sits (SummariseLineLoad).
  MeshFaceLoad Loads(const Eigen::VectorXd& force) const;
  /// The same for contacts in any order, contact j in slice `slice[j]` (a helical pair's,
  /// HelicalPairSlices).
  MeshFaceLoad Loads(const Eigen::VectorXd& force, const std::vector<int>& slice) const;
  /// W [-], the coupling along the face (S × S; FaceCouplingMatrix).
  const Eigen::MatrixXd& coupling() const { return coupling_; }

 private:
  int slices_ = 1;
  double width_ = 0;
  struct GearLead {
    double slope = 0;  ///< h [rad/m]
    double crowning = 0, end_relief = 0, end_relief_length = 0, width = 0;
  };
  GearLead lead_[2];
  Eigen::MatrixXd coupling_;
};

}  // namespace epicycle::transmission
