// Load across the face width (docs/model.md §10, "Face width"): each mesh's face width b divided
// into S slices of width b/S, every slice the plane model per unit width at the same contact
// point (its own gap, local term and structural compliance), the slices of a body coupled along
// the face, and the gap of each slice changed by what varies along the axis: a planet pin's tilt,
// the carrier's torsional wind-up, each gear's lead slope deviation, crowning and end relief.
//
// Axial coordinate z [m] from the mid-plane of the stage (every gear centred on it), slice s of
// a mesh of width b at z_s = −b/2 + (s + ½) b/S.
//
// Gap of slice s of a contact j between bodies A and B (δ_j the plane contact's overlap):
//   δ_js = δ_j + z_s n·(t_A − t_B) − z_s (ℓ_A h_A + ℓ_B h_B) − c_A(z_s) − c_B(z_s)
// with n the contact normal (from A into B), t_X the axis slope of body X [-] (a displacement
// z t_X of its section at z: a planet's pin tilt plus the carrier's wind-up; zero for the sun and
// the ring), ℓ_X the lever of the unit force on X [m] (PotentialContact::lever_a/b), h_X the
// lead slope deviation as a turn of the sections [rad/m] (f_Hβ/(b r_b)), and c_X(z) ≥ 0 the
// material removed by the lead modifications [m]: crowning C_β (2z/b)² and an end relief
// C_I ((|z| − (b/2 − L_I))/L_I) over the last L_I of each end.
//
// Structural compliance of slices (s, t) of contacts (j, k): C_jk W_st, W [-] the coupling along
// the face, with Σ_t W_st = S (a load uniform along the face deflects every slice as the plane
// model does):
//   - kNone: W = S I (uncoupled strips, ISO 6336-1 method C's idealisation);
//   - kPasternak: the face is an elastic foundation with shear coupling (a Pasternak layer,
//     w − λ² w'' = c p, free ends: w' = 0), whose Green's function on [0, b] is
//       G(x, x') = cosh(x_</λ) cosh((b − x_>)/λ) / (λ sinh(b/λ)),
//     and W_st = (S/Δz) ∫_s ∫_t G dx dx' (a Galerkin average over both slices: symmetric,
//     positive definite; λ → 0 gives S I, λ → ∞ the rigid 1 1ᵀ);
//   - kToothBody: the tooth along the face (strips, or a Pasternak layer of λ > 0), the gear
//     body on the face's resultant,
//       W = (1 − φ) W_tooth + φ 1 1ᵀ,   W_tooth = S I (λ = 0) or the Pasternak W of λ,
//     φ ∈ [0, 1) the bodies' share of the structural compliance at the contact (a disc held at
//     its hub answers the resultant of a load on its face, not where along the face it sits).
//     A gap linear in z then meets the tooth part alone: with strips the load falls at
//     c_t F_β/b per unit length, 1/c_t = (1 − φ) C b + (the local term per unit width), C the
//     plane contact's structural compliance [m/N] over the face width b. ContactBodyShare
//     (fe_compliance.hpp) computes φ from the FE tables (docs/model.md §10).
// The local contact term of a slice is the plane term of width b/S.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/compliance/compliance_operator.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/damage.hpp"
#include "epicycle/transmission/pin.hpp"

