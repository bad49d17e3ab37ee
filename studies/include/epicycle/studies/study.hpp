// A tolerance study (docs/studies.md): a base scene, random variables (manufacturing and assembly
// errors, the input torque) with their distributions or grids, what each case computes, and a
// seed. Read from a TOML file whose keys name their units (sigma_um, values_Nm); every bad value
// is reported with the file, line, key, value and rule, like the scene reader.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::studies {

/// What a random variable sets in the case's scene (the sampled value replaces the scene's).
enum class Quantity {
  kPinRadial,      ///< planet pin-hole radial position error Δζ [m]
  kPinTangential,  ///< planet pin-hole tangential position error Δη [m]
  kRunout,         ///< run-out amplitude e [m], with a phase uniform in [0, 2π) [rad]
  kThickness,      ///< tooth thickness error Δs [m]
  kTorque,         ///< input torque on the sun T [N·m]
  kPitDepth,       ///< depth d of one of the scene's pits [m] (transmission::Pit::depth)
  kPitWidth,       ///< width fraction w of one of the scene's pits [-]
  /// depth q of one of the scene's root cracks [m] (compliance::RootCrack::depth: a polyline's
  /// segments scaled alike); a case with its own crack builds its own damaged rows (cached)
  kCrackDepth,
  /// A planet pin's tilt (the scene's [[face_width.pin_tilt]]): its axis' displacement over the
  /// planet's face width b [m], radial (outward at +z) or tangential (counter-clockwise at +z);
  /// the case's slope is the value over b. Needs the scene's slices of the face width.
  kPinTiltRadial,
  kPinTiltTangential,
  /// A gear's lead slope deviation f_Hβ [m] and its crowning C_β ≥ 0 [m] (the scene's
  /// [[face_width.lead]] slope_um, crowning_um). Need the scene's slices of the face width.
  kLeadSlope,
  kCrowning,
};

/// The factor from a quantity's study-file unit to SI (µm: 1e-6; mm: 1e-3; N·m and fractions: 1)
/// and its inverse as written exactly (1e6, 1e3, 1), for the rows' values.
double FileToSi(Quantity q);
double SiToFile(Quantity q);

enum class Distribution {
  kNormal,   ///< mean + σ·Z, Z standard normal
  kUniform,  ///< uniform in [min, max)
  kIso1328,  ///< run-out amplitude uniform in [0, F_rT/2], F_rT of an ISO 1328-1 flank class
  kGrid,     ///< the listed values, one grid axis of a deterministic parameter sweep
};

/// The gear a variable belongs to: sun, ring or planet i (0-based), or one of the scene's pits.
struct Target {
  enum class Kind { kSun, kRing, kPlanet, kNone, kPit, kCrack } kind = Kind::kNone;
  int planet = 0;  ///< 0-based, Kind::kPlanet
  int pit = 0;     ///< index in the scene's [[damage.pit]], Kind::kPit
  int crack = 0;   ///< index in the scene's [[damage.crack]], Kind::kCrack
  /// "sun", "ring", "planet1", ..., "pit0", ..., "crack0", ... or "stage" (the torque)
  std::string Name() const;
};

struct Variable {
  Quantity quantity = Quantity::kPinTangential;
  Target target;
  Distribution distribution = Distribution::kNormal;
  double mean = 0;           ///< [m], [N·m] or [-] (a pit's width) (normal); likewise below
  double sigma = 0;          ///< σ [m] or [N·m] (normal)
  double min = 0, max = 0;   ///< [m] or [N·m] (uniform; iso1328: [0, F_rT/2])
  std::vector<double> grid;  ///< [m] or [N·m] (grid)
  int grade = 0;             ///< ISO 1328-1 flank tolerance class (iso1328) [-]
  /// Column name(s) of the sampled values in the result rows, in their file units:
  /// "planet1.pin_tangential_um"; a run-out has two, "..._amplitude_um" and "..._phase_deg".
  std::vector<std::string> Columns() const;
};

/// What each case computes.
enum class CaseKind {
  kMeshCycle,         ///< a quasi-static sweep over one mesh cycle
  kPlanetRevolution,  ///< over one planet revolution relative to the carrier (run-out period)
};

