// The planetary layout: sun, n planets on a carrier, fixed ring; assembly conditions, clashes,
// the meshes' operating data, mesh phasing, manufacturing and assembly errors, rigid kinematics.
#pragma once

#include <string>
#include <vector>

#include "epicycle/geometry/contact.hpp"
#include "epicycle/geometry/gear.hpp"

namespace epicycle::geometry {

/// Planet pin-hole position error in the carrier frame at the planet's nominal position
/// (time-invariant, assembly-independent).
struct PinError {
  double radial = 0;      ///< Δζ [m], outward
  double tangential = 0;  ///< Δη [m], counter-clockwise
};

/// Run-out (eccentricity): the geometric centre is offset from the rotation centre by e at phase
/// φ in the body frame, so it turns with the gear (time-varying, assembly-dependent).
struct Runout {
  double amplitude = 0;  ///< e [m], ≥ 0
  double phase = 0;      ///< φ [rad], in the gear's body frame
};

struct StageSpec {
  GearSpec sun, planet, ring;                   ///< planet: the spec shared by every planet
  int planets = 3;                              ///< n [-]
  double carrier_radius = 0;                    ///< a_c [m]
  std::vector<double> planet_angles;            ///< ψ_i [rad]; empty: equally spaced 2π(i−1)/n
  std::vector<PinError> pin_errors;             ///< n entries or empty
  std::vector<Runout> planet_runouts;           ///< n entries or empty
  std::vector<double> planet_thickness_errors;  ///< Δs_i [m], n entries or empty
  Runout sun_runout, ring_runout;
  int load_sign = -1;            ///< sign of the sun torque: which flanks carry the load
  double min_planet_gap = 1e-3;  ///< least gap between neighbouring planets' tip circles [m]
};

enum class MeshKind { kSunPlanet, kPlanetRing };

/// Index of planet i's mesh of `kind` in Stage::meshes(): 2i for the sun-planet mesh, 2i + 1 for
/// the planet-ring mesh (i 0-based) [-].
inline int MeshIndex(int planet, MeshKind kind) {
  return 2 * planet + (kind == MeshKind::kPlanetRing ? 1 : 0);
}
/// Name of planet i's mesh of `kind` (i 0-based): "sun-planet<i+1>" or "planet<i+1>-ring".
std::string MeshName(int planet, MeshKind kind);

/// Operating data of one mesh at the nominal (error-free) carrier radius.
struct MeshSummary {
  MeshKind kind = MeshKind::kSunPlanet;
  int planet = 0;                           ///< 0-based planet index
  std::string name;                         ///< "sun-planet1", "planet1-ring"
  double centre_distance = 0;               ///< a [m]
  double pressure_angle = 0;                ///< α_w at a [rad]
  double zero_backlash_pressure_angle = 0;  ///< α_w of the same shifts at zero backlash [rad]
  double normal_backlash = 0;               ///< j_n [m] (closed form)
  double transverse_backlash = 0;           ///< j_wt = j_n / cos α_w [m]
  double contact_ratio_iso = 0;             ///< ε_α from the tip circles [-]
  double contact_ratio = 0;                 ///< ε_α of the involutes present (tip-form radii) [-]
  double sap_a = 0, sap_b = 0;              ///< radii where the mate's tip starts the contact [m]
  double phase = 0;                         ///< mesh phase relative to planet 1, in [0, 1) cycles
};

/// Operating data of the mesh of g1 with g2 at centre distance a (internal: g2 the ring).
MeshSummary SummariseMesh(const Gear& g1, const Gear& g2, bool internal, double a);
/// Tips against roots and fillets of one mesh. @throws std::invalid_argument naming `owner`.
void CheckMesh(const Gear& g1, const Gear& g2, bool internal, double a, const std::string& owner);

/// Rigid poses of every member at one carrier angle.
struct StagePoses {
  double carrier_angle = 0;  ///< [rad]
  GearPose sun, ring;
  std::vector<GearPose> planets;
};

class Stage {
 public:
  /// @throws std::invalid_argument on gears that cannot be made, planets that clash or cannot be
  ///         assembled, tips that hit roots or fillets, error vectors of the wrong size.
  explicit Stage(StageSpec spec);

