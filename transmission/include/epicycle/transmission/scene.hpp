// A scene: one planetary stage with its gears, cutters, errors, material and load, read from a
// TOML file whose keys name their units (module_mm, torque_Nm, runout_um, pressure_angle_deg).
// The keys are documented in docs/scenes.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/io/enum_names.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/damage.hpp"
#include "epicycle/transmission/dynamic_settings.hpp"
#include "epicycle/transmission/face_width.hpp"

namespace epicycle::transmission {

struct Material {
  double youngs_modulus = 207e9;  ///< E [Pa]
  double poisson_ratio = 0.3;     ///< ν [-]
  /// ISO 6336-5 endurance limits for the ratings (docs/stresses.md, "Ratings"); 0: not given.
  double bending_limit = 0;  ///< σ_Flim [Pa] (the scene's bending_limit_MPa)
  double contact_limit = 0;  ///< σ_Hlim [Pa] (contact_limit_MPa)
};

/// The scene's optional [rating] table: what the ratings take from the application.
struct RatingSettings {
  double application_factor = 1.0;  ///< K_A [-] (ISO 6336-1), application_factor
};

struct Inertia {
  double mass = 0;     ///< [kg]
  double inertia = 0;  ///< polar moment of inertia [kg·m²]
};

/// The members' masses and inertias (the scene's [sun], [planet], [ring], [carrier] tables);
/// every planet has the planet's.
struct StageInertias {
  Inertia sun, planet, ring, carrier;
};

/// External loads on the stage [N·m] (counter-clockwise +): the one home of the input torque.
/// Its sign selects the loaded flanks, which the stage's geometry is built with
/// (geometry::StageSpec::load_sign, set from it by the scene reader); a study or a command that
/// changes the torque changes it here and keeps the sign (StageModel checks it).
struct StageLoads {
  double sun_torque = 0;  ///< input torque on the sun [N·m], non-zero
};

/// A profile shift solved from a backlash (one of the scene's [[fit]] tables).
struct ShiftFit {
  std::string gear;            ///< "sun", "planet" or "ring"
  std::string mesh;            ///< "sun-planet" or "planet-ring"
  double normal_backlash = 0;  ///< j_n [m]
  double profile_shift = 0;    ///< the solved x [-]
};

/// How the bodies are modelled (the scene's optional [model] table).
struct ModelSettings {
  /// Plane strain (default, wide steel gears: docs/compliance.md) or plane stress, the same in the
  /// FE structural term and the local contact term.
  solvers::PlaneAssumption plane = solvers::PlaneAssumption::kPlaneStrain;
  double join_depth = 0;  ///< h [m]; 0: each table's default (compliance::InfluenceTableOptions)
  /// Factor on each table's default h [-] when join_depth is 0 (InfluenceTableOptions::
  /// join_depth_factor), in (0, 1/0.6): the default h is 0.6 of the distance to the centre line.
  double join_depth_factor = 1;
  int mesh_refinement = 1;  ///< density factor of the gear-body meshes [-], 1..4
  /// Tooth stresses (docs/model.md §9): the influence tables also tabulate the fillet stresses,
  /// and the drivers report root stresses and Hertz contact pressures. Off, no stress is
  /// tabulated or computed.
  bool stresses = false;
};

/// How the sun is held in translation (its rotation is always set by the input torque).
enum class SunSupport {
  kFixed,     ///< constrained: the paper's first case
  kFloating,  ///< free: the paper's second case
  kElastic,   ///< on a bearing of stiffness Supports::sun_stiffness
};

/// The supports' names (the scene's supports.sun, the programs' --sun): the one table of
/// SunSupportName and of every reader of the word.
inline constexpr std::array<io::EnumName<SunSupport>, 3> kSunSupportNames{{
    {SunSupport::kFixed, "fixed"},
    {SunSupport::kFloating, "floating"},
    {SunSupport::kElastic, "elastic"},
}};

/// "fixed", "floating" or "elastic": the scene file's word for the support.
const char* SunSupportName(SunSupport support);

/// The scene's optional [supports] table. The ring is fixed and the carrier held.
struct Supports {
  SunSupport sun = SunSupport::kFixed;
  double sun_stiffness = 0;     ///< [N/m], kElastic only
  double planet_stiffness = 0;  ///< planet bearings [N/m]; 0: rigid pins
};

/// A scene holds a planetary stage, or a single gear pair (for mesh-stiffness studies).
enum class SceneKind { kStage, kPair };

struct Scene {
  SceneKind kind = SceneKind::kStage;
  std::string name;
  std::string description;
  std::string source;         ///< file name (for messages)
  geometry::StageSpec stage;  ///< kind == kStage
  geometry::PairSpec pair;    ///< kind == kPair
  double pair_torque = 0;     ///< torque on gear 1 of a pair [N·m] (ccw +)
  Material material;
  RatingSettings rating;
  ModelSettings model;
  Supports supports;
  StageInertias inertia;
  StageLoads loads;            ///< kind == kStage: the input torque
  double gap_window = 100e-6;  ///< contact-search gap window [m]
  std::vector<ShiftFit> fits;  ///< in the order they were applied
  std::string hash;            ///< ContentHash of the scene text (provenance of results)
  /// The scene's TOML text as read (MakeStage and MakePair find the lines of keys in it for
  /// messages); empty for a scene made in code.
  std::string text;
  /// Legal values outside the model's validity (docs/scenes.md, "Ranges and validity"), one
  /// message each naming the key, its value and the limit; reported with every result.
  std::vector<std::string> warnings;
  DynamicSettings dynamics;  ///< the [dynamics] and [lubricant] tables
  Damage damage;             ///< the [[damage.pit]] tables (empty: healthy teeth)
  FaceWidthSpec face_width;  ///< the [face_width] table (one slice: the plane model)
};

/// "fnv1a64:<16 hex digits>", the 64-bit FNV-1a hash of `text`: identifies an input file in the
/// results made from it (not a cryptographic hash).
std::string ContentHash(const std::string& text);

/// @throws std::invalid_argument naming the file, line, key, value and rule.
Scene ReadScene(const std::string& path);

/// The scene's stage (scene.stage), with the geometry's complaints told in the scene's terms: a
/// value the geometry derives (a tip radius from `addendum_per_module`, a root rounding that no
/// longer fits a thicker tooth) is named with the key the scene wrote and its file:line, and when
/// the error-free stage builds, the scene's [[errors.*]] entries of that gear are named as the
/// cause. @throws std::invalid_argument so worded.
geometry::Stage MakeStage(const Scene& scene);
/// The same for a gear pair: `spec` the scene's pair, or a mesh of its stage (MakeMeshPair).
geometry::GearPair MakePair(const Scene& scene, const geometry::PairSpec& spec);
/// Whether any gear of the scene is helical (helix_angle_deg > 0).
bool IsHelical(const Scene& scene);
/// Refuses a helical scene in `driver` (a command or run that computes the planar model: contact
/// search, compliance, load sharing, dynamics): until the model resolves the face width in slices
/// (docs/geometry.md, "Helical gears"), a helical scene runs only the geometry report, and the
/// planar model would give a spur result for it.
/// @throws std::invalid_argument naming the scene's helix_angle_deg key (file:line), its value and
///         the rule, for a helical scene.
void RequireSpur(const Scene& scene, const std::string& driver);
/// With slices of the face width: the largest gap change that the pin tilts, the carrier's
/// wind-up and the leads give across each mesh within half the contact search's gap window (the
/// search runs in the mid-plane). Called by the scene reader, and by a driver that changes these
/// values in a scene it has read (a study's case).
/// @throws std::invalid_argument naming the entry that contributes most, the change and the window.
void CheckFaceGapWindow(const Scene& scene);
/// Same, from text (source names it in messages).
Scene ParseScene(const std::string& text, const std::string& source);

}  // namespace epicycle::transmission