namespace epicycle::transmission {

struct ContactTerms;
struct StageContact;
struct TangentialLoads;
class StageCompliance;

/// How the slices of one body deflect together (the kernel W above).
enum class FaceCoupling {
  kNone,       ///< uncoupled strips
  kPasternak,  ///< a Pasternak foundation of coupling length λ with free ends
  kToothBody,  ///< the tooth (strips or Pasternak λ) plus bodies that answer the resultant (φ)
  /// W given as a table (FaceWidthSpec::coupling_table, and coupling_table_planet_ring for a
  /// stage's ring meshes): a gear pair's 3D structural compliance along the face over its plane
  /// strain (docs/fe_reference.md, "The structural compliance along the face"); its rows need not
  /// sum to S.
  kTable,
};

/// A lead (helix) deviation and the lead modifications of one gear (the scene's
/// [[face_width.lead]]).
struct LeadSpec {
  std::string gear;       ///< "sun", "ring", "planet<i>" (a stage); "gear1", "gear2" (a pair)
  double slope = 0;       ///< f_Hβ [m] of arc on the base circle over the face width, + ccw at +z
  double crowning = 0;    ///< C_β [m] removed at each end, parabolic, ≥ 0
  double end_relief = 0;  ///< C_I [m] removed at each end, linear over end_relief_length, ≥ 0
  double end_relief_length = 0;  ///< L_I [m], in (0, b/2] when end_relief > 0
  std::string where;             ///< "file:line: face_width.lead[0]" for messages
};

/// A planet pin's tilt in the carrier (the scene's [[face_width.pin_tilt]]): the slope of the
/// pin's axis, radial (outward at +z) and tangential (counter-clockwise at +z) [-].
struct PinTilt {
  int planet = 0;  ///< 0-based
  double radial = 0, tangential = 0;
  std::string where;
};

/// The scene's [face_width] table. slices == 1 is the plane model (nothing here runs).
struct FaceWidthSpec {
  int slices = 1;  ///< S [-], 1..kMaxFaceSlices
  FaceCoupling coupling = FaceCoupling::kNone;
  double coupling_length = 0;  ///< λ [m], > 0 for kPasternak
  /// W [-], S×S, symmetric positive definite, for kTable: a pair's mesh, a stage's sun-planet
  /// meshes.
  Eigen::MatrixXd coupling_table;
  Eigen::MatrixXd coupling_table_planet_ring;  ///< W [-] of a stage's planet-ring meshes, kTable
  std::vector<PinTilt> pin_tilts;
  std::vector<LeadSpec> leads;
  /// The planets' pins as load-dependent tilts (pin.hpp); empty: rigid pins.
  std::vector<PinSpec> pins;
  /// The carrier's torsional stiffness between its two plates [N·m/rad] (0: rigid) and the
  /// distance between the plates [m]: under the carrier torque T_c every pin tilts tangentially
  /// by T_c r_c/(k_θ L), r_c the carrier radius, the end at the output plate leading.
  double carrier_torsional_stiffness = 0;
  double carrier_plate_distance = 0;  ///< L [m], > 0 when the stiffness is given
  int carrier_output_side = 1;        ///< the output plate at z = +L/2 (+1) or −L/2 (−1)
  std::string carrier_where;          ///< "file:line: face_width.carrier_..." for messages
  bool active() const { return slices > 1; }
};

inline constexpr int kMaxFaceSlices = 200;

/// W [-], S×S, of `coupling` on a face of width `width` [m] (docs/model.md §10, "Face width"):
/// `coupling_length` λ [m] of kPasternak and of kToothBody's tooth (0: strips), `body_share` φ
/// [-] of kToothBody.
/// @throws std::invalid_argument for S < 1, a width not > 0, kPasternak with λ not > 0,
///         kToothBody with φ outside [0, 1) or λ < 0, or kTable (a table is given, not computed).
Eigen::MatrixXd FaceCouplingMatrix(int slices, double width, FaceCoupling coupling,
                                   double coupling_length, double body_share = 0);

/// z_s = −b/2 + (s + ½) b/S [m], the centre of slice s of a face of width b.
inline double SliceCentre(int slice, int slices, double width) {
  return -0.5 * width + (slice + 0.5) * width / slices;
}
/// z_s [m] of the slices of a face of width b.
std::vector<double> SliceCentres(int slices, double width);

/// c(z) [m]: what a lead's crowning C_β (2z/b)² and end relief C_I ((|z| − (b/2 − L_I))/L_I)
/// over the last L_I of each end remove at z of a face of width b [m] (the header's c_X).
double LeadRemoved(double crowning, double end_relief, double end_relief_length, double width,
                   double z);

/// The face-width model of a stage, resolved against its bodies once: every body's axis slope,
/// lead slope and modifications, and the coupling matrix of each mesh's face width.
class FaceWidthModel {
 public:
  FaceWidthModel() = default;
  /// `carrier_torque` [N·m] the carrier's torque from the stage at its nominal load (the
  /// wind-up's). @throws std::invalid_argument naming the key for a gear or planet that the stage
  /// does not have.
  FaceWidthModel(const FaceWidthSpec& spec, const geometry::Stage& stage, double carrier_torque);
  bool active() const { return spec_.active(); }
  int slices() const { return spec_.slices; }
  const FaceWidthSpec& spec() const { return spec_; }

