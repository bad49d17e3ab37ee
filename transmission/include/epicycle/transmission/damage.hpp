// Tooth damage of a scene (docs/model.md §9, "Pitting and spalls" and "Root crack"): where it is on
// which tooth of which gear, read once from the scene's [[damage.*]] arrays, and how it changes
// what every driver builds. A root crack changes the compliance of its body only (the cracked
// tooth's influence rows, compliance::DamagedInfluence, built by GearTables). A pit or spall lowers
// a region of one flank by its depth over a fraction of the face width: a contact whose point lies
// in the region is split into strips of the face width, each a contact of its own at the same point
// and along the same normal, with the gap grown by the depth of the pits that cover it and a local
// term of its own width; all strips of a contact share its rows of the structural compliance (the
// load spreads across the face within the body).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/compliance/root_crack.hpp"
#include "epicycle/geometry/contact.hpp"

namespace epicycle::transmission {

/// A pit or spall on one flank of one tooth (the scene's [[damage.pit]]).
struct Pit {
  /// The gear as the scene names it: "sun", "ring", "planet<i>" (a stage); "gear1", "gear2" (a
  /// pair). A stage mesh studied as a pair keeps the stage's names.
  std::string gear;
  int tooth = 0;  ///< k in the gear's body frame, 0 ≤ k < z (geometry::PotentialContact::tooth_a/b)
  int flank = 1;  ///< σ = ±1, the body-frame flank side (geometry::PotentialContact::side_a/b)
  double roll_from = 0, roll_to = 0;  ///< involute roll angle range u [rad], roll_from < roll_to
  double width_fraction = 1;          ///< w ∈ (0, 1]: the share of the face width it covers [-]
  double depth = 0;                   ///< d > 0 [m], normal to the flank
  std::string where;                  ///< "file:line: damage.pit[0]" for messages
  /// "planet1 tooth 3 flank + roll 20..25 deg, w 0.5, depth 50 um"
  std::string Describe() const;
};

/// Where a crack's mouth is placed on its fillet (the scene's `start` or `start_arc_mm`).
enum class CrackStart {
  kArc,             ///< at RootCrack::start_arc as given
  kLargestTension,  ///< compliance::LargestRootTensionArc of a unit load at the tip-most point
                    ///< of the flank grid of the crack's side (needs the body's fillet stresses)
  kIso30,           ///< compliance::IsoCriticalFilletArc (ISO 6336-3's 30° point)
};

/// A root crack in one tooth (the scene's [[damage.crack]]): an open crack (its faces do not
/// touch), docs/model.md §9 "Root crack".
struct Crack {
  std::string gear;  ///< named as Pit::gear
  /// The crack in the gear's body frame; `start_arc` is final only for CrackStart::kArc (the
  /// others are placed when the body's table is at hand: ResolvedStart).
  compliance::RootCrack crack;
  CrackStart start = CrackStart::kLargestTension;
  std::string where;  ///< "file:line: damage.crack[0]" for messages
  /// "sun tooth 0 fillet + from the largest root tension, depth 1.2 mm (1 segment)"
  std::string Describe() const;
};

/// Every damage of a scene.
struct Damage {
  std::vector<Pit> pits;
  std::vector<Crack> cracks;
  bool empty() const { return pits.empty() && cracks.empty(); }
  /// The crack on the gear named `gear`, or null (the scene allows one per gear).
  const Crack* CrackOn(const std::string& gear) const;
  /// One line per damage (Pit::Describe, Crack::Describe), for reports.
  std::vector<std::string> Describe() const;
};

/// A contact's share of the face width between the pits of its two flanks: the strip
/// [face-width fraction] whose gap is grown by `depth`. A healthy contact is one strip (1, 0).
struct ContactStrip {
  double width_fraction = 1;  ///< [-], in (0, 1]
  double depth = 0;           ///< [m], the sum of the depths of the pits covering the strip
  int part = 0;               ///< its index among the contact's strips (0: the least deep)
};

/// The damage of a model's bodies, resolved against their names once.
class DamageModel {
 public:
  DamageModel() = default;
  /// `bodies[b]` is the name of body b (a stage's BodyName, or a pair's gear names). A pit on a
  /// gear that is not among them is left out: a stage mesh studied as a pair keeps the pits of
  /// its two gears (the scene reader has checked every name).
  DamageModel(const Damage& damage, const std::vector<std::string>& bodies);
  bool empty() const { return pits_.empty(); }

  /// The strips of a potential contact between bodies `body_a` and `body_b` into `out` (cleared):
  /// one strip (1, 0, 0) when neither flank is pitted at the contact point. A flank is pitted at
  /// the contact when the contact's point on it lies on its involute (a tip round's contact has
  /// the pit of the flank it touches, not of the round) within the pit's roll range. Pits of the
  /// two flanks both cover the face width from the same edge, so the strips are [0, w_min] with
  /// both depths, [w_min, w_max] with the wider pit's, [w_max, 1] with none (empty strips left
  /// out), ordered by depth.
  void Strips(int body_a, int body_b, const geometry::PotentialContact& contact,
              std::vector<ContactStrip>* out) const;
  /// The depth [m] by which the pits of the contact's two flanks lower the face at `fraction` of
  /// the face width from the edge the pits are measured from (Strips' breakpoints: a slice of
  /// the face width takes the depth at its centre).
  double DepthAt(int body_a, int body_b, const geometry::PotentialContact& contact,
                 double fraction) const;

 private:
  // The pit (width fraction, depth) on each flank of the contact, (0, 0) where none.
  void FlankPits(int body_a, int body_b, const geometry::PotentialContact& c, double w[2],
                 double d[2]) const;
  struct Resolved {
    int body = 0;
    Pit pit;
  };
  std::vector<Resolved> pits_;
};

/// Expands the quantities of the potential contacts of a model into those of its strips: strip s
/// is contact `source[s]` with overlap δ − depth (the other fields unchanged).
/// `out` receives, for every strip, the index of its source contact; returns false (and leaves
/// `out` the identity) when no contact is pitted. Strips whose gap exceeds `gap_window` [m] are
/// left out, as the contact search leaves out contacts beyond it (so a pit deeper than the window
/// removes its part of the contact). Without local terms (`local_terms` false) a pitted strip
/// beside an intact one can never carry (same compliance rows, gap larger by its depth): only the
/// least deep strip is kept, with its width fraction.
bool SplitContacts(const DamageModel& damage, const std::vector<int>& body_a,
                   const std::vector<int>& body_b,
                   const std::vector<geometry::PotentialContact>& contacts, double gap_window,
                   bool local_terms, std::vector<int>* source, std::vector<ContactStrip>* strips);

/// C_parts(s, t) = C(source[s], source[t]): the strips of a contact share its structural rows.
Eigen::MatrixXd ExpandCompliance(const Eigen::MatrixXd& compliance, const std::vector<int>& source);

}  // namespace epicycle::transmission
