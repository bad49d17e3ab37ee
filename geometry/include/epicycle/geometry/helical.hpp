// Helical gears and stages on the spur generator (docs/geometry.md, "Helical gears";
// docs/model.md §3): the transverse section of a helical gear is the spur profile its transverse
// rack generates, every other section that profile turned by its lead; a mesh's working
// quantities (α_wt, β_w, ε_α, ε_β, ε_γ) and the axial forces its inclined contact lines put on the
// gears, with the tilting moment they make on each planet. All lengths in metres, angles in
// radians, forces in newtons.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/geometry/gear.hpp"
#include "epicycle/geometry/helix.hpp"
#include "epicycle/geometry/stage.hpp"

namespace epicycle::geometry {

using Vec3 = Eigen::Vector3d;

/// The spec the spur generator takes for a gear given in the normal section: `normal` holds m_n,
/// α_n, x_n (and a shaper cutter's x_n) with its helix set; the result holds m_t, α_t, x_t
/// (Transverse) and keeps every length as it is (tip, root and hub radii, the rack's addendum and
/// dedendum: heights are the same in both sections). The rack's tip round keeps its radius ρ_a0:
/// its transverse section is an ellipse of semi-axes ρ_a0 (depth) and ρ_a0 / cos β (along the
/// pitch line), which the generator takes as the circle of radius ρ_a0 (the fillet's departure
/// is below ρ_a0 (1/cos β − 1): 0.9 % of ρ_a0 at β = 7.5°). Tooth-thickness errors and reliefs
/// stay normal to the flank in the transverse section. β = 0: `normal` unchanged.
GearSpec TransverseSpec(GearSpec normal);

/// m_n = m_t cos β of a gear made from a TransverseSpec [m].
double NormalModule(const Gear& gear);

/// The turn of the transverse section at axial position z [m] from the section z = 0 [rad]:
///   Δθ(z) = ± (2 tan β / d) z   (+ right hand, − left hand; 0 for a spur gear).
double SectionTurn(const Gear& gear, double z);

/// A point of a gear's tooth surface in its body frame (z along the axis, z = 0 the section the
/// spur profile describes): the transverse profile's point `p` (body frame) in the section at z,
/// (R(Δθ(z)) p, z) [m].
Vec3 SurfacePoint(const Gear& gear, const Vec2& p, double z);

/// The working quantities of one helical mesh (ISO 21771:2007), beside its MeshSummary.
struct HelicalMesh {
  std::string name;                     ///< the MeshSummary's name
  double face_width = 0;                ///< b, the common face width [m]
  double transverse_module = 0;         ///< m_t [m]
  double normal_module = 0;             ///< m_n [m]
  double helix_angle = 0;               ///< β [rad]
  double base_helix_angle = 0;          ///< β_b [rad]
  double working_pressure_angle = 0;    ///< α_wt [rad] (the MeshSummary's pressure_angle)
  double working_helix_angle = 0;       ///< β_w [rad]
  double transverse_contact_ratio = 0;  ///< ε_α from the tip circles [-]
  double overlap_ratio = 0;             ///< ε_β [-]
  double total_contact_ratio = 0;       ///< ε_γ = ε_α + ε_β [-]
};
/// The helical quantities of mesh `m` of gears g1, g2 (a MeshSummary of them).
HelicalMesh SummariseHelicalMesh(const MeshSummary& m, const Gear& g1, const Gear& g2);

/// Forces of a helical mesh with the stage's input torque shared equally among the planets, and
/// the moment they put on a planet. The normal force on the base plane has the transverse part
/// F_bt = |T_s| / (n r_b,sun) (the same on a planet's two meshes: its rotation balances them) and
/// the axial part F_bt tan β_b; at the working pitch cylinder F_t = F_bt cos α_wt and
/// F_a = F_t tan β_w (the same F_a). On the gear whose flank σ carries the load, the axial force
/// is σ h F_bt tan β_b along +z (h = +1 right hand, −1 left): the outward normal of flank σ of a
/// gear of hand h has the axial part −σ h sin β_b. A planet's two meshes push on opposite flanks,
/// so their axial forces are opposite; acting at the two operating pitch points, a diameter
/// apart, they tilt the planet about its tangential axis e_t = (−sin ψ_i, cos ψ_i):
///   M_t = F_a,sun (r_w,planet|sun + r_w,planet|ring)   (F_a,sun the sun mesh's force on the
///   planet)
/// with no net axial force on the planet (the radial-axis part from the contact's position along
/// the path of contact is left out: zero when the path is centred on the pitch point).
struct MeshAxialLoad {
  std::string name;                  ///< "sun-planet1", "planet1-ring"
  double transverse_force = 0;       ///< F_t at the working pitch cylinder [N]
  double base_transverse_force = 0;  ///< F_bt on the base plane [N]
  double axial_force = 0;            ///< |F_a| = F_t tan β_w [N]
  double axial_on_planet = 0;        ///< F_a on the planet along +z (signed) [N]
  double planet_arm = 0;             ///< r_w of the planet in this mesh, its lever arm [m]
};
struct PlanetTilt {
  int planet = 0;              ///< 0-based
  double tilting_moment = 0;   ///< M_t about e_t [N·m] (signed)
  double net_axial_force = 0;  ///< F_a,sun + F_a,ring on the planet [N] (0)
};
struct StageAxialLoads {
  std::vector<MeshAxialLoad> meshes;  ///< in Stage::meshes() order
  std::vector<PlanetTilt> planets;
  double sun_axial_force = 0;   ///< Σ of the sun meshes' axial forces on the sun, along +z [N]
  double ring_axial_force = 0;  ///< the same on the ring [N]
};
/// @throws std::invalid_argument for a zero or non-finite torque.
StageAxialLoads AxialLoads(const Stage& stage, double sun_torque);

/// Checks the helices of a mesh of gears named in `g1`, `g2` (external, or internal with g2 the
/// internal gear): the same β, opposite hands (external) or the same hand (internal).
/// @throws std::invalid_argument "<g2>.helix_angle_deg = ...: must equal <g1>'s ..." or
///         "<g2>.hand = ...: ..." naming the rule.
void CheckMeshHelices(const GearSpec& g1, const GearSpec& g2, bool internal);

}  // namespace epicycle::geometry