  /// Splits every searched contact (terms->plane_contacts, compliance terms->plane_compliance)
  /// into its slices: terms->contacts, overlap and the dense compliance, and the compliance's
  /// Kronecker terms (terms->compliance_terms: C_n ⊗ W, or two terms when the ring mesh's W
  /// differs from the sun mesh's); the local terms are built afterwards from each slice's width
  /// fraction. Each slice's gap grows by the depth of the pits of `damage` that cover its centre.
  /// Writes into the terms' own buffers: with the same number of contacts as the last call it
  /// allocates nothing.
  void Expand(const geometry::StagePoses& poses, const DamageModel& damage,
              ContactTerms* terms) const;

  /// The gap change [m] of slice s of `contact` (the terms in the header's equation but δ_j).
  double GapChange(const geometry::StagePoses& poses, const StageContact& contact, int s) const;

  /// The axis slope of body b in the inertial frame at these poses [-]: with pins
  /// (pins().active()), a planet's adds its tilt on its pin under load, held in the poses
  /// (GearPose::axis_slope: per-position state, set by the quasi-static driver).
  Eigen::Vector2d AxisSlope(const geometry::StagePoses& poses, int body) const;

  /// The planets' pins (pin.hpp); inactive when every pin is rigid.
  const PinModel& pins() const { return pins_; }

  /// The misalignment of `contact`'s mesh that varies linearly across its face, the gap change
  /// from z = −b/2 to +b/2 [m], signed (+: the gap closes towards +z), split as ISO 6336-1 splits
  /// it: `assembly` (f_ma: the pin tilts and the lead slopes) and `deflection` (f_sh: the
  /// carrier's wind-up and the planets' tilts on their pins under load). Crowning and end relief are even in z and not part of it.
  struct Misalignment {
    double assembly = 0, deflection = 0;  ///< [m]
  };
  Misalignment MeshMisalignment(const geometry::StagePoses& poses,
                                const StageContact& contact) const;

  /// W [-] of the slices of two contacts: the planet–ring mesh's when both are on it, else the
  /// sun–planet mesh's (the planet's face is the narrower mesh's).
  const Eigen::MatrixXd& Coupling(bool both_on_ring_mesh) const {
    return both_on_ring_mesh ? coupling_planet_ring_ : coupling_sun_planet_;
  }
  /// The face width b [m] of the sun–planet or the planet–ring meshes.
  double MeshWidth(bool ring_mesh) const {
    return ring_mesh ? planet_ring_width_ : sun_planet_width_;
  }

