// A single gear pair (external, or a pinion inside an internal gear) at a centre distance: the
// layout behind mesh-stiffness studies. Gear 1 turns about the origin, gear 2 about (a, 0).
#pragma once

#include <vector>

#include "epicycle/geometry/contact.hpp"
#include "epicycle/geometry/stage.hpp"

namespace epicycle::geometry {

struct PairSpec {
  GearSpec gear1, gear2;       ///< gear 2 internal: an internal pair with gear 1 inside it
  double centre_distance = 0;  ///< a [m]
  int load_sign = 1;           ///< sign of the torque on gear 1: which flanks carry the load
};

struct PairPoses {
  double angle = 0;  ///< rotation of gear 1 from its aligned start [rad]
  GearPose gear1, gear2;
};

class GearPair {
 public:
  /// @throws std::invalid_argument for gears that cannot be made or that interfere.
  explicit GearPair(PairSpec spec);

  const PairSpec& spec() const { return spec_; }
  const Gear& gear1() const { return g1_; }
  const Gear& gear2() const { return g2_; }
  bool internal() const { return g2_.internal(); }
  const MeshSummary& summary() const { return summary_; }
  int loaded_side() const { return spec_.load_sign; }            ///< σ of gear 1's loaded flanks
  double mesh_cycle() const { return 2.0 * kPi / g1_.teeth(); }  ///< gear-1 turn per cycle [rad]
  /// Gear 2's turn per unit turn of gear 1: −z1/z2 (external) or +z1/z2 (internal).
  double ratio() const;

  /// Rigid poses with gear 1 turned by `angle` from the start where the loaded flanks touch.
  PairPoses Poses(double angle) const;
  PosedGear A(const PairPoses& p) const { return {&g1_, p.gear1}; }
  PosedGear B(const PairPoses& p) const { return {&g2_, p.gear2}; }
  std::vector<PotentialContact> Contacts(const PairPoses& p, const ContactSearchOptions& o) const;

 private:
  PairSpec spec_;
  Gear g1_, g2_;
  MeshSummary summary_;
  double turn2_ = 0;  // gear 2's rotation at angle 0
};

}  // namespace epicycle::geometry