/// How the cases sample the random variables.
enum class Design {
  kMonteCarlo,  ///< `samples` independent cases per grid point
  /// The Saltelli design of the Sobol indices (studies/sobol.hpp): N = `samples` rows of two
  /// independent matrices A and B and the d matrices A_B^(i), N (d + 2) cases, d = variables.size()
  kSobol,
};

struct StudySpec {
  std::string name;
  std::string source;         ///< the study file (for messages)
  std::string scene_file;     ///< the base scene's file, relative paths resolved against the study
  transmission::Scene scene;  ///< the base scene
  std::uint64_t seed = 0;     ///< of the counter-based random streams [-]
  long samples = 1;           ///< Monte-Carlo cases per grid point; Sobol: the base sample N [-]
  Design design = Design::kMonteCarlo;
  CaseKind compute = CaseKind::kMeshCycle;
  int positions = 0;       ///< carrier positions per case [-] (default 36 cycle, 360 revolution)
  double start_angle = 0;  ///< carrier angle of the first position [rad]
  std::optional<transmission::SunSupport> sun;  ///< overrides the scene's support
  solvers::Backend backend = solvers::Backend::kActiveSetNewton;
  std::string backend_name = "newton";
  std::vector<Variable> variables;  ///< "planets" entries expanded, one per planet
  /// Design values of K_γ (a standard's table values; the key `k_gamma_limit`, a number or an
  /// array): the summary reports P(K_γ > each) with its Clopper–Pearson interval
  /// (studies::ExceedanceProbability); empty: none reported [-].
  std::vector<double> k_gamma_limits;
  std::string hash;                 ///< transmission::ContentHash of the study text
  /// Legal values outside the model's validity (as transmission::Scene::warnings).
  std::vector<std::string> warnings;

  /// Points of the grid: the product of the grid variables' sizes (1 without grids) [-].
  long GridPoints() const;
  /// Cases of the study: GridPoints() · samples, or samples · (d + 2) with the Sobol design [-].
  long Cases() const;
  /// The sampled-value columns of every variable, in order.
  std::vector<std::string> Columns() const;
  /// The gears whose root stress every case reports (sun, ring, planet1 …: transmission::BodyNames
  /// of the stage) when the study has stresses (scene.model.stresses: the study's `stresses` key,
  /// by default the scene's [model] stresses), else none.
  std::vector<std::string> StressGears() const;
  /// With stresses and the scene's [material] bending_limit_MPa and contact_limit_MPa: each case
  /// also gives every gear's safety factors from its own run (transmission::RateStage's model
  /// columns: S_F from the largest root tension, S_H from the largest line-of-action pressure).
  bool Rated() const;
  /// With slices of the face width (the scene's [face_width]): each mesh's name in
  /// transmission::FaceLoads' order ("sun-planet1", …, "planet1-ring", …), whose K_Hβ and K_γ·K_Hβ
  /// every case reports; else empty.
  std::vector<std::string> FaceMeshes() const;
  /// A helical stage (docs/model.md §10): the columns of the axial loads every case reports, the
  /// means over its sweep (transmission::SweepSummary::helical_mean, pin_tilts): per mesh in
  /// FaceMeshes' order F_a_<mesh>_N, the axial force on the planet [N]; per planet i
  /// M_tilt_radial_planet<i>_Nm and M_tilt_tangential_planet<i>_Nm, its tilting moment [N·m]; with
  /// pins (the scene's [[face_width.pin]]) per planet tilt_radial_planet<i>_urad and
  /// tilt_tangential_planet<i>_urad, its tilt on its pin [µrad]; else empty.
  std::vector<std::string> HelicalColumns() const;
  /// True when a variable changes the bodies' compliance (a crack's depth): each case then
  /// builds its own tables (from the cache) instead of sharing the nominal ones.
  bool VariesBodies() const;
};

/// @throws std::invalid_argument naming the file, line, key, value and rule (an unknown
///         distribution or quantity, a negative σ, a grade outside ISO 1328-1, a gear the scene
///         does not have, a scene that cannot be read).
StudySpec ReadStudy(const std::string& path);
/// The same from text; `source` names it in messages and relative scene paths are resolved
/// against `directory`.
StudySpec ParseStudy(const std::string& text, const std::string& source,
                     const std::string& directory);

}  // namespace epicycle::studies
