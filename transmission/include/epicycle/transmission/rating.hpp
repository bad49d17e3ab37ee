// ISO 6336 ratings of a stage's gears (docs/model.md §9 "Ratings", docs/stresses.md "Ratings"):
// the standard's nominal stresses and safety factors (ISO 6336-2 and -3, method B) with the mesh
// load factor K_γ once from the standard's table and once from the model's run, beside the
// safety factors of the model's own root stresses and contact pressures.
//
// Bending (ISO 6336-3), per gear and mesh, F_t = T_s/(n r_s) the nominal tangential force at the
// reference circle of each planet's meshes (the same on both meshes of a planet):
//   σ_F0 = F_t/(b m) Y_F Y_S               (Y_β = Y_B = Y_DT = 1: spur, solid rim, ε_α < 2.05)
//   σ_F  = σ_F0 K_A K_v K_Fβ K_Fα K_γ
//   S_F  = σ_Flim Y_ST Y_M Y_NT Y_δrelT Y_RrelT Y_X / σ_F,   Y_ST = 2,
//          Y_M = 0.7 for a planet (an idler: fully reversed bending, ISO 6336-5), else 1.
// Contact (ISO 6336-2), per mesh, pinion 1 (fewer teeth), u = z_2/z_1 (< 0 internal):
//   σ_H0 = Z_H Z_E Z_ε √(F_t/(d_1 b) (u + 1)/u),   σ_H = Z_B|D σ_H0 √(K_A K_v K_Hβ K_Hα K_γ)
//   S_H  = σ_Hlim Z_NT Z_L Z_v Z_R Z_W Z_X / σ_H.
// Taken as 1, with the reason each: K_Hβ = K_Fβ (the plane model carries the load uniformly over
// the face width), K_Hα = K_Fα (the model resolves the load sharing between tooth pairs itself;
// the ISO columns are the standard's nominal case), the life factors Z_NT, Y_NT (endurance, beyond
// 5·10⁷ cycles), the lubricant, roughness, size and work-hardening factors and Y_δrelT, Y_RrelT,
// Y_X (reference test-gear conditions). K_v = 1 in a quasi-static run.
// The model's own: S_F = σ_Flim Y_ST Y_M / (σ_root K_A K_v), σ_root the largest fillet tension of
// the run; S_H = σ_Hlim / (p_H √(K_A K_v)), p_H the largest Hertz pressure of the run. These
// already contain the load sharing between planets and between tooth pairs and the stress
// concentration of the actual fillet.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/sweep_summary.hpp"

