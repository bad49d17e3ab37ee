#include "epicycle/transmission/scene.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/geometry/helical.hpp"
#include "epicycle/geometry/iso.hpp"
#include "epicycle/io/input_file.hpp"
#include "epicycle/io/toml_reader.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "scene_internal.hpp"

namespace epicycle::transmission {

using geometry::GearKind;
using geometry::GearSpec;
using io::ParseDocument;
using io::Rule;
using io::TableReader;

namespace {

using internal::HandFromName;
using internal::kHelixRule;
using internal::kMm;
using internal::kUm;
using internal::ReadDamage;
using internal::ReadFaceWidth;
using internal::ReadGear;
using internal::ReadInertia;

// Physical ranges of the scene's values (docs/scenes.md, "Ranges and validity"). Sizes are
// relative to the module, errors to the module (errors) and to the backlash (warnings).
constexpr double kErrorModules = 0.25;           // |error| ≤ m/4
constexpr double kBacklashModules = 0.25;        // 0 ≤ j_n ≤ m/4
constexpr double kYoungsRangeGPa[2] = {1.0, 1200.0};
constexpr double kContactLimitMPa[2] = {100.0, 2500.0};  // σ_Hlim
constexpr double kBendingLimitMPa[2] = {50.0, 1000.0};   // σ_Flim
constexpr double kCarrierModules = 2.0;                  // |a_c − m(z_s + z_p)/2| ≤ 2 m

// [contact] gap_window_um: from 1 µm up to a quarter module, the size of the largest error the
// scene takes (the window must hold the gaps that deflections and errors can close, no more).
double ReadGapWindow(TableReader& t, double module) {
  const double hi = module / 4 / kUm;
  return t.RealOr("gap_window_um", 100.0,
                  Rule::Closed(1, hi).Because(
                      "at least 1 um, up to a quarter module: the gaps that deflections and "
                      "errors can close")) *
         kUm;
}

// A bearing's stiffness [N/um]: rolling bearings of gears are 1e2 .. 1e4 N/um; below 1 the member
// floats on it, above 1e6 it is rigid (a fixed support, or rigid pins).
const Rule kBearingRule = Rule::Closed(1, 1e6).Because(
    "rolling bearings are 1e2 .. 1e4 N/um; below 1 the member floats, above 1e6 it is rigid");
constexpr int kRingTeethSlack = 4;  // |z_r − z_s − 2 z_p| ≤ 4

Rule ErrorRule(double module) {
  const double e = kErrorModules * module / kUm;
  return Rule::Closed(-e, e).Because(
      "a quarter of the module in um: a larger error moves a tooth by a large part of its "
      "thickness, outside the small-error geometry of the model");
}

Rule BacklashRule(double module) {
  return Rule::Closed(0, kBacklashModules * module / kUm)
      .Because(
          "0 to a quarter of the module in um: a negative backlash is an interference fit, "
          "which the model does not have");
}

// An error value with its key, kept to be compared with the backlash once the shifts are final.
struct ErrorKey {
  std::string where;  // "file:line: errors.runout[0].amplitude_um = 20"
  double value = 0;   // |error| [m]
  int gear = 0;       // -1 sun, -2 ring, else the planet index
};

// The optional [dynamics] and [lubricant] tables (docs/scenes.md), with their cross-key rules
// (DynamicSettings::Validate's) named at the key the user wrote.
void ReadDynamics(TableReader& top, DynamicSettings& d, std::vector<std::string>* warnings) {
  if (auto t = top.OptionalTable("dynamics")) {
    // The rule of every sun speed a run is given (run_arguments.hpp: --speed-rpm, Python's).
    d.sun_speed = io::RpmToRadPerSecond(
        t->RealOr("sun_speed_rpm", 1500.0,
                  Rule::Closed(kSunSpeedRpm.lo, kSunSpeedRpm.hi).Because(kSunSpeedRpm.why)));
    d.carrier_free = t->StringOr("carrier", "speed", {"speed", "torque"}) == "torque";
    d.carrier_load_inertia = t->RealOr("carrier_load_inertia_kgm2", 0.0, Rule::NonNegative());
    d.sun_speed_driven = t->StringOr("sun", "torque", {"torque", "speed"}) == "speed";
    if (d.sun_speed_driven && !d.carrier_free)
      t->Fail("sun", "\"speed\"",
              "needs carrier = \"torque\": with both the sun and the carrier turned at prescribed "
              "speeds nothing carries the load");
    d.carrier_stiffness = t->RealOr("carrier_stiffness_N_per_um", 0.0, Rule::NonNegative()) * 1e6;
    d.carrier_damping = t->RealOr("carrier_damping_Ns_per_m", 0.0, Rule::NonNegative());
    d.mesh_damping_ratio = t->RealOr("mesh_damping_ratio", 0.05, Rule::Closed(0, 1));
    d.mesh_damping = t->RealOr("mesh_damping_Ns_per_m", 0.0, Rule::NonNegative());
    d.sun_bearing_damping = t->RealOr("sun_bearing_damping_Ns_per_m", 0.0, Rule::NonNegative());
    d.planet_bearing_damping =
        t->RealOr("planet_bearing_damping_Ns_per_m", 0.0, Rule::NonNegative());
    d.ring_elastic = t->StringOr("ring", "fixed", {"fixed", "elastic"}) == "elastic";
    if (d.ring_elastic) {
      d.ring_stiffness = t->Real("ring_stiffness_N_per_um", Rule::NonNegative()) * 1e6;
      d.ring_torsional_stiffness = t->Real("ring_torsional_stiffness_Nm_per_rad", Rule::Positive());
      d.ring_damping = t->RealOr("ring_damping_Ns_per_m", 0.0, Rule::NonNegative());
      d.ring_torsional_damping =
          t->RealOr("ring_torsional_damping_Nms_per_rad", 0.0, Rule::NonNegative());
    }
    d.friction.law =
        FrictionLawFromName(t->StringOr("friction", "xu-kahraman", io::Names(kFrictionLawNames)));
    d.friction.coefficient = t->RealOr("friction_coefficient", 0.05, Rule::Closed(0, 1));
    t->Done();
  }
  if (auto t = top.OptionalTable("lubricant")) {
    // The lubricated laws (docs/friction.md) are regressions on gear oils at their
    // running temperatures, ISO VG 22 at 100 C (about 3 mPa s) to VG 1000 at 40 C (about 900):
    // outside [2, 1000] they are extrapolated (a warning). Below 0.1 mPa s Xu-Kahraman's
    // e^(b5 e^(-SR P_h log10 nu0)) overflows (at 0.078 for SR = 2, P_h = 2.5 GPa): no finite
    // coefficient; above 1e4 its coefficient passes the cap in most contacts (median 0.78 over
    // P_h 0.3-2.5 GPa, SR 0.05-2, V_e 1-30 m/s, R 3-50 mm) and Benedict-Kelley's logarithm turns
    // negative (no friction): the laws give no coefficient of the contact, only their bounds.
    const double nu = t->RealOr(
        "viscosity_mPas", 50.0,
        Rule::Closed(0.1, 1e4).Because(
            "below 0.1 Xu-Kahraman's law overflows (no finite coefficient); above 1e4 both "
            "lubricated laws are pinned at their bounds (the cap, or no friction) in most "
            "contacts"));
    if (nu < 2 || nu > 1000)
      warnings->push_back(
          t->Warning("viscosity_mPas",
                     "outside [2, 1000], the gear oils at running temperature that the "
                     "friction laws were fitted on: the coefficients are extrapolated"));
    d.friction.lubricant.dynamic_viscosity = nu * 1e-3;
    const double roughness_um = t->RealOr("roughness_um", 0.8, Rule::Positive());
    // Benedict & Kelley's roughness factor 50/(50 − S) takes S in µin: S < 50 µin = 1.27 µm.
    if (d.friction.law == FrictionLaw::kBenedictKelley && !(roughness_um < 1.27))
      t->Fail("roughness_um", io::Num(roughness_um, io::kInputDigits),
              "must be < 1.27 (50 microinch) for friction = \"benedict-kelley\" (its roughness "
              "factor 50/(50 - S))");
    d.friction.lubricant.composite_roughness = roughness_um * kUm;
    t->Done();
  }
}

// "sun", "ring", "planet1".."planetN" → -1 (sun), -2 (ring), or the 0-based planet index.
int GearIndex(TableReader& t, const std::string& key, int planets) {
  const std::string v = t.String(key);
  if (v == "sun") return -1;
  if (v == "ring") return -2;
  if (v.rfind("planet", 0) == 0 && v.size() > 6) {
    try {
      const int i = std::stoi(v.substr(6));
      if (i >= 1 && i <= planets) return i - 1;
    } catch (const std::exception&) {
    }
  }
  t.Fail(key, "\"" + v + "\"",
         "must be \"sun\", \"ring\" or \"planet1\"..\"planet" + std::to_string(planets) + "\"");
}

// Meshing gears share module and pressure angle: a mismatch is blamed on the gear read second.
// The helix angle first: gears of different helix angles differ in transverse module. Module and
// pressure angle are told in the section the scene gives them (the normal section).
void SameAsMate(TableReader& t, const GearSpec& g, const GearSpec& mate, const std::string& name) {
  if (std::abs(g.helix.angle - mate.helix.angle) > 1e-12) {
    t.Fail("helix_angle_deg", io::Num(geometry::Deg(g.helix.angle), io::kInputDigits),
           "must equal " + name +
               ".helix_angle_deg = " + io::Num(geometry::Deg(mate.helix.angle), io::kInputDigits) +
               " (gears that mesh share the helix angle at the reference cylinder)");
  }
  const double c = std::cos(g.helix.angle);  // 1 for spur gears
  auto normal_angle = [&](double alpha_t) {
    return g.helix.helical() ? std::atan(std::tan(alpha_t) * c) : alpha_t;
  };
  if (std::abs(g.module - mate.module) > 1e-12 * mate.module) {
    t.Fail("module_mm", io::Num(g.module * c / kMm, io::kInputDigits),
           "must equal " + name + ".module_mm = " + io::Num(mate.module * c / kMm, io::kInputDigits) +
               " (gears that mesh share the module)");
  }
  if (std::abs(g.pressure_angle - mate.pressure_angle) > 1e-12) {
    t.Fail("pressure_angle_deg", io::Num(normal_angle(g.pressure_angle) * 180.0 / geometry::kPi, io::kInputDigits),
           "must equal " + name + ".pressure_angle_deg = " +
               io::Num(normal_angle(mate.pressure_angle) * 180.0 / geometry::kPi, io::kInputDigits) +
               " (gears that mesh share the pressure angle)");
  }
}

const GearSpec& GearOf(const geometry::StageSpec& st, int i) {
  return i == -1 ? st.sun : i == -2 ? st.ring : st.planet;
}

// One table of a kind per gear: a second one for the same gear is refused, naming both (it would
// otherwise replace the first without a word).
class OneTablePerGear {
 public:
  explicit OneTablePerGear(std::string kind) : kind_(std::move(kind)) {}
  void Add(const TableReader& t, int gear) {
    const auto [first, fresh] = seen_.emplace(gear, t.Where("gear"));
    if (fresh) return;
    const std::string name = gear == -1   ? "sun"
                             : gear == -2 ? "ring"
                                          : "planet" + std::to_string(gear + 1);
    t.Fail("gear", "\"" + name + "\"",
           "a second [[errors." + kind_ + "]] for " + (gear < 0 ? "the " : "") + name +
               " (the first: " + first->second + "); give one per gear");
  }

