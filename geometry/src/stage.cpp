#include "epicycle/geometry/stage.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/geometry/iso.hpp"
#include "messages.hpp"

namespace epicycle::geometry {

namespace {

GearSpec PlanetSpec(const StageSpec& s, int i) {
  GearSpec g = s.planet;
  if (!s.planet_thickness_errors.empty()) g.thickness_error += s.planet_thickness_errors.at(i);
  return g;
}

std::vector<Gear> MakePlanets(const StageSpec& s) {
  if (s.planets < 1 || s.planets > 12) {
    Fail("stage", "planets", std::to_string(s.planets), "must be in [1, 12]");
  }
  auto check_size = [&](std::size_t size, const char* key) {
    if (size != 0 && size != static_cast<std::size_t>(s.planets)) {
      Fail("errors", key, std::to_string(size) + " entries",
           "needs one entry per planet (" + std::to_string(s.planets) + ") or none");
    }
  };
  check_size(s.pin_errors.size(), "pin");
  check_size(s.planet_runouts.size(), "planet_runout");
  check_size(s.planet_thickness_errors.size(), "planet_thickness_um");
  if (!s.planet_angles.empty() && s.planet_angles.size() != static_cast<std::size_t>(s.planets)) {
    Fail("stage", "planet_angles_deg", std::to_string(s.planet_angles.size()) + " entries",
         "needs one angle per planet (" + std::to_string(s.planets) + ") or none");
  }
  std::vector<Gear> out;
  for (int i = 0; i < s.planets; ++i) out.emplace_back(PlanetSpec(s, i));
  return out;
}

// Helices first: gears of different helix angles differ in transverse module, which the module
// check would blame.
void CheckHelices(const StageSpec& s) {
  CheckMeshHelices(s.sun, s.planet, false);
  CheckMeshHelices(s.planet, s.ring, true);
}

double Sap(double rb, double roll) { return std::sqrt(rb * rb + roll * roll); }

}  // namespace

void CheckMesh(const Gear& g1, const Gear& g2, bool internal, double a, const std::string& owner) {
  // Tips against roots.
  auto need = [&](double clearance, const std::string& what) {
    if (clearance <= 0) {
      throw std::invalid_argument(owner + ": " + what + " (radial clearance " + Mm(clearance) +
                                  " mm)");
    }
  };
  const std::string n1 = g1.name(), n2 = g2.name();
  if (internal) {
    need(g2.root_radius() - a - g1.tip_radius(), "the " + n1 + "'s tip hits the " + n2 + "'s root");
    need(g2.tip_radius() - a - g1.root_radius(), "the " + n2 + "'s tip hits the " + n1 + "'s root");
  } else {
    need(a - g1.tip_radius() - g2.root_radius(), "the " + n1 + "'s tip hits the " + n2 + "'s root");
    need(a - g2.tip_radius() - g1.root_radius(), "the " + n2 + "'s tip hits the " + n1 + "'s root");
  }
  // Tips against fillets: the mate's tip circle must start the contact on the involute.
  const double aw = iso::PressureAngleAt(g1.module(), g1.teeth(), g2.teeth(),
                                         g1.spec().pressure_angle, a, internal);
  const double la = a * std::sin(aw);
  auto roll_len = [](const Gear& g, double r) {
    return std::sqrt(r * r - g.base_radius() * g.base_radius());
  };
  auto fillet = [&](const Gear& g, const std::string& mate, double sap) {
    const bool bad = g.internal() ? sap > g.form_radius() : sap < g.form_radius();
    if (bad) {
      throw std::invalid_argument(owner + ": tip-fillet interference: the " + mate +
                                  "'s tip reaches the " + g.name() + "'s flank at radius " +
                                  Mm(sap) + " mm, past its form radius " + Mm(g.form_radius()) +
                                  " mm");
    }
  };
  if (internal) {
    const double roll1 = roll_len(g2, g2.tip_radius()) - la;
    if (roll1 <= 0) {
      throw std::invalid_argument(owner + ": the " + n2 + "'s tip passes the " + n1 +
                                  "'s interference point");
    }
    fillet(g1, n2, Sap(g1.base_radius(), roll1));
    fillet(g2, n1, Sap(g2.base_radius(), roll_len(g1, g1.tip_radius()) + la));
  } else {
    const double roll1 = la - roll_len(g2, g2.tip_radius());
    const double roll2 = la - roll_len(g1, g1.tip_radius());
    if (roll1 <= 0 || roll2 <= 0) {
      throw std::invalid_argument(owner + ": a tip of the " + n1 + "-" + n2 +
                                  " mesh passes the interference point");
    }
    fillet(g1, n2, Sap(g1.base_radius(), roll1));
    fillet(g2, n1, Sap(g2.base_radius(), roll2));
  }
}

MeshSummary SummariseMesh(const Gear& g1, const Gear& g2, bool internal, double a) {
  const double alpha = g1.spec().pressure_angle;
  MeshSummary m;
  m.centre_distance = a;
  m.pressure_angle = iso::PressureAngleAt(g1.module(), g1.teeth(), g2.teeth(), alpha, a, internal);
  m.zero_backlash_pressure_angle = iso::ZeroBacklashPressureAngle(
      g1.teeth(), g2.teeth(), g1.spec().profile_shift, g2.spec().profile_shift, alpha, internal);
  m.normal_backlash = iso::NormalBacklash(
      g1.module(), g1.teeth(), g2.teeth(), g1.spec().profile_shift, g2.spec().profile_shift, alpha,
      a, internal, g1.spec().thickness_error, g2.spec().thickness_error);
  m.transverse_backlash = m.normal_backlash / std::cos(m.pressure_angle);
  m.contact_ratio_iso =
      iso::ContactRatio(g1.base_radius(), g1.tip_radius(), g2.base_radius(), g2.tip_radius(), a,
                        m.pressure_angle, g1.base_pitch(), internal);
  m.contact_ratio =
      iso::ContactRatio(g1.base_radius(), g1.tip_form_radius(), g2.base_radius(),
                        g2.tip_form_radius(), a, m.pressure_angle, g1.base_pitch(), internal);
  const double la = a * std::sin(m.pressure_angle);
  auto roll_len = [](const Gear& g, double r) {
    return std::sqrt(r * r - g.base_radius() * g.base_radius());
  };
  if (internal) {
    m.sap_a = Sap(g1.base_radius(), roll_len(g2, g2.tip_radius()) - la);
    m.sap_b = Sap(g2.base_radius(), roll_len(g1, g1.tip_radius()) + la);
  } else {
    m.sap_a = Sap(g1.base_radius(), la - roll_len(g2, g2.tip_radius()));
    m.sap_b = Sap(g2.base_radius(), la - roll_len(g1, g1.tip_radius()));
  }
  return m;
}

Stage::Stage(StageSpec spec)
    : spec_(std::move(spec)),
      sun_((CheckHelices(spec_), spec_.sun)),
      ring_(spec_.ring),
      planets_(MakePlanets(spec_)) {
  if (sun_.internal() || planets_[0].internal() || !ring_.internal()) {
    throw std::invalid_argument(
        "stage: the sun and planets must be external gears, the ring internal");
  }
  if (std::abs(sun_.module() - ring_.module()) > 1e-12 ||
      std::abs(sun_.module() - planets_[0].module()) > 1e-12) {
    Fail("ring", "module_mm", Mm(ring_.module()),
         "every gear of the stage must have the same module");
  }
  if (spec_.load_sign != 1 && spec_.load_sign != -1) {
    Fail("stage", "load_sign", std::to_string(spec_.load_sign), "must be +1 or -1");
  }
  RequirePositive("stage", "carrier_radius_mm", spec_.carrier_radius);
  for (const Runout* r : {&spec_.sun_runout, &spec_.ring_runout}) {
    if (!(r->amplitude >= 0)) Fail("errors", "runout_um", Num(r->amplitude * 1e6), "must be >= 0");
  }
  for (const Runout& r : spec_.planet_runouts) {
    if (!(r.amplitude >= 0))
      Fail("errors", "planet_runout_um", Num(r.amplitude * 1e6), "must be >= 0");
  }
  CheckAssembly();
  CheckClearances();
  Align();
  Summarise();
}

void Stage::CheckAssembly() {
  const int zsum = sun_.teeth() + ring_.teeth();
  const int n = planets();
  angles_.clear();
  if (spec_.planet_angles.empty()) {
    if (zsum % n != 0) {
      Fail("stage", "planets", std::to_string(n),
           "cannot be equally spaced: (z_sun + z_ring)/n = " + std::to_string(zsum) + "/" +
               std::to_string(n) +
               " is not whole (change a tooth count or give planet_angles_deg)");
    }
    for (int i = 0; i < n; ++i) angles_.push_back(2.0 * kPi * i / n);
    return;
  }
  for (int i = 0; i < n; ++i) {
    const double psi = spec_.planet_angles[i];
    const double teeth = zsum * psi / (2.0 * kPi);
    if (std::abs(teeth - std::round(teeth)) > 1e-9) {
      Fail("stage", "planet_angles_deg[" + std::to_string(i) + "]", Precise(Deg(psi)),
           "the planet cannot be assembled: (z_sun + z_ring)·ψ/360° = " + Precise(teeth) +
               " is not whole; the nearest angle that is: " +
               Num(std::round(teeth) * 360.0 / zsum) + "°");
    }
    angles_.push_back(psi);
  }
}

void Stage::CheckClearances() const {
  const double a = spec_.carrier_radius;
  const Gear& p = planets_[0];
  // Neighbouring planets (in angle order; `order` keeps their indices).
  std::vector<std::size_t> order(angles_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return angles_[x] < angles_[y]; });
  for (std::size_t i = 0; i < order.size() && order.size() > 1; ++i) {
    const std::size_t j = order[i], k = order[(i + 1) % order.size()];
    const double next = i + 1 < order.size() ? angles_[k] : angles_[k] + 2.0 * kPi;
    const double gap = 2.0 * a * std::sin((next - angles_[j]) / 2.0) - 2.0 * p.tip_radius();
    if (gap < spec_.min_planet_gap) {
      const std::string clash =
          "tip circles are " + Mm(gap) +
          " mm apart, less than min_planet_gap_mm = " + Mm(spec_.min_planet_gap);
      if (spec_.planet_angles.empty())
        Fail("stage", "planets", std::to_string(planets()),
             "neighbouring planets clash: their " + clash);
      // Angles given: the later of the two planets, with the spacing neighbours need,
      // 2 asin((2 r_a + gap)/(2 a)).
      const double need =
          2.0 * std::asin(std::min(1.0, (2.0 * p.tip_radius() + spec_.min_planet_gap) / (2.0 * a)));
      const std::size_t later = std::max(j, k), earlier = std::min(j, k);
      Fail("stage", "planet_angles_deg[" + std::to_string(later) + "]",
           Precise(Deg(angles_[later])),
           "clashes with planet " + std::to_string(earlier + 1) + " at " +
               Precise(Deg(angles_[earlier])) + "° (their " + clash +
               "): neighbouring planets must be at least " + Num(Deg(need)) + "° apart");
    }
  }
  CheckMesh(sun_, p, false, a, "stage");
  CheckMesh(p, ring_, true, a, "stage");
}

