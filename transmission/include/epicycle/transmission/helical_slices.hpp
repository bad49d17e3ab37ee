// Helical meshes across the face width (docs/model.md §10, "Helical meshes in slices").
//
// Slice s of a mesh of width b sits at z_s = −b/2 + (s + ½) b/S (face_width.hpp). The transverse
// section of gear X at z is its spur section turned by Δθ_X(z) = ±(2 tan β/d_X) z
// (geometry::SectionTurn; + right hand). Every slice is therefore the plane model at its own
// poses: each gear's rotation grown by Δθ_X(z_s) about its own (geometric) axis. Its contacts are
// searched there (points, overlaps, levers, normals, all in the transverse plane), located on the
// flanks there, and carried back onto the section the poses describe for the FE compliance:
//   C(j^s, k^t) = C_plane(p_j^s, p_k^t) W_st   (W the coupling along the face, face_width.hpp),
// so a slice's contact and another slice's are coupled through the flank positions they really
// occupy. The gap of each slice changes by face_width.hpp's misalignment and lead terms.
//
// Local term per unit length of contact line. A slice of transverse width Δb = b/S holds a
// contact line of length Δb / cos β_b on the base plane. The plane model's unknown is the force
// F_t in the transverse plane along the transverse normal; the force normal to the flank is
// F_n = F_t / cos β_b, the normal-section curvature radii are ρ/cos β_b, and an approach u_n along
// the flank normal is an approach u_t = u_n / cos β_b along the transverse normal. The plane term
// u(F; b, R) = (2k/(πb)) F [asinh(h/L) − c/(1+w)], L² = 4FR/(πbE*), taken per unit length of line
// (F_n/(Δb/cos β_b) = F_t/Δb, L_n² = 4 F_t R/(π Δb E* cos β_b)) and projected, is
//   u_t(F_t) = u_n / cos β_b = u(F_t; Δb cos β_b, R):
// the transverse slice's plane term with the width Δb cos β_b (β = 0: Δb, the spur slice).
//
// Forces. The normal force on the base plane has the transverse part F_t (the solved contact
// force) and the axial part F_a = F_t tan β_b at the contact point. At the working pitch cylinder
// this is F_t,w tan β_w with F_t,w = F_t cos α_wt (tan β_w = tan β_b / cos α_wt): the same force.
// On the gear whose flank σ carries it, the axial force is σ h F_t tan β_b along +z (h = +1 right
// hand; geometry/helical.hpp). Each planet carries the axial forces of its two meshes, which
// balance, and their moment about its centre; the transverse forces at their slices' z add the
// moment of the load's shift along the face.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/damage.hpp"
#include "epicycle/transmission/face_width.hpp"
#include "epicycle/transmission/pair_face_width.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::transmission {

struct ContactTerms;
class RecordVisitor;

/// True when the stage's gears have a helix (β > 0).
bool IsHelicalStage(const geometry::Stage& stage);

/// cos β_b [-] of a mesh of gears a, b (their common base helix angle; 1 for spur gears): the
/// factor on a helical slice's local-term width (header).
double LocalWidthFactor(const geometry::Gear& a, const geometry::Gear& b);

/// The contact terms of a helical stage at `poses` (header): every slice searched at its own
/// turned poses, its gap changed by `faces`' misalignment and lead terms and lowered by the pits
/// of `damage` covering its centre, the compliance of every pair of slices' contacts with `faces`'
/// coupling. The local terms are left to the caller (ContactLocalTerm with LocalWidthFactor).
/// Outcomes as StageModel::Terms.
[[nodiscard]] StageOutcome HelicalSliceTerms(const geometry::Stage& stage,
                                             const StageCompliance& compliance,
                                             const FaceWidthModel& faces,
                                             const DamageModel& damage,
                                             const geometry::StagePoses& poses, double gap_window,
                                             ContactTerms* terms);

/// A helical gear pair's contacts in slices (the pair driver's, pair_face_width.hpp): slice s's
/// contacts searched with gear 1 and gear 2 turned by Δθ_1(z_s), Δθ_2(z_s) (as a stage's slices
/// above), in slice order, each with its gap changed by `faces`' lead terms (GapChange).
struct PairSliceContacts {
  std::vector<geometry::PotentialContact> contacts;
  std::vector<int> slice;                           ///< each contact's slice s [-]
  std::vector<std::array<double, 2>> section_turn;  ///< each contact's Δθ_1, Δθ_2 [rad]
};
/// @throws std::invalid_argument for faces without slices.
PairSliceContacts HelicalPairSlices(const geometry::GearPair& pair, const PairFaceWidth& faces,
                                    const geometry::PairPoses& poses,
                                    const geometry::ContactSearchOptions& search);