 private:
  std::string kind_;
  std::map<int, std::string> seen_;
};

void ReadErrors(TableReader& e, Scene& s, std::vector<ErrorKey>* keys) {
  geometry::StageSpec& st = s.stage;
  const int n = st.planets;
  auto keep = [&](TableReader& t, const std::string& key, double value, int gear) {
    if (t.Has(key)) keys->push_back({t.Warning(key, ""), std::abs(value), gear});
  };
  OneTablePerGear pins("pin"), runouts("runout"), thicknesses("thickness");
  for (TableReader& p : e.TableArray("pin")) {
    const int i = GearIndex(p, "gear", n);
    if (i < 0) p.Fail("gear", i == -1 ? "\"sun\"" : "\"ring\"", "pin errors belong to planets");
    pins.Add(p, i);
    if (st.pin_errors.empty()) st.pin_errors.assign(n, {});
    const Rule rule = ErrorRule(st.planet.module);
    st.pin_errors[i].radial = p.RealOr("radial_um", 0.0, rule) * kUm;
    st.pin_errors[i].tangential = p.RealOr("tangential_um", 0.0, rule) * kUm;
    keep(p, "radial_um", st.pin_errors[i].radial, i);
    keep(p, "tangential_um", st.pin_errors[i].tangential, i);
    p.Done();
  }
  for (TableReader& r : e.TableArray("runout")) {
    const int i = GearIndex(r, "gear", n);
    runouts.Add(r, i);
    geometry::Runout ro;
    const Rule rule = ErrorRule(GearOf(st, i).module);
    ro.amplitude = r.Real("amplitude_um", Rule::Closed(0, rule.hi).Because(rule.why)) * kUm;
    keep(r, "amplitude_um", ro.amplitude, i);
    ro.phase = geometry::Rad(
        r.RealOr("phase_deg", 0.0,
                 Rule::Closed(-360, 360).Because("an angle of the gear: one turn either way")));
    if (i == -1) {
      st.sun_runout = ro;
    } else if (i == -2) {
      st.ring_runout = ro;
    } else {
      if (st.planet_runouts.empty()) st.planet_runouts.assign(n, {});
      st.planet_runouts[i] = ro;
    }
    r.Done();
  }
  for (TableReader& th : e.TableArray("thickness")) {
    const int i = GearIndex(th, "gear", n);
    thicknesses.Add(th, i);
    const double ds = th.Real("error_um", ErrorRule(GearOf(st, i).module)) * kUm;
    keep(th, "error_um", ds, i);
    if (i == -1) {
      st.sun.thickness_error = ds;
    } else if (i == -2) {
      st.ring.thickness_error = ds;
    } else {
      if (st.planet_thickness_errors.empty()) st.planet_thickness_errors.assign(n, 0.0);
      st.planet_thickness_errors[i] = ds;
    }
    th.Done();
  }
}

// Addendum/dedendum coefficients (stored negative by ReadGear) become radii once x is final.
// The coefficients are in normal modules m_n = m_t cos β (= m for a spur gear); x_t m_t = x_n m_n.
void ResolveRadii(GearSpec& g) {
  const double r = g.module * g.teeth / 2.0, xm = g.profile_shift * g.module;
  const double sign = g.kind == GearKind::kInternal ? -1.0 : 1.0;  // a ring's tip is inside
  const double mn = g.module * std::cos(g.helix.angle);
  if (g.tip_radius < 0) g.tip_radius = r + xm + sign * (-g.tip_radius) * mn;
  if (g.root_radius < 0) g.root_radius = r + xm + (-g.root_radius) * mn;
}

template <typename Fitted>
void ReadPair(TableReader& top, Scene& s, std::vector<TableReader>& fits,
              const std::vector<std::string>& fit_gears, Fitted&& fitted) {
  geometry::PairSpec& p = s.pair;
  bool internal = false;
  // centre_distance_mm is checked against the gears once they are read.
  TableReader pair_table = top.Table("pair");
  p.centre_distance = pair_table.Real("centre_distance_mm", Rule::Positive()) * kMm;
  internal = pair_table.BoolOr("internal", false);
  Inertia unused;
  {
    TableReader t = top.Table("gear1");
    p.gear1 = ReadGear(t, "gear1", GearKind::kExternal, fitted("gear1"), &unused);
    t.Done();
  }
  {
    TableReader t = top.Table("gear2");
    p.gear2 = ReadGear(t, "gear2", internal ? GearKind::kInternal : GearKind::kExternal,
                       fitted("gear2"), &unused);
    t.Done();
  }
  {
    // As the carrier radius: m (z2 ∓ z1)/2 without shift, within 2 modules.
    const double m_mm = p.gear1.module / kMm;
    const double a0 =
        m_mm * (internal ? p.gear2.teeth - p.gear1.teeth : p.gear2.teeth + p.gear1.teeth) / 2.0;
    // A helical pair's module is the transverse one, m_t = m_n/cos β: say so, naming m_n.
    const std::string m =
        p.gear1.helix.helical()
            ? "m_t = gear1.module_mm/cos(beta) = " + io::Num(m_mm, io::kInputDigits) +
                  " mm (module_mm = " + io::Num(m_mm * std::cos(p.gear1.helix.angle), io::kInputDigits) +
                  ", helix_angle_deg = " + io::Num(geometry::Deg(p.gear1.helix.angle), io::kInputDigits) + "): m_t"
            : "m";
    pair_table.Check(
        "centre_distance_mm", p.centre_distance / kMm,
        Rule::Closed(a0 - kCarrierModules * m_mm, a0 + kCarrierModules * m_mm)
            .Because(m + (internal ? " (z2 - z1)/2 = " : " (z1 + z2)/2 = ") + io::Num(a0, io::kInputDigits) +
                     " mm within 2 modules (profile shifts move it by about x m)"));
    pair_table.Done();
  }
  {
    TableReader t = top.Table("load");
    s.pair_torque = t.Real("gear1_torque_Nm", Rule::Any());
    if (s.pair_torque == 0) {
      t.Fail("gear1_torque_Nm", "0", "must be non-zero (its sign selects the loaded flanks)");
    }
    p.load_sign = s.pair_torque > 0 ? 1 : -1;
    t.Done();
  }
  if (auto t = top.OptionalTable("contact")) {
    s.gap_window = ReadGapWindow(*t, p.gear1.module);
    t->Done();
  }
  for (std::size_t k = 0; k < fits.size(); ++k) {
    ShiftFit f;
    f.gear = fit_gears[k];
    f.mesh = "gear1-gear2";
    f.normal_backlash = fits[k].Real("normal_backlash_um", BacklashRule(p.gear1.module)) * kUm;
    fits[k].Done();
    f.profile_shift =
        geometry::iso::FitProfileShift(p.gear1, p.gear2, internal, f.gear == "gear1" ? 1 : 2,
                                       p.centre_distance, f.normal_backlash);
    (f.gear == "gear1" ? p.gear1 : p.gear2).profile_shift = f.profile_shift;
    s.fits.push_back(f);
  }
  ResolveRadii(p.gear1);
  ResolveRadii(p.gear2);
}

// Normal backlash of a mesh with the final shifts, without thickness errors (those are among the
// errors compared with it).
double NominalBacklash(const GearSpec& g1, const GearSpec& g2, bool internal, double a) {
  return geometry::iso::NormalBacklash(g1.module, g1.teeth, g2.teeth, g1.profile_shift,
                                       g2.profile_shift, g1.pressure_angle, a, internal);
}

// ε_α < 1: there are instants without a loaded tooth pair; the model computes them, but the pair
// is not a working gear mesh.
void ContactRatioWarning(const GearSpec& g1, const GearSpec& g2, bool internal, double a,
                         const std::string& where, std::vector<std::string>* warnings) {
  const double alpha = g1.pressure_angle;
  const double rb1 = g1.module * g1.teeth / 2.0 * std::cos(alpha);
  const double rb2 = g2.module * g2.teeth / 2.0 * std::cos(alpha);
  double alpha_w = 0;
  try {
    alpha_w = geometry::iso::PressureAngleAt(g1.module, g1.teeth, g2.teeth, alpha, a, internal);
  } catch (const std::invalid_argument&) {
    return;  // no operating pressure angle: the stage check names the cause
  }
  const double pb = geometry::kPi * g1.module * std::cos(alpha);
  const double eps =
      geometry::iso::ContactRatio(rb1, g1.tip_radius, rb2, g2.tip_radius, a, alpha_w, pb, internal);
  if (std::isfinite(eps) && eps < 1.0) {
    warnings->push_back(where + ": transverse contact ratio epsilon_alpha = " + io::Num(eps, io::kInputDigits) +
                        " < 1 (tip radii, shifts and centre distance): there are instants "
                        "without a loaded tooth pair; the results are outside the model's "
                        "validity for a working mesh");
  }
}

void StageWarnings(const std::vector<ErrorKey>& keys, Scene& s) {
  const geometry::StageSpec& st = s.stage;
  const double a = st.carrier_radius;
  ContactRatioWarning(st.sun, st.planet, false, a, s.source + ": [sun]/[planet]", &s.warnings);
  ContactRatioWarning(st.planet, st.ring, true, a, s.source + ": [planet]/[ring]", &s.warnings);
  const double j_sp = NominalBacklash(st.sun, st.planet, false, a);
  const double j_pr = NominalBacklash(st.planet, st.ring, true, a);
  for (const ErrorKey& k : keys) {
    const double j = k.gear == -1 ? j_sp : k.gear == -2 ? j_pr : std::min(j_sp, j_pr);
    const char* mesh = k.gear == -1   ? "sun-planet"
                       : k.gear == -2 ? "planet-ring"
                       : j_sp <= j_pr ? "sun-planet"
                                      : "planet-ring";
    if (k.value > j) {
      s.warnings.push_back(k.where + "larger than the normal backlash j_n = " + io::Num(j / kUm, io::kInputDigits) +
                           " um of the " + mesh +
                           " meshes: the gear can close the backlash and load the coast flanks "
                           "(a planet jams and its load-sharing ratio can turn negative); the "
                           "model is meant for errors below the backlash");
    }
  }
}

}  // namespace

std::string ContentHash(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64-bit offset basis and prime
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
  return buf;
}

namespace {

// The scene's optional [material], [rating] and [model] tables.
void ReadMaterialRatingModel(TableReader& top, Scene& s) {
  if (auto t = top.OptionalTable("material")) {
    s.material.youngs_modulus =
        t->Real("youngs_modulus_GPa",
                Rule::Closed(kYoungsRangeGPa[0], kYoungsRangeGPa[1])
                    .Because("engineering polymers to carbides; steel is about 207")) *
        1e9;
    s.material.poisson_ratio = t->Real("poisson_ratio", Rule::HalfOpen(0, 0.5));
    // ISO 6336-5's materials: σ_Hlim from about 300 MPa (grey cast iron) to 1650 MPa
    // (case-hardened steel, quality ME); σ_Flim from about 100 to 525 MPa. The ranges leave room
    // around them; outside, a value is a unit mistake.
    s.material.contact_limit =
        t->RealOr("contact_limit_MPa", 0.0,
                  Rule::Closed(kContactLimitMPa[0], kContactLimitMPa[1])
                      .Because("ISO 6336-5's sigma_Hlim of gear materials lie in 300..1650")) *
        1e6;
    s.material.bending_limit =
        t->RealOr("bending_limit_MPa", 0.0,
                  Rule::Closed(kBendingLimitMPa[0], kBendingLimitMPa[1])
                      .Because("ISO 6336-5's sigma_Flim of gear materials lie in 100..525")) *
        1e6;
    t->Done();
  }
  if (auto t = top.OptionalTable("rating")) {
    s.rating.application_factor = t->RealOr(
        "application_factor", 1.0,
        Rule::Closed(1, 4).Because(
            "ISO 6336-6's application factors run from 1.0 (uniform) to 2.25 (heavy shocks on "
            "both sides); a larger one calls for the load spectrum itself"));
    t->Done();
  }
  if (auto t = top.OptionalTable("model")) {
    s.model.plane =
        *io::ValueOf(solvers::kPlaneAssumptionNames,
                     t->StringOr("plane", "strain", io::Names(solvers::kPlaneAssumptionNames)));
    s.model.join_depth = t->RealOr("join_depth_mm", 0.0, Rule::NonNegative()) * kMm;
    if (t->Has("join_depth_factor") && s.model.join_depth > 0) {
      t->Fail("join_depth_factor", "given",
              "give either join_depth_mm or join_depth_factor, not both (the factor scales each "
              "body's default h, join_depth_mm sets one h for all)");
    }
    const double max_factor = 1.0 / compliance::InfluenceTable::kDefaultDepthFraction;
    s.model.join_depth_factor =
        t->RealOr("join_depth_factor", 1.0,
                  Rule::Open(0, max_factor)
                      .Because("the default h is 0.6 of the distance from the flank to the tooth "
                               "centre line, which h must stay below"));
    s.model.mesh_refinement =
        static_cast<int>(t->IntegerOr("mesh_refinement", 1, Rule::Closed(1, 4)));
    s.model.stresses = t->BoolOr("stresses", false);
    t->Done();
  }
}

// A helical stage's carrier radius a [mm] against its normal module: the unshifted sun-planet
// centre distance m_t (z_s + z_p)/2 = a0 [mm] with m_t = m_n / cos β must lie within 2 m_n of a
// (the spur rule of [carrier] radius_mm); otherwise no shift assembles the stage at a, and the
// module the user wrote is what moved it.
void CarrierFitsModule(const TableReader& sun_table, const geometry::StageSpec& st, double a,
                       double a0) {
  const double mn_mm = st.sun.module * std::cos(st.sun.helix.angle) / kMm;
  if (std::abs(a - a0) <= kCarrierModules * mn_mm) return;
  sun_table.Fail(
      "module_mm", io::Num(mn_mm, io::kInputDigits),
      "with helix_angle_deg = " + io::Num(geometry::Deg(st.sun.helix.angle), io::kInputDigits) +
          " the transverse module m_n/cos(beta) = " + io::Num(st.sun.module / kMm, io::kInputDigits) +
          " mm puts the sun-planet centre distance of unshifted gears, m_t (z_sun + z_planet)/2, "
          "at " +
          io::Num(a0, io::kInputDigits) + " mm, more than 2 normal modules from carrier.radius_mm = " + io::Num(a, io::kInputDigits) +
          ": the stage cannot be assembled at that carrier radius (profile shifts move it by "
          "about x m_n)");
}

// A stage's [helix], [sun], [planet], [ring], [carrier] and [load] tables; `fitted(gear)`: the
// gear's profile shift is fitted ([[fit]]).
template <typename Fitted>
void ReadStageMembers(TableReader& top, Scene& s, Fitted&& fitted) {
  geometry::StageSpec& st = s.stage;
  // The stage's [helix] table: one helix angle, the sun's hand; the planets take the opposite
  // hand (external meshes), the ring the planets' (internal mesh).
  std::optional<geometry::Helix> sun_helix, planet_helix;
  if (auto h = top.OptionalTable("helix")) {
    sun_helix.emplace();
    sun_helix->angle = geometry::Rad(h->Real("helix_angle_deg", kHelixRule));
    sun_helix->hand = HandFromName(h->String("sun_hand", {"right", "left"}));
    h->Done();
    planet_helix = sun_helix;
    planet_helix->hand =
        sun_helix->hand == geometry::Hand::kRight ? geometry::Hand::kLeft : geometry::Hand::kRight;
  }
  TableReader sun_table = top.Table("sun");
  st.sun = ReadGear(sun_table, "sun", GearKind::kExternal, fitted("sun"), &s.inertia.sun,
                    &s.warnings, sun_helix);
  sun_table.Done();
  {
    TableReader t = top.Table("planet");
    st.planet = ReadGear(t, "planet", GearKind::kExternal, fitted("planet"), &s.inertia.planet,
                         &s.warnings, planet_helix);
    SameAsMate(t, st.planet, st.sun, "sun");
    t.Done();
  }
  {
    TableReader t = top.Table("ring");
    // The planets sit between sun and ring: z_r = z_s + 2 z_p for gears without shift; shifts of
    // a few tenths move the centre distances by less than a module each. Checked first: a ring
    // too small for the stage would otherwise fail on its rim or its fitted shift.
    const int expect = st.sun.teeth + 2 * st.planet.teeth;
    t.Check("teeth", static_cast<double>(t.Integer("teeth", Rule::Closed(3, 10000))),
            Rule::Closed(expect - kRingTeethSlack, expect + kRingTeethSlack)
                .Because("z_sun + 2 z_planet = " + std::to_string(expect) +
                         " within 4 teeth: the planets must fit between sun and ring"));
    st.ring = ReadGear(t, "ring", GearKind::kInternal, fitted("ring"), &s.inertia.ring, &s.warnings,
                       planet_helix);
    SameAsMate(t, st.ring, st.planet, "planet");
    t.Done();
  }
  {
    TableReader t = top.Table("carrier");
    // The sun-planet centre distance of gears without shift, m (z_s + z_p)/2, within 2 m.
    const double a0 = st.sun.module * (st.sun.teeth + st.planet.teeth) / 2.0 / kMm;
    const double m_mm = st.sun.module / kMm;
    if (st.sun.helix.helical()) {
      st.carrier_radius = t.Real("radius_mm", Rule::Positive()) * kMm;
      CarrierFitsModule(sun_table, st, st.carrier_radius / kMm, a0);
    } else {
      st.carrier_radius =
          t.Real("radius_mm",
                 Rule::Closed(a0 - kCarrierModules * m_mm, a0 + kCarrierModules * m_mm)
                     .Because("m (z_sun + z_planet)/2 = " + io::Num(a0, io::kInputDigits) +
                              " mm within 2 modules (profile shifts move it by about x m)")) *
          kMm;
    }
    st.planets = static_cast<int>(t.Integer("planets", Rule::Closed(1, 12)));
    if (t.Has("planet_angles_deg")) {
      for (double a : t.RealArray("planet_angles_deg", Rule::HalfOpen(0, 360))) {
        st.planet_angles.push_back(geometry::Rad(a));
      }
    }
    st.min_planet_gap = t.RealOr("min_planet_gap_mm", 1.0, Rule::NonNegative()) * kMm;
    s.inertia.carrier = ReadInertia(t);
    t.Done();
  }
  {
    TableReader t = top.Table("load");
    s.loads.sun_torque = t.Real("sun_torque_Nm", Rule::Any());
    if (s.loads.sun_torque == 0)
      t.Fail("sun_torque_Nm", "0", "must be non-zero (its sign selects the loaded flanks)");
    st.load_sign = s.loads.sun_torque > 0 ? 1 : -1;
    t.Done();
  }
}

// A stage's optional [supports] table.
void ReadSupports(TableReader& top, Scene& s) {
  if (auto t = top.OptionalTable("supports")) {
    s.supports.sun =
        *io::ValueOf(kSunSupportNames, t->StringOr("sun", "fixed", io::Names(kSunSupportNames)));
    if (s.supports.sun == SunSupport::kElastic) {
      s.supports.sun_stiffness = t->Real("sun_stiffness_N_per_um", kBearingRule) * 1e6;
    }
    // 0: rigid pins (the default); a bearing otherwise.
    if (t->Has("planet_stiffness_N_per_um") &&
        t->RealOr("planet_stiffness_N_per_um", 0.0, Rule::NonNegative()) != 0) {
      s.supports.planet_stiffness = t->Real("planet_stiffness_N_per_um", kBearingRule) * 1e6;
    }
    t->Done();
  }
}

// A stage's [[fit]] tables (`fits`, their gears `fit_gears`): each solves the profile shift of
// its gear for a normal backlash in its mesh, on the nominal teeth, in order.
void ApplyStageFits(std::vector<TableReader>& fits, const std::vector<std::string>& fit_gears,
                    Scene& s) {
  geometry::StageSpec& st = s.stage;
  for (std::size_t k = 0; k < fits.size(); ++k) {
    TableReader& fit = fits[k];
    ShiftFit f;
    f.gear = fit_gears[k];
    const std::string default_mesh = f.gear == "ring" ? "planet-ring" : "sun-planet";
    f.mesh = fit.StringOr("mesh", default_mesh, {"sun-planet", "planet-ring"});
    if ((f.gear == "sun" && f.mesh != "sun-planet") ||
        (f.gear == "ring" && f.mesh != "planet-ring")) {
      fit.Fail("mesh", "\"" + f.mesh + "\"", "the " + f.gear + " is not in that mesh");
    }
    if (st.sun.helix.helical())
      fit.Fail("gear", "\"" + f.gear + "\"",
               "a [[fit]] solves a shift in the transverse plane of a spur stage; a helical stage "
               "(helix_angle_deg > 0) gives each gear's profile_shift (normal section)");
    f.normal_backlash = fit.Real("normal_backlash_um", BacklashRule(st.sun.module)) * kUm;
    fit.Done();
    const bool internal = f.mesh == "planet-ring";
    // The fit is made on the nominal teeth: thickness errors must not be compensated by it.
    GearSpec g1 = internal ? st.planet : st.sun;
    GearSpec g2 = internal ? st.ring : st.planet;
    g1.thickness_error = g2.thickness_error = 0;
    const int unknown = (f.gear == "sun" || (f.gear == "planet" && internal)) ? 1 : 2;
    f.profile_shift = geometry::iso::FitProfileShift(g1, g2, internal, unknown, st.carrier_radius,
                                                     f.normal_backlash);
    GearSpec& target = f.gear == "sun" ? st.sun : f.gear == "ring" ? st.ring : st.planet;
    target.profile_shift = f.profile_shift;
    s.fits.push_back(f);
  }
}

}  // namespace

Scene ParseScene(const std::string& text, const std::string& source) {
  const toml::table root = ParseDocument(text, source);
  Scene s;
  s.source = source;
  TableReader top(root, "", source);
  {
    TableReader t = top.Table("scene");
    s.name = t.String("name");
    s.description = t.StringOr("description", "");
    t.Done();
  }
  ReadMaterialRatingModel(top, s);
  // A scene is a planetary stage, or a single gear pair when it has a [pair] table.
  const bool is_pair = top.Has("pair");
  s.kind = is_pair ? SceneKind::kPair : SceneKind::kStage;
  // [[fit]] tables name gears whose profile shift is solved for a backlash, in order.
  std::vector<TableReader> fits = top.TableArray("fit");
  std::vector<std::string> fit_gears;
  for (TableReader& f : fits) {
    const std::string g = is_pair ? f.String("gear", {"gear1", "gear2"})
                                  : f.String("gear", {"sun", "planet", "ring"});
    for (const std::string& h : fit_gears) {
      if (h == g) f.Fail("gear", "\"" + g + "\"", "each gear can be fitted once");
    }
    fit_gears.push_back(g);
  }
  auto fitted = [&](const std::string& g) {
    for (const std::string& h : fit_gears) {
      if (h == g) return true;
    }
    return false;
  };

  if (is_pair) {
    ReadPair(top, s, fits, fit_gears, fitted);
    ReadDamage(top, s, {{"gear1", &s.pair.gear1}, {"gear2", &s.pair.gear2}});
    // Slices and the leads of gear1 and gear2 (a pin's tilt and the carrier belong to stages).
    ReadFaceWidth(top, s, {{"gear1", &s.pair.gear1}, {"gear2", &s.pair.gear2}});
    top.Done();
    const bool internal = s.pair.gear2.kind == GearKind::kInternal;
    ContactRatioWarning(s.pair.gear1, s.pair.gear2, internal, s.pair.centre_distance,
                        s.source + ": [gear1]/[gear2]", &s.warnings);
    s.hash = ContentHash(text);
    s.text = text;
    return s;
  }
  geometry::StageSpec& st = s.stage;
  std::vector<ErrorKey> error_keys;
  ReadStageMembers(top, s, fitted);
  if (auto t = top.OptionalTable("contact")) {
    s.gap_window = ReadGapWindow(*t, st.sun.module);
    t->Done();
  }
  ReadSupports(top, s);
  if (auto t = top.OptionalTable("errors")) {
    ReadErrors(*t, s, &error_keys);
    t->Done();
  }
  ReadDynamics(top, s.dynamics, &s.warnings);
  if (s.dynamics.carrier_free && !s.dynamics.sun_speed_driven)
    s.warnings.push_back(
        s.source +
        ": [dynamics] carrier = \"torque\" with the sun torque-driven: both ends carry a torque "
        "and nothing holds the stage's speed; in motion the mesh damping and friction take their "
        "losses from its rotation, so it slows over a long run (a speed sweep's start transient "
        "of seconds: the transmission error then grows past the model's validity); sun = "
        "\"speed\" holds the sun at its speed");
  ApplyStageFits(fits, fit_gears, s);
  for (GearSpec* g : {&st.sun, &st.planet, &st.ring}) ResolveRadii(*g);
  {
    std::vector<std::pair<std::string, const GearSpec*>> gears{{"sun", &st.sun}};
    for (int i = 0; i < st.planets; ++i)
      gears.emplace_back("planet" + std::to_string(i + 1), &st.planet);
    gears.emplace_back("ring", &st.ring);
    ReadDamage(top, s, gears);
    ReadFaceWidth(top, s, gears);
  }
  top.Done();
  StageWarnings(error_keys, s);
  s.hash = ContentHash(text);
  s.text = text;
  return s;
}

Scene ReadScene(const std::string& path) {
  // A scene is a page of keys (the paper's stage: 3 kB); 1 MiB leaves room for comments.
  return ParseScene(io::ReadInputFile(path, "scene file (TOML)", 1u << 20), path);
}

const char* SunSupportName(SunSupport support) {
  const char* name = io::NameOf(kSunSupportNames, support);
  return name ? name : "elastic";
}

}  // namespace epicycle::transmission
