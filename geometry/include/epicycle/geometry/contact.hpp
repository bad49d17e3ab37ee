// Contact search between two meshing gears (docs/model.md §3): every potential contact of every
// tooth pair within a gap window, on both flanks, on the line of action (involute against involute,
// closed form) and off it (tip round against flank: closest points between an arc and an involute).
#pragma once

#include <string>
#include <vector>

#include "epicycle/geometry/gear.hpp"

namespace epicycle::geometry {

/// Where a gear is: its rotation centre (bearing / pin), its geometric centre (differs by the
/// run-out vector, which turns with the gear) and the rotation of its body frame.
struct GearPose {
  Vec2 rotation_centre = Vec2::Zero();   ///< [m]
  Vec2 geometric_centre = Vec2::Zero();  ///< [m] centre of the tooth geometry
  double rotation = 0;                   ///< θ [rad], counter-clockwise
  /// The slope of the gear's axis [-], inertial frame: its section at z displaced by z·slope. A
  /// planet's tilt on its pin under load (transmission/pin.hpp), set per position by the
  /// quasi-static driver; 0 elsewhere.
  Vec2 axis_slope = Vec2::Zero();
};

struct PosedGear {
  const Gear* gear = nullptr;
  GearPose pose;
};

/// The involute flank of tooth k on side σ in the inertial frame:
///   p(u) = c + r_b [e(S + H u) − H u e⊥(S + H u)],  S = θ + 2πk/z + σθ0 + F_p,k/r,  H = σ h,
///   outward normal σ e⊥(S + H u)
/// (F_p,k the tooth's cumulative pitch deviation). A relieved flank is p(u) − C(u)·(outward
/// normal), C = Gear::ReliefAt(u): the contact search accounts for it; this struct does not.
struct WorldInvolute {
  Vec2 centre = Vec2::Zero();
  double base_radius = 0;
  double start = 0;  ///< S [rad]
  int hand = 1;      ///< H
  int side = 1;      ///< σ
  double u_min = 0, u_max = 0;
  Vec2 Point(double u) const;
  Vec2 Normal(double u) const;  ///< outward unit normal
};
WorldInvolute FlankInWorld(const PosedGear& g, int tooth, int side);

/// A line of action of the pair (A external; B external, or B the internal gear with A inside):
/// the common tangent of the two base circles along which A's flank of side σ_A meets B's flank.
struct LineOfAction {
  int side_a = 1, side_b = 1;     ///< σ_A, σ_B (σ_B = σ_A external, −σ_A internal)
  Vec2 tangent_a = Vec2::Zero();  ///< N_A, tangency point on A's base circle [m]
  Vec2 tangent_b = Vec2::Zero();  ///< N_B [m]
  Vec2 direction = Vec2::Zero();  ///< d, unit: A's outward flank normal (from A into B)
  double base_angle_a = 0;        ///< β_A [rad], angle of N_A about A's centre
  double base_angle_b = 0;        ///< β_B [rad]
  double length = 0;              ///< (N_B − N_A)·d [m]
  double pressure_angle = 0;      ///< α_w [rad] at the actual centre distance
  double centre_distance = 0;     ///< a [m] between geometric centres
};
/// @throws std::invalid_argument if the base circles do not admit the tangent (gears too close).
LineOfAction MakeLineOfAction(const PosedGear& a, const PosedGear& b, bool internal, int side_a);

/// Overlap along the line of action of the tooth pair nearest to contact, ignoring where the
/// involutes end, relief and pitch deviations (the nominal teeth): δ ∈ (−p_b/2, p_b/2] [m]. d δ/d
/// θ_A = σ_A r_bA, d δ/d θ_B = −σ_B ... (see .cpp).
double NearestLoaOverlap(const PosedGear& a, const PosedGear& b, bool internal, int side_a);

enum class ContactKind {
  kInvolute,   ///< involute against involute, on the line of action
  kTipRoundA,  ///< A's tip round against B's flank, off the line of action
  kTipRoundB,  ///< B's tip round against A's flank, off the line of action
};
std::string KindName(ContactKind kind);

/// One potential contact. Force F ≥ 0 acts on B along +normal and on A along −normal.
struct PotentialContact {
  ContactKind kind = ContactKind::kInvolute;
  int side_a = 1, side_b = 1;    ///< flank sides σ
  int tooth_a = 0, tooth_b = 0;  ///< tooth indices in each body frame
  Vec2 point = Vec2::Zero();     ///< location (midpoint of the two closest points) [m]
  Vec2 point_a = Vec2::Zero(), point_b = Vec2::Zero();  ///< closest points on A and on B [m]
  /// The same material points on the nominal profiles of the nominal teeth (without relief, tooth
  /// turned back by its pitch deviation) [m]: where the FE influence tables, built on the nominal
  /// generated profile, are read. Equal to point_a, point_b for unmodified gears.
  Vec2 surface_a = Vec2::Zero(), surface_b = Vec2::Zero();
  Vec2 normal = Vec2::Zero();     ///< unit, A's outward normal (from A into B)
  double overlap = 0;             ///< δ [m]: > 0 interpenetration, < 0 gap
  double lever_a = 0;             ///< moment about A's rotation centre of the unit force on A [m]
  double lever_b = 0;             ///< moment about B's rotation centre of the unit force on B [m]
  double curvature_radius_a = 0;  ///< [m], > 0 convex, < 0 concave
  double curvature_radius_b = 0;  ///< [m]
  double roll_a = 0,
         roll_b = 0;  ///< involute roll angles of the contact (or of the flank point) [rad]
};

struct ContactSearchOptions {
  double gap_window = 100e-6;  ///< keep contacts with δ ≥ −window [m]
  bool both_sides = true;      ///< search both flanks (drive and coast)
  int side_a = 1;              ///< with both_sides false: the one side σ_A to search
  /// Try every tooth's tip round, without the pre-filter of the rounds that cannot reach the mate
  /// (a check of the tooth selection and of that filter).
  bool exhaustive_tips = false;
};

/// Whether the posed gears admit a line of action: their geometric centres apart by more than the
/// sum (external) or the difference (internal) of the base radii. FindContacts and AppendContacts
/// throw std::invalid_argument for gears that do not; a caller whose poses come from a motion
/// (an integrator's trial step) asks first.
bool HasLineOfAction(const PosedGear& a, const PosedGear& b, bool internal);

/// What AppendContacts keeps of one mesh between calls so that it skips the tip rounds that
/// provably cannot reach the mate while the gears stay near where they were (docs/dynamic_cost.md,
/// "Tip rounds reused under a pose bound"). At a refresh (the first call, a changed gear, window or
/// side, or a pose outside the budget) the search notes the poses P0 and, for each flank side and
/// each gear's rounds, the teeth whose round could become a candidate within the budget, and
/// which of them cannot reach the mate anywhere within it. Until the next refresh a call whose
/// every geometric centre lies within `centre_budget` of P0's and whose rotations lie within
/// `turn_budget_a`, `turn_budget_b` of P0's skips those rounds: the contacts it appends are the
/// ones a search without reuse appends, in the same order. Owned by the caller, one per mesh
/// (e.g. per thread, or per right-hand-side work space); the statistics are the caller's to read.
struct TipRoundReuse {
  /// The budget D [m]: each gear may turn by D over its largest radius and its geometric centre
  /// move by D before a refresh. Larger: fewer refreshes, more rounds that may reach within it.
  double budget = 100e-6;
  // Set by the search.
  bool valid = false;
  const Gear* gear_a = nullptr;
  const Gear* gear_b = nullptr;
  bool internal = false;
  double gap_window = 0;
  bool both_sides = true;
  int side_a = 1;
  GearPose pose_a, pose_b;   ///< P0
  double centre_budget = 0;  ///< [m]
  double turn_budget_a = 0;  ///< [rad]
  double turn_budget_b = 0;  ///< [rad]
  /// One flank side's rounds of one gear: the teeth that can be candidates within the budget
  /// (at most three) and whether each cannot reach the mate within it; `usable` false if the
  /// budget admitted more candidates than that (then nothing is skipped).
  struct Rounds {
    bool usable = false;
    int count = 0;
    int teeth[3] = {0, 0, 0};
    bool dead[3] = {false, false, false};
  };
  Rounds rounds[2][2];  ///< [side index][0: A's rounds, 1: B's]
  long refreshes = 0;   ///< calls that refreshed
  long reuses = 0;      ///< calls within the budget of the last refresh
  long skipped = 0;     ///< rounds skipped (a gear's rounds on a side skipped at once count 1)
};

/// Every potential contact between A and B (internal: B is the ring, A a planet inside it).
/// Relief and pitch deviations enter the geometry: on the line of action the overlap is the
/// involutes' minus C_A(u_A) + C_B(u_B) (exact along the line, whose direction stays the contact
/// normal: the relieved flank's own normal is tilted by dC/ds ≤ 0.05 rad, see docs/geometry.md);
/// a tip round against a relieved flank takes the exact closest point (Newton on the relieved
/// curve); tooth k of either gear is turned by F_p,k/r.
std::vector<PotentialContact> FindContacts(const PosedGear& a, const PosedGear& b, bool internal,
                                           const ContactSearchOptions& options);
/// FindContacts appending to `out`: a caller that searches many meshes reuses one vector.
/// With `reuse` (not null, and options.exhaustive_tips false), the tip rounds it proves out of
/// reach are skipped (TipRoundReuse); the contacts are the same.
void AppendContacts(const PosedGear& a, const PosedGear& b, bool internal,
                    const ContactSearchOptions& options, std::vector<PotentialContact>* out,
                    TipRoundReuse* reuse = nullptr);

}  // namespace epicycle::geometry