/// The axial forces and tilting moments of one planet.
struct PlanetHelicalLoad {
  int planet = 0;              ///< 0-based
  double axial_force = 0;      ///< Σ of its meshes' axial forces on it, along +z [N] (≈ 0)
  double sun_mesh_axial = 0;   ///< the sun mesh's axial force on it, along +z [N]
  double ring_mesh_axial = 0;  ///< the ring mesh's axial force on it, along +z [N]
  /// Moment of the axial forces about the planet's centre, in the carrier frame: about the
  /// radial axis (outward) and the tangential axis (counter-clockwise) [N·m].
  double axial_moment_radial = 0, axial_moment_tangential = 0;
  /// The whole tilting moment on the pin: the axial forces' and that of the transverse forces at
  /// their slices' z [N·m], about the same axes.
  double moment_radial = 0, moment_tangential = 0;
};

/// The axial loads of a helical stage's state.
struct HelicalLoads {
  std::vector<PlanetHelicalLoad> planets;
  double sun_axial_force = 0;      ///< on the sun, along +z [N] (to its bearings)
  double ring_axial_force = 0;     ///< on the ring, along +z [N]
  double carrier_axial_force = 0;  ///< Σ of the planets', to the carrier's bearings [N]
};

/// A field of the axial loads: its record name without the unit, its unit, where it is.
template <typename T>
struct HelicalField {
  const char* name;
  const char* unit;
  double T::* value;
};
/// The stage's members' fields, in the record's order.
inline constexpr std::array<HelicalField<HelicalLoads>, 3> kHelicalMemberFields{{
    {"sun_axial_force", "N", &HelicalLoads::sun_axial_force},
    {"ring_axial_force", "N", &HelicalLoads::ring_axial_force},
    {"carrier_axial_force", "N", &HelicalLoads::carrier_axial_force},
}};
/// A planet's fields, in the record's order.
inline constexpr std::array<HelicalField<PlanetHelicalLoad>, 7> kPlanetHelicalFields{{
    {"sun_mesh_axial_force", "N", &PlanetHelicalLoad::sun_mesh_axial},
    {"ring_mesh_axial_force", "N", &PlanetHelicalLoad::ring_mesh_axial},
    {"axial_force", "N", &PlanetHelicalLoad::axial_force},
    {"axial_tilting_moment_radial", "Nm", &PlanetHelicalLoad::axial_moment_radial},
    {"axial_tilting_moment_tangential", "Nm", &PlanetHelicalLoad::axial_moment_tangential},
    {"tilting_moment_radial", "Nm", &PlanetHelicalLoad::moment_radial},
    {"tilting_moment_tangential", "Nm", &PlanetHelicalLoad::moment_tangential},
}};

/// The axial loads of the forces `force` [N] of the sliced contacts `contacts` of a helical
/// stage at `poses` (the planets' centres). Empty (no planets) for a spur stage.
HelicalLoads HelicalLoadsOf(const geometry::Stage& stage, const geometry::StagePoses& poses,
                            const std::vector<StageContact>& contacts, const Eigen::VectorXd& force);

/// sum += w · loads, field by field (`sum` sized to loads' planets when it has none): the means
/// over a sweep's positions or a run's steps.
void AddHelicalLoads(const HelicalLoads& loads, double w, HelicalLoads* sum);

/// The axial loads over a set of states (a speed sweep's window): field by field their mean and
/// their largest magnitude.
struct HelicalLoadRange {
  HelicalLoads mean;     ///< means [N], [N·m]
  HelicalLoads max_abs;  ///< largest |value| [N], [N·m]
  int count = 0;         ///< states added [-]
  /// Adds one state's loads (none for a spur stage: the range stays empty).
  void Add(const HelicalLoads& loads);
  /// The means of the states added (mean holds their sum until then).
  void Finish();
};

/// The record's `helical` object of `loads` (docs/records.md): that the axial and tilting motions
/// are held (the model's planar DOFs, docs/model.md §10), the axial forces [N] of the sun,
/// the ring and the carrier, and per planet its meshes' axial forces [N] and tilting moments
/// [N·m]; nothing for loads without planets (a spur stage).
void VisitHelicalLoads(RecordVisitor& visit, const HelicalLoads& loads);
/// The same object of a range: every field as <name>_mean_<unit> and <name>_max_abs_<unit>;
/// nothing for an empty range (a spur stage).
void VisitHelicalLoads(RecordVisitor& visit, const HelicalLoadRange& range);

}  // namespace epicycle::transmission
