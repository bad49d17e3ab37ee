#include "epicycle/geometry/pair.hpp"

#include <stdexcept>

#include "epicycle/geometry/helical.hpp"
#include "messages.hpp"

namespace epicycle::geometry {

GearPair::GearPair(PairSpec spec)
    : spec_(std::move(spec)),
      g1_((CheckMeshHelices(spec_.gear1, spec_.gear2, spec_.gear2.kind == GearKind::kInternal),
           spec_.gear1)),
      g2_(spec_.gear2) {
  if (g1_.internal()) Fail("pair", "gear1", g1_.name(), "gear 1 must be an external gear");
  if (std::abs(g1_.module() - g2_.module()) > 1e-12) {
    Fail("pair", "gear2.module_mm", Mm(g2_.module()), "both gears must have the same module");
  }
  if (spec_.load_sign != 1 && spec_.load_sign != -1) {
    Fail("pair", "load_sign", std::to_string(spec_.load_sign), "must be +1 or -1");
  }
  RequirePositive("pair", "centre_distance_mm", spec_.centre_distance);
  CheckMesh(g1_, g2_, internal(), spec_.centre_distance, "pair");
  summary_ = SummariseMesh(g1_, g2_, internal(), spec_.centre_distance);
  summary_.name = g1_.name() + "-" + g2_.name();
  // Turn gear 2 until the loaded flanks touch: along the line of action d δ/d θ_B = σ_B r_bB.
  const PairPoses p0 = Poses(0.0);
  const int side_b = internal() ? -loaded_side() : loaded_side();
  turn2_ =
      -NearestLoaOverlap(A(p0), B(p0), internal(), loaded_side()) / (side_b * g2_.base_radius());
}

double GearPair::ratio() const {
  const double r = static_cast<double>(g1_.teeth()) / g2_.teeth();
  return internal() ? r : -r;
}

PairPoses GearPair::Poses(double angle) const {
  PairPoses p;
  p.angle = angle;
  p.gear1.rotation = angle;
  p.gear2.rotation_centre = p.gear2.geometric_centre = Vec2(spec_.centre_distance, 0.0);
  p.gear2.rotation = turn2_ + ratio() * angle;
  return p;
}

std::vector<PotentialContact> GearPair::Contacts(const PairPoses& p,
                                                 const ContactSearchOptions& o) const {
  return FindContacts(A(p), B(p), internal(), o);
}

}  // namespace epicycle::geometry