 private:
  struct BodyLead {
    double slope = 0;  ///< h [rad/m]
    double crowning = 0, end_relief = 0, end_relief_length = 0, width = 0;
    double Removed(double z) const;  ///< c(z) [m]
  };
  FaceWidthSpec spec_;
  std::vector<BodyLead> lead_;                  // per body
  std::vector<Eigen::Vector2d> planet_slope_;   // carrier frame: (radial, tangential)
  double wind_up_slope_ = 0;                    // tangential [-], every pin
  PinModel pins_;
  double sun_planet_width_ = 0, planet_ring_width_ = 0;
  Eigen::MatrixXd coupling_sun_planet_, coupling_planet_ring_;
};

/// The load per unit face width of one mesh at one state.
struct MeshFaceLoad {
  int planet = 0;
  bool ring_mesh = false;      ///< false: the sun–planet mesh
  double width = 0;            ///< b [m], the mesh's face width
  std::vector<double> line_load;  ///< w_s [N/m] per slice (Σ over the mesh's contacts)
  double mean = 0;                ///< F/b [N/m]
  double k_h_beta = 1;            ///< K_Hβ = max w_s / mean [-] (1 without load)
  int largest_slice = 0;          ///< where the largest w_s sits
  double largest_z = 0;           ///< its slice centre z [m]
  /// The mesh's misalignment (FaceWidthModel::MeshMisalignment of its most loaded contact) [m].
  double misalignment_assembly = 0, misalignment_deflection = 0;
  /// With stresses (AddFaceStresses; else empty), per slice: the largest fillet tension of the
  /// mesh's two gears [Pa] and the largest Hertz pressure of its contacts on the line of action
  /// [Pa] (0 where the slice carries nothing).
  std::vector<double> root_stress, hertz_pressure;
  std::vector<int> root_stress_body;  ///< per slice: the gear of root_stress (kSunBody, ...)
};

/// Completes a mesh's face load from its line loads w_s (f.line_load, slices of a face of width
/// `width` [m]): the mean, K_Hβ = max/mean (1 without load), the largest slice and its z.
void SummariseLineLoad(double width, MeshFaceLoad* f);

/// The root stresses of a sliced state, slice by slice (docs/model.md §10, "Stresses across the
/// face"): slice s is the plane model per unit width at its own line load w_s, and the plane
/// model's fillet stresses are those of a load w b spread over the face width b, so slice s's
/// stresses are `compliance.FilletStresses` of the slice's contacts alone at the forces S f_js
/// (the stress recovery σ = Σ_j S_B(p; j) F_j is linear in the forces: this is the plane model at
/// w_s, not a scaling of a face-mean stress); `friction` likewise (its forces times S).
/// @return per slice, its fillets; the compliance's exceptions propagate.
std::vector<std::vector<compliance::FilletStress>> SliceFilletStresses(
    const StageCompliance& compliance, const geometry::Stage& stage,
    const geometry::StagePoses& poses, const std::vector<StageContact>& contacts,
    const Eigen::VectorXd& force, const TangentialLoads* friction);

/// The fillet stresses of a state: compliance.FilletStresses of its contacts, or, for sliced
/// contacts (StageContact::slices > 1), every slice's SliceFilletStresses one after the other
/// (a gear's extremes are then those over its slices), each slice's also into `slices` if given.
std::vector<compliance::FilletStress> StateFilletStresses(
    const StageCompliance& compliance, const geometry::Stage& stage,
    const geometry::StagePoses& poses, const std::vector<StageContact>& contacts,
    const Eigen::VectorXd& force, const TangentialLoads* friction,
    std::vector<std::vector<compliance::FilletStress>>* slices = nullptr);

/// Fills MeshFaceLoad::root_stress, root_stress_body and hertz_pressure of `loads` (FaceLoads of
/// the same contacts and forces) from the slices' fillets (SliceFilletStresses) and each
/// contact's Hertz pressure at its own force (its local term is the slice's: width b/S). A fillet
/// belongs to the mesh whose loaded contact of that slice on the fillet's body sits on the
/// nearest tooth. @throws std::invalid_argument if the sizes differ.
void AddFaceStresses(const std::vector<StageContact>& contacts,
                     const std::vector<solvers::LocalTermParameters>& local,
                     const Eigen::VectorXd& force,
                     const std::vector<std::vector<compliance::FilletStress>>& slice_fillets,
                     std::vector<MeshFaceLoad>* loads);

/// The face loads of every mesh (sun–planet meshes of planets 0…, then planet–ring meshes) from
/// the forces [N] of sliced contacts; `width` [m] of each mesh as in FaceWidthModel.
std::vector<MeshFaceLoad> FaceLoads(const geometry::Stage& stage, int slices,
                                    const std::vector<StageContact>& contacts,
                                    const Eigen::VectorXd& force);

}  // namespace epicycle::transmission