void Stage::Align() {
  // Turn each planet until its loaded flank touches the ring, then the sun until its loaded
  // flank touches planet 1 (d δ/d θ_A = σ_A r_bA for the gear A of a pair).
  sun_turn0_ = 0;
  planet_turn0_.assign(planets(), 0.0);
  const StagePoses p = Poses(0.0, false);
  for (int i = 0; i < planets(); ++i) {
    const int side = ring_mesh_planet_side();
    const double d = NearestLoaOverlap(Planet(p, i), Ring(p), true, side);
    planet_turn0_[i] = -d / (side * planets_[i].base_radius());
  }
  const StagePoses q = Poses(0.0, false);
  const double d = NearestLoaOverlap(Sun(q), Planet(q, 0), false, sun_mesh_side());
  sun_turn0_ = -d / (sun_mesh_side() * sun_.base_radius());
}

StagePoses Stage::Poses(double carrier_angle, bool with_errors) const {
  StagePoses p;
  Poses(carrier_angle, &p, with_errors);
  return p;
}

void Stage::Poses(double carrier_angle, StagePoses* out, bool with_errors) const {
  StagePoses& p = *out;
  p.carrier_angle = carrier_angle;
  auto place = [&](const Vec2& centre, double rotation, const Runout& r) {
    GearPose g;
    g.rotation_centre = centre;
    g.rotation = rotation;
    g.geometric_centre = centre;
    if (with_errors) g.geometric_centre += r.amplitude * Dir(rotation + r.phase);
    return g;
  };
  p.sun = place(Vec2::Zero(), sun_turn0_ + sun_ratio() * carrier_angle, spec_.sun_runout);
  p.ring = place(Vec2::Zero(), 0.0, spec_.ring_runout);
  p.planets.resize(static_cast<std::size_t>(planets()));
  for (int i = 0; i < planets(); ++i) {
    const Runout r = spec_.planet_runouts.empty() ? Runout{} : spec_.planet_runouts[i];
    p.planets[i] = place(Pin(i, carrier_angle, with_errors),
                         planet_turn0_[i] + planet_ratio() * carrier_angle, r);
  }
}