  const StageSpec& spec() const { return spec_; }
  const Gear& sun() const { return sun_; }
  const Gear& ring() const { return ring_; }
  const Gear& planet(int i) const { return planets_.at(i); }
  int planets() const { return static_cast<int>(planets_.size()); }
  double planet_angle(int i) const { return angles_.at(i); }
  double carrier_radius() const { return spec_.carrier_radius; }
  const std::vector<MeshSummary>& meshes() const { return meshes_; }  ///< per planet: sun, ring
  /// Loaded flank sides: sun mesh (sun side, planet side = same) and ring mesh (planet side; ring
  /// side = −planet side).
  int sun_mesh_side() const { return spec_.load_sign; }
  int ring_mesh_planet_side() const { return -spec_.load_sign; }
  /// Carrier rotation of one mesh cycle, 2π/z_r [rad] (ring fixed).
  double mesh_cycle() const { return 2.0 * kPi / ring_.teeth(); }
  /// Sun and planet speeds per unit carrier speed (ring fixed).
  double sun_ratio() const { return 1.0 + static_cast<double>(ring_.teeth()) / sun_.teeth(); }
  double planet_ratio() const {
    return 1.0 - static_cast<double>(ring_.teeth()) / planets_[0].teeth();
  }

  /// Rigid kinematic poses at carrier angle φ_c: nominal positions and rotations, with the
  /// scene's errors applied to the geometry when `with_errors`.
  StagePoses Poses(double carrier_angle, bool with_errors = true) const;
  /// The same into `out`, reusing its planets' storage (no allocation once it has held them).
  void Poses(double carrier_angle, StagePoses* out, bool with_errors = true) const;
  /// Centre of planet i's pin at carrier angle φ_c [m]: r_c e(φ_c + ψ_i) plus the pin error in
  /// the carrier frame when `with_errors`; the planets' rotation centres of Poses, and the pins
  /// the dynamic model moves with the carrier.
  Vec2 Pin(int planet, double carrier_angle, bool with_errors = true) const;

  PosedGear Sun(const StagePoses& p) const { return {&sun_, p.sun}; }
  PosedGear Ring(const StagePoses& p) const { return {&ring_, p.ring}; }
  PosedGear Planet(const StagePoses& p, int i) const { return {&planets_.at(i), p.planets.at(i)}; }

  /// The potential contacts of one mesh (planet i; sun mesh or ring mesh).
  std::vector<PotentialContact> Contacts(const StagePoses& p, int planet, MeshKind kind,
                                         const ContactSearchOptions& options) const;
  /// The same, appended to `out`; with `reuse`, the mesh's tip rounds reused under a pose bound
  /// (geometry::TipRoundReuse, one per mesh), the same contacts.
  void AppendContacts(const StagePoses& p, int planet, MeshKind kind,
                      const ContactSearchOptions& options, std::vector<PotentialContact>* out,
                      TipRoundReuse* reuse = nullptr) const;
  /// Whether the mesh's gears admit a line of action at these poses (geometry::HasLineOfAction):
  /// Contacts and AppendContacts throw std::invalid_argument for a mesh that does not.
  bool HasLineOfAction(const StagePoses& p, int planet, MeshKind kind) const;

 private:
  void CheckAssembly();
  void CheckClearances() const;
  void Align();
  void Summarise();

  StageSpec spec_;
  Gear sun_, ring_;
  std::vector<Gear> planets_;
  std::vector<double> angles_;
  double sun_turn0_ = 0;              // θ_S at φ_c = 0
  std::vector<double> planet_turn0_;  // θ_Pi at φ_c = 0
  std::vector<MeshSummary> meshes_;
};

}  // namespace epicycle::geometry
