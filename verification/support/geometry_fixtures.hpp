// Gears and stages of the shipped scenes built through geometry's API alone, for the geometry
// suite (which does not link the scene reader of transmission/). Each value is computed as the
// scene reader computes it from the file (the same products and the same backlash fits), and the
// transmission suite checks that reading the scene gives exactly these specs
// (unit/transmission/geometry_fixtures.cpp), so the two cannot drift apart.
#pragma once

#include <cmath>
#include <vector>

#include "epicycle/geometry/contact.hpp"
#include "epicycle/geometry/gear.hpp"
#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/plane.hpp"
#include "epicycle/geometry/stage.hpp"

namespace epicycle::test {

/// A profile shift solved for a normal backlash, as a scene's [[fit]] table gives it.
struct FittedShift {
  double profile_shift = 0;    ///< x [-]
  double normal_backlash = 0;  ///< j_n [m]
};

/// The paper's stage of scenes/paper_stage.toml: its spec and the two fits (planet in the
/// sun–planet mesh, ring in the planet–ring mesh).
struct PaperStageFixture {
  geometry::StageSpec stage;
  std::vector<FittedShift> fits;
};

namespace internal {

constexpr double kMm = 1e-3, kUm = 1e-6;

// A gear of the paper's table as the scene gives it (module 4.23 mm, 25 mm wide, 25°, tip round
// 0.2115 mm); the tip and root radii are set once the shift is final.
inline geometry::GearSpec PaperGear(const char* name, geometry::GearKind kind, int teeth) {
  geometry::GearSpec g;
  g.name = name;
  g.kind = kind;
  g.teeth = teeth;
  g.module = 4.23 * kMm;
  g.face_width = 25.0 * kMm;
  g.pressure_angle = geometry::Rad(25.0);
  g.tip_round_radius = 0.2115 * kMm;
  g.min_tip_thickness = -1;
  return g;
}

// As a scene gives them, a tip (and a directly defined ring's root) given as a coefficient h* is
// held as −h* until the shift is final; then r_a = r + x m ± h_a* m (a ring's tip inside) and
// r_f = r + x m + h_f* m.
inline void ResolveRadii(geometry::GearSpec& g) {
  const double r = g.module * g.teeth / 2.0, xm = g.profile_shift * g.module;
  const double sign = g.kind == geometry::GearKind::kInternal ? -1.0 : 1.0;
  if (g.tip_radius < 0) g.tip_radius = r + xm + sign * (-g.tip_radius) * g.module;
  if (g.root_radius < 0) g.root_radius = r + xm + (-g.root_radius) * g.module;
}

}  // namespace internal

/// scenes/paper_stage.toml (16/24/65, sun shift 0.30, carrier radius 86.715 mm, sun torque
/// −600 N·m) with both meshes fitted to `normal_backlash_um` (the file: 150).
inline PaperStageFixture PaperStage(double normal_backlash_um = 150.0) {
  using internal::kMm;
  using internal::kUm;
  PaperStageFixture f;
  geometry::StageSpec& st = f.stage;
  st.sun = internal::PaperGear("sun", geometry::GearKind::kExternal, 16);
  st.sun.profile_shift = 0.30;
  st.sun.tip_radius = -1.0;  // addendum_per_module = 1.0
  st.sun.hub_radius = 20.0 * kMm;
  st.sun.rack =
      geometry::RackCutter{1.35 * st.sun.module, 1.15 * st.sun.module, 0.05 * st.sun.module};
  st.planet = internal::PaperGear("planet", geometry::GearKind::kExternal, 24);
  st.planet.tip_radius = -1.0;
  st.planet.hub_radius = 20.0 * kMm;
  st.planet.rack = geometry::RackCutter{1.35 * st.planet.module, 1.25 * st.planet.module,
                                        0.05 * st.planet.module};
  st.ring = internal::PaperGear("ring", geometry::GearKind::kInternal, 65);
  st.ring.tip_radius = -1.0;
  st.ring.hub_radius = 156.4 * kMm;  // the rim
  st.ring.root_radius = -1.35;       // dedendum_per_module = 1.35
  st.ring.root_round_radius = 0.2115 * kMm;
  st.carrier_radius = 86.715 * kMm;
  st.planets = 3;
  st.min_planet_gap = 1.0 * kMm;
  st.load_sign = -1;
  const double backlash = normal_backlash_um * kUm;
  // [[fit]] planet in the sun–planet mesh, then the ring in the planet–ring mesh (gear 2 of each).
  st.planet.profile_shift =
      geometry::iso::FitProfileShift(st.sun, st.planet, false, 2, st.carrier_radius, backlash);
  f.fits.push_back({st.planet.profile_shift, backlash});
  st.ring.profile_shift =
      geometry::iso::FitProfileShift(st.planet, st.ring, true, 2, st.carrier_radius, backlash);
  f.fits.push_back({st.ring.profile_shift, backlash});
  for (geometry::GearSpec* g : {&st.sun, &st.planet, &st.ring}) internal::ResolveRadii(*g);
  return f;
}

/// scenes/iso_pair_20_40.toml: 20/40 teeth, m 4 mm, 20°, no shift, centre distance 120 mm, ISO 53
/// profile A racks (1.25 m, 1.0 m, tip round 0.38 m), torque +200 N·m on gear 1.
inline geometry::PairSpec IsoPair2040() {
  using internal::kMm;
  geometry::PairSpec p;
  const auto gear = [](const char* name, int teeth, double hub_mm) {
    geometry::GearSpec g;
    g.name = name;
    g.teeth = teeth;
    g.module = 4.0 * kMm;
    g.face_width = 20.0 * kMm;
    g.pressure_angle = geometry::Rad(20.0);
    g.profile_shift = 0.0;
    g.tip_round_radius = 0.08 * kMm;
    g.min_tip_thickness = -1;
    g.hub_radius = hub_mm * kMm;
    g.rack = geometry::RackCutter{1.25 * g.module, 1.0 * g.module, 0.38 * g.module};
    return g;
  };
  p.gear1 = gear("gear1", 20, 16.0);
  p.gear2 = gear("gear2", 40, 32.0);
  p.centre_distance = 120.0 * kMm;
  p.load_sign = 1;
  return p;
}

/// The start radius of a relief given by its roll angle u [deg]: r_b √(1 + u²).
inline double ReliefStartRadius(const geometry::GearSpec& g, double roll_deg) {
  return 0.5 * g.module * g.teeth * std::cos(g.pressure_angle) *
         std::hypot(1.0, geometry::Rad(roll_deg));
}

/// Tip and root relief given by roll angle on the sun, tip relief on the planet, and ISO 1328-1
/// pitch deviations of grades 6 (sun) and 7 (planet), as a scene's [<gear>.modification] and
/// [<gear>.pitch] tables set them: the modifications that widen the contact search's tip-round
/// filter (a relieved mate, teeth turned by their offsets).
inline void AddReliefAndPitchDeviations(geometry::StageSpec& s) {
  using geometry::ReliefShape;
  s.sun.modification.tip = {8e-6, ReliefStartRadius(s.sun, 30.0), ReliefShape::kLinear};
  s.sun.modification.root = {5e-6, ReliefStartRadius(s.sun, 20.0), ReliefShape::kLinear};
  s.sun.pitch_deviations = geometry::iso::RandomPitchDeviations(s.sun.teeth, s.sun.module, 6, 3);
  s.planet.modification.tip = {10e-6, ReliefStartRadius(s.planet, 30.0), ReliefShape::kParabolic};
  s.planet.pitch_deviations =
      geometry::iso::RandomPitchDeviations(s.planet.teeth, s.planet.module, 7, 5);
}

/// Every potential contact of every mesh of the stage at poses p: f(a, b, kind, contact), with a
/// and b the mesh's first and second gear (sun–planet i, or planet i–ring).
template <typename F>
void ForEachStageContact(const geometry::Stage& st, const geometry::StagePoses& p,
                         const geometry::ContactSearchOptions& opt, F&& f) {
  for (int i = 0; i < st.planets(); ++i) {
    for (geometry::MeshKind kind :
         {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
      const geometry::PosedGear a =
          kind == geometry::MeshKind::kSunPlanet ? st.Sun(p) : st.Planet(p, i);
      const geometry::PosedGear b =
          kind == geometry::MeshKind::kSunPlanet ? st.Planet(p, i) : st.Ring(p);
      for (const geometry::PotentialContact& c : st.Contacts(p, i, kind, opt)) f(a, b, kind, c);
    }
  }
}

}  // namespace epicycle::test
