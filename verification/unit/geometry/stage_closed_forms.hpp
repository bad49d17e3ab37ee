// Closed forms of the stage's meshes written out for the tests, independently of the library:
// operating pressure angles at the carrier radius and the directions of the lines of action.
//
// For a pair (A external; B external, or B the ring with A inside) meshing on A's flank side σ_A,
// let u be the unit vector from A's centre to B's (external) or from the ring's centre to A's
// (internal), u⊥ = u turned +90°, and cos α_w = (r_bA + r_bB)/a (external) or (r_bB − r_bA)/a
// (internal). The flank normal σ_A e⊥(β) of an involute at its base-circle tangency point β
// gives the line of action's moment about A's centre, cross(N − c_A, d) = σ_A r_bA; the mate's
// base circle lies on the other side of the line (external: cross(N − c_B, d) = −σ_A r_bB) or on
// the same side (internal: +σ_A r_bB). So cross(D, d) = σ_A (r_bA ± r_bB) for D = c_B − c_A
// (external) or c_A − c_ring (internal), and, as d leaves A towards B (external) or outwards
// towards the ring (internal), d·u = sin α_w > 0:
//     d = sin α_w u + σ_A cos α_w u⊥.
// The overlap is measured along d from A's flank into B: moving B by v changes it by −v·d (to
// first order), moving A by v by +v·d.
#pragma once

#include <cmath>

#include "epicycle/geometry/stage.hpp"

namespace epicycle::test {

/// α_w of planet meshes of kind `kind` at the stage's carrier radius, with r_b = m z cos α / 2.
inline double ClosedFormPressureAngle(const geometry::Stage& st, geometry::MeshKind kind) {
  const geometry::GearSpec& s = st.spec().sun;
  const double rb_per_tooth = 0.5 * s.module * std::cos(s.pressure_angle);
  const double zs = s.teeth, zp = st.spec().planet.teeth, zr = st.spec().ring.teeth;
  const double sum =
      kind == geometry::MeshKind::kSunPlanet ? rb_per_tooth * (zs + zp) : rb_per_tooth * (zr - zp);
  return std::acos(sum / st.carrier_radius());
}

/// The line-of-action direction d = sin α_w u + σ_A cos α_w u⊥ of a mesh of the planet at
/// nominal position angle ψ (carrier angle plus the planet's angle on the carrier).
inline geometry::Vec2 ClosedFormLoaDirection(const geometry::Stage& st, geometry::MeshKind kind,
                                             int side_a, double psi) {
  const double aw = ClosedFormPressureAngle(st, kind);
  return std::sin(aw) * geometry::Dir(psi) + side_a * std::cos(aw) * geometry::DirPerp(psi);
}

/// Bound of the second-order remainder of the overlap change when the centre vector D of a mesh
/// moves by v: in the polar coordinates (a, γ) of D the overlap is ±(r_bA ± r_bB) γ
/// ± (L(a) − (r_bA ± r_bB) α_w(a)), L = a sin α_w, whose Hessian in D is bounded by
/// (cos α_w + cos²α_w/sin α_w + sin α_w)/a ≤ (2 + 1/sin α_w)/a; the remainder is below half of
/// that times |v|². Returned: twice the bound (the Hessian varies along the step).
inline double SecondOrderBound(const geometry::Stage& st, geometry::MeshKind kind, double v2) {
  const double aw = ClosedFormPressureAngle(st, kind);
  return (2 + 1 / std::sin(aw)) * v2 / st.carrier_radius();
}

}  // namespace epicycle::test