namespace epicycle::transmission {

/// One factor with its value and where it came from.
struct RatingFactor {
  std::string symbol;  ///< "Z_H sun-planet", "Y_F sun", "K_gamma table", ...
  double value = 0;    ///< [-] (Z_E: [√Pa])
  std::string source;  ///< "ISO 6336-2 method B, alpha_w = 27.85 deg", "the run: max L_i", ...
};

/// K_γ of the standard's table for a planetary stage of `planets` planets (application level,
/// AGMA 6123 / ISO 6336): 1.0 up to 3, 1.2 for 4, 1.3 for 5, 1.4 for 6 and more.
double TableMeshLoadFactor(int planets);

/// One gear's rating. NaN where a value does not exist (the reason in `note`): the ISO bending
/// rating of a gear not cut by a rack (method B's form factors need the rack), the model's own
/// values without stresses.
struct GearRating {
  int body = 0;       ///< kSunBody, kRingBody, PlanetBody(i)
  std::string gear;   ///< BodyName(body)
  double k_gamma_table = 0;  ///< K_γ, the standard's table [-]
  double k_gamma_model = 0;  ///< K_γ from the run: max L_i of the planet paths this gear meets [-]
  double reversed_bending = 1;  ///< Y_M [-]: 0.7 for a planet, else 1
  std::string bending_mesh;     ///< the mesh whose σ_F0 is the larger (a planet has two)
  double sigma_f0 = 0;          ///< σ_F0 [Pa]
  double sigma_f_table = 0, sigma_f_model = 0;  ///< σ_F with the table's and the run's K_γ [Pa]
  double s_f_table = 0, s_f_model = 0;          ///< S_F [-]
  std::string contact_mesh;                     ///< the mesh whose σ_H is the larger
  double sigma_h0 = 0;                          ///< σ_H0 [Pa] (without Z_B, Z_D)
  double z_bd = 1;                              ///< Z_B (pinion) or Z_D (wheel) of that mesh [-]
  double sigma_h_table = 0, sigma_h_model = 0;  ///< σ_H [Pa]
  double s_h_table = 0, s_h_model = 0;          ///< S_H [-]
  double root_stress = 0;       ///< the run's largest fillet tension [Pa]
  double s_f_stress = 0;        ///< S_F from it [-]
  /// The run's largest p_H on the drive flanks on the line of action [Pa] (a tip round's corner
  /// contact is reported with the contact pressures, not rated: ISO 6336-2 rates the flank).
  double contact_pressure = 0;
  double s_h_pressure = 0;      ///< S_H from it [-]
  std::string note;
};

/// ISO 6336-1 clause 7, K_Hβ by method C, with the inputs the model was given (docs/model.md §10,
/// "Ratings across the face", which lists each formula's source and what is unconfirmed). All
/// lengths in m, forces in N, stiffnesses per unit face width in N/m² (1 N/(mm·µm) = 1e9 N/m²):
///   F_βx = 1.33 B1 f_sh + B2 f_ma,  B1, B2 of the helix modification (MethodCModification),
///   F_βx ≥ F_βx,min = max(0.005 µm per N/mm of F_m/b, 0.5 f_Hβ),
///   y_β = 0.15 F_βx ≤ 6 µm (case-hardened or nitrided steel),
///   F_βy = F_βx − y_β,  c_γβ = 0.85 c_γα,  x = F_βy c_γβ b/(2 F_m),
///   K_Hβ = 1 + x (x ≤ 1: the whole face carries),  2 √x = √(2 F_βy c_γβ b/F_m) (x > 1),
///   K_Fβ = K_Hβ^N_F,  N_F = (b/h)²/(1 + b/h + (b/h)²),  b/h ≥ 3 (h the tooth depth).
struct FaceLoadFactorInputs {
  double assembly = 0;    ///< f_ma [m] ≥ 0
  double deflection = 0;  ///< f_sh [m] ≥ 0
  double lead_slope = 0;  ///< f_Hβ [m] ≥ 0, the larger lead slope deviation of the two gears
  double mesh_stiffness = 0;  ///< c_γα [N/m²] > 0, per unit face width
  double face_width = 0;      ///< b [m] > 0
  double mean_force = 0;      ///< F_m = F_t K_A K_γ K_v [N] > 0
  double tooth_depth = 0;     ///< h [m] > 0
  double b1 = 1, b2 = 1;      ///< B1, B2 [-] in (0, 1] (MethodCModification)
};
/// ISO 6336-1 method C's B1 and B2 (its table of helix modifications) for a mesh whose two gears
/// carry the crowning C_β = `crowning` [m] (the sum of both gears') and end relief or not, with
/// the mesh's f_ma = `assembly` and f_sh = `deflection` [m]:
///   crowned, C_β ≥ 0.5 (f_ma + f_sh): the row "C_β = 0.5 (f_ma + f_sh)", B1 = 0.5, B2 = 0.5;
///   crowned, smaller C_β:            the row "C_β = 0.5 f_ma",          B1 = 1,   B2 = 0.5;
///   end relief (not crowned):         B1 = 0.7, B2 = 0.7;  neither: B1 = 1, B2 = 1.
/// The model's lead slopes are deviations (f_Hβ), not a helix correction, so the standard's
/// helix-correction rows (B1 = 0.1) are not taken (docs/model.md §10, "Ratings across the face").
/// @throws std::invalid_argument for a negative or non-finite length.
std::array<double, 2> MethodCModification(double crowning, bool end_relieved, double assembly,
                                          double deflection);
struct FaceLoadFactorC {
  double f_beta_x = 0;      ///< F_βx [m], after its minimum
  double f_beta_x_min = 0;  ///< F_βx,min = max(0.005 µm per N/mm of F_m/b, 0.5 f_Hβ) [m]
  bool at_minimum = false;  ///< F_βx,min exceeds 1.33 B1 f_sh + B2 f_ma (F_βx is the minimum)
  double y_beta = 0;        ///< running-in allowance y_β [m]
  double f_beta_y = 0;      ///< F_βy [m]
  double c_gamma_beta = 0;  ///< c_γβ [N/m²]
  bool lifted = false;      ///< x > 1: part of the face carries nothing (the square-root case)
  double k_h_beta = 1;      ///< K_Hβ [-]
  double n_f = 1;           ///< N_F [-]
  double k_f_beta = 1;      ///< K_Fβ [-]
};
/// @throws std::invalid_argument naming the field whose value breaks its rule.
FaceLoadFactorC IsoFaceLoadFactorC(const FaceLoadFactorInputs& in);

/// The rating of one planet mesh across its face width (a stage with slices): the model's K_Hβ
/// beside ISO 6336-1 method C's fed the model's misalignment and mesh stiffness, and the safety
/// factors of the model's own stresses per slice.
struct MeshFaceRating {
  std::string mesh;             ///< "sun-planet1", "planet1-ring"
  double k_gamma_table = 0;     ///< K_γ, the standard's table [-]
  double k_gamma_model = 0;     ///< K_γ of the planet, the run's max L_i [-]
  double k_h_beta_model = 0;    ///< the run's largest K_Hβ [-]
  FaceLoadFactorInputs iso_inputs;
  FaceLoadFactorC iso;          ///< method C
  double k_gamma_k_h_beta_model = 0;  ///< max over positions of L_i K_Hβ [-]
  double k_gamma_k_h_beta_iso = 0;    ///< K_γ table × K_Hβ method C [-]
  std::string root_stress_gear;       ///< the gear whose fillet carries root_stress
  double root_stress = 0;   ///< the largest root stress over slices and positions [Pa]
  double s_f_stress = 0;    ///< S_F = σ_Flim Y_ST Y_M/(σ K_A K_v) [-]
  double hertz_pressure = 0;  ///< the largest Hertz pressure over slices and positions [Pa]
  double s_h_pressure = 0;    ///< S_H = σ_Hlim/(p_H √(K_A K_v)) [-]
};

struct StageRating {
  double tangential_force = 0;  ///< F_t per planet mesh [N]
  double application_factor = 1;  ///< K_A [-]
  double dynamic_factor = 1;      ///< K_v [-]
  std::string dynamic_source;
  std::vector<RatingFactor> factors;  ///< every factor, in the order computed
  std::vector<GearRating> gears;      ///< sun, planets, ring
  /// With slices of the face width and the meshes' stiffness (RateStage's `mesh_stiffness`): per
  /// mesh (sun–planet meshes, then planet–ring); else empty.
  std::vector<MeshFaceRating> face_width;
};

/// What a rating takes from its scene, resolved once when the stage's rig is built (StageRig,
/// dynamics::StageDynamics, a study's case) and held there: every rating reads these, never the
/// scene (docs/model.md §9, "Ratings").
struct RatingInputs {
  std::string source;             ///< the scene's file, for messages
  double bending_limit = 0;       ///< σ_Flim [Pa] ([material] bending_limit_MPa); 0: not given
  double contact_limit = 0;       ///< σ_Hlim [Pa] ([material] contact_limit_MPa); 0: not given
  double youngs_modulus = 0;      ///< E [Pa] of every gear ([material] youngs_modulus_GPa)
  double poisson_ratio = 0;       ///< ν [-] of every gear ([material] poisson_ratio)
  double application_factor = 1;  ///< K_A [-] ([rating] application_factor)
  double sun_torque = 0;          ///< T_s [N·m] ([load] sun_torque_Nm)
  std::vector<LeadSpec> leads;  ///< the gears' lead slopes and modifications ([[face_width.lead]])
};

/// The rating inputs of a stage scene.
/// @throws std::invalid_argument naming the scene key whose value breaks its rule (a scene made in
///         code: E > 0, ν in [0, 0.5), K_A in [1, 4], T_s finite and not 0, limits finite ≥ 0).
RatingInputs RatingInputsOf(const Scene& scene);

/// A run in motion's own stresses for the model's columns of a rating: its largest root stresses
/// and Hertz pressures, which already carry the dynamic loads (those columns then take K_v = 1;
/// the ISO columns take the run's K_v against the quasi-static reference).
struct MotionStresses {
  std::vector<RootStressSummary> root_stress;
  std::vector<FlankPressure> contact_pressure;
  std::string source;  ///< "the dynamic run at 1000 rpm", for the factor list
};

/// Refuses a rating (asked for by `asked_by`, e.g. "--rating") whose inputs lack either endurance
/// limit. @throws std::invalid_argument naming the missing [material] key.
void CheckRatingInputs(const RatingInputs& inputs, const std::string& asked_by);

/// The ratings of `stage` (`inputs`: its material, limits, K_A and torque) with the run's `summary`
/// (K_γ from its LSR; root stresses and contact pressures when it has them) and the dynamic factor
/// K_v
/// (`dynamic_source` says where it came from). With `motion` (a dynamic run: `summary` is then
/// its quasi-static reference at the same carrier angles) the model's own columns are the run's
/// stresses in motion without K_v. With `mesh_stiffness` (c_γα [N/m²] per unit face width of the
/// sun and ring meshes, MeanMeshStiffnessPerWidth) and a summary with face_width, the meshes'
/// face-width ratings (StageRating::face_width).
/// @throws std::invalid_argument naming the scene key if the inputs have no bending_limit_MPa or
///         contact_limit_MPa in [material], or for K_v not finite and ≥ 1;
///         std::runtime_error if the summary has no converged position (no K_γ from the run).
StageRating RateStage(const RatingInputs& inputs, const geometry::Stage& stage,
                      const SweepSummary& summary, double dynamic_factor = 1.0,
                      const std::string& dynamic_source = "quasi-static run",
                      const MotionStresses* motion = nullptr,
                      const std::array<double, 2>* mesh_stiffness = nullptr);

}  // namespace epicycle::transmission