Vec2 Stage::Pin(int planet, double carrier_angle, bool with_errors) const {
  const double dir = carrier_angle + angles_.at(planet);
  Vec2 c = spec_.carrier_radius * Dir(dir);
  if (with_errors && !spec_.pin_errors.empty()) {
    const PinError& e = spec_.pin_errors[planet];
    c += e.radial * Dir(dir) + e.tangential * DirPerp(dir);
  }
  return c;
}

std::vector<PotentialContact> Stage::Contacts(const StagePoses& p, int planet, MeshKind kind,
                                              const ContactSearchOptions& options) const {
  if (kind == MeshKind::kSunPlanet) return FindContacts(Sun(p), Planet(p, planet), false, options);
  return FindContacts(Planet(p, planet), Ring(p), true, options);
}

void Stage::AppendContacts(const StagePoses& p, int planet, MeshKind kind,
                           const ContactSearchOptions& options, std::vector<PotentialContact>* out,
                           TipRoundReuse* reuse) const {
  if (kind == MeshKind::kSunPlanet) {
    geometry::AppendContacts(Sun(p), Planet(p, planet), false, options, out, reuse);
  } else {
    geometry::AppendContacts(Planet(p, planet), Ring(p), true, options, out, reuse);
  }
}

bool Stage::HasLineOfAction(const StagePoses& p, int planet, MeshKind kind) const {
  if (kind == MeshKind::kSunPlanet)
    return geometry::HasLineOfAction(Sun(p), Planet(p, planet), false);
  return geometry::HasLineOfAction(Planet(p, planet), Ring(p), true);
}

void Stage::Summarise() {
  meshes_.clear();
  for (int i = 0; i < planets(); ++i) {
    const Gear& p = planets_[i];
    const double phase = std::fmod(sun_.teeth() * angles_[i] / (2.0 * kPi), 1.0);
    for (MeshKind kind : {MeshKind::kSunPlanet, MeshKind::kPlanetRing}) {
      const bool internal = kind == MeshKind::kPlanetRing;
      MeshSummary m = internal ? SummariseMesh(p, ring_, true, spec_.carrier_radius)
                               : SummariseMesh(sun_, p, false, spec_.carrier_radius);
      m.kind = kind;
      m.planet = i;
      m.name = MeshName(i, kind);
      m.phase = phase < 0 ? phase + 1.0 : phase;
      meshes_.push_back(m);
    }
  }
}

std::string MeshName(int planet, MeshKind kind) {
  return kind == MeshKind::kPlanetRing ? "planet" + std::to_string(planet + 1) + "-ring"
                                       : "sun-planet" + std::to_string(planet + 1);
}

}  // namespace epicycle::geometry
