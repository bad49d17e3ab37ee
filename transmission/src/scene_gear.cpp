// A gear's table of the scene (docs/scenes.md, "Helical gears", "Profile modifications and pitch
// deviations"): its numbers, flank modifications, pitch deviations, helix and inertia, with the
// rules each is read under.
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/geometry/iso.hpp"
#include "epicycle/io/units.hpp"
#include "scene_internal.hpp"

namespace epicycle::transmission::internal {

using geometry::GearKind;
using geometry::GearSpec;

namespace {

// The gear's share of the scene's physical ranges (docs/scenes.md, "Ranges and validity"), sizes
// relative to the module.
constexpr double kModuleRangeMm[2] = {0.05, 100.0};
constexpr double kFaceWidthModules[2] = {0.5, 100.0};
constexpr double kHubFractionOfReference = 0.2;  // hub ≥ 0.2 r
constexpr double kRimFractionOfReference = 2.0;  // rim ≤ 2 r

// Tip/root relief and pitch deviations of one gear: [<gear>.modification], [<gear>.pitch].
void ReadFlankModifications(TableReader& t, GearSpec& g) {
  if (auto m = t.OptionalTable("modification")) {
    auto relief = [&](const std::string& which, geometry::Relief* r) {
      const std::string radius = which + "_relief_start_mm",
                        roll = which + "_relief_start_roll_deg";
      if (!m->Has(which + "_relief_um")) return;  // Done() refuses the zone's other keys
      r->amount = m->Real(which + "_relief_um", Rule::NonNegative()) * kUm;
      if (m->Has(radius) == m->Has(roll)) {
        m->Fail(radius, m->Has(radius) ? "given" : "missing",
                "give exactly one of " + radius + " or " + roll);
      }
      if (m->Has(radius)) {
        r->start_radius = m->Real(radius, Rule::Positive()) * kMm;
      } else {  // roll angle u: r = r_b √(1 + u²)
        const double u = geometry::Rad(m->Real(roll, Rule::Positive()));
        r->start_radius =
            0.5 * g.module * g.teeth * std::cos(g.pressure_angle) * std::hypot(1.0, u);
      }
      r->shape = m->StringOr(which + "_relief_shape", "linear", {"linear", "parabolic"}) == "linear"
                     ? geometry::ReliefShape::kLinear
                     : geometry::ReliefShape::kParabolic;
    };
    relief("tip", &g.modification.tip);
    relief("root", &g.modification.root);
    m->Done();
  }
  if (auto p = t.OptionalTable("pitch")) {
    const int given = p->Has("single_um") + p->Has("cumulative_um") + p->Has("iso1328_grade");
    if (given != 1) {
      p->Fail("single_um", given == 0 ? "missing" : "given with another",
              "give exactly one of single_um, cumulative_um or iso1328_grade");
    }
    const std::string where = p->path() + ".";
    if (p->Has("iso1328_grade")) {
      const int grade = static_cast<int>(p->Integer("iso1328_grade", Rule::Closed(1, 11)));
      const auto seed = static_cast<std::uint64_t>(p->IntegerOr("seed", 1, Rule::NonNegative()));
      g.pitch_deviations = geometry::iso::RandomPitchDeviations(g.teeth, g.module, grade, seed,
                                                                where + "iso1328_grade");
    } else {
      const std::string key = p->Has("single_um") ? "single_um" : "cumulative_um";
      std::vector<double> v = p->RealArray(key, Rule::Any());
      if (static_cast<int>(v.size()) != g.teeth) {
        p->Fail(key, std::to_string(v.size()) + " entries",
                "needs one entry per tooth (" + std::to_string(g.teeth) + ")");
      }
      for (double& x : v) x *= kUm;
      g.pitch_deviations =
          key == "single_um" ? geometry::iso::CumulativeFromSingle(v, where + key) : v;
    }
    p->Done();
  }
}

// The fields common to every gear table; `fit_target` gears may omit profile_shift.
// A gear's mass and inertia against the solid steel disc of its pitch circle (ρ = 7850 kg/m³,
// m_d = ρ π r² b, J_d = m_d r²/2): real gears (a bore, a web, a shaft, a rim) lie within a few
// times that; outside [1/100, 100] times it the value is most likely in another unit or
// mistyped, and the modes and the integrator's steps follow it (docs/scenes.md, "Ranges and
// validity"). 0 (not given) is left to the dynamic model, which asks for what it needs.
void InertiaWarnings(const TableReader& t, const GearSpec& g, const Inertia& i,
                     std::vector<std::string>* warnings) {
  constexpr double kSteelDensity = 7850;  // [kg/m³]
  const double r = 0.5 * g.module * g.teeth;
  const double disc_mass = kSteelDensity * std::numbers::pi * r * r * g.face_width;
  const double disc_inertia = 0.5 * disc_mass * r * r;
  auto check = [&](const char* key, double value, double disc, const char* unit) {
    if (value > 0 && (value < 1e-2 * disc || value > 1e2 * disc))
      warnings->push_back(
          t.Warning(key, "outside [1/100, 100] times the solid steel disc of the pitch circle (" +
                             io::Num(disc, io::kInputDigits) + " " + unit +
                             "): another unit, or a typing error?"));
  };
  check("mass_kg", i.mass, disc_mass, "kg");
  check("inertia_kgm2", i.inertia, disc_inertia, "kg m2");
}

// The lightest gear the model represents (docs/scenes.md, "Ranges and validity"). The model takes
// the teeth as massless springs (the static FE compliance and the local term), so a member's
// motion on its mesh must be slower than its teeth's own first bending vibration. A tooth as a
// cantilever of the whole depth L = 2.25 m and the pitch thickness s = πm/2 (Euler–Bernoulli)
// bends at ω_t = 1.875² (s/L²) √(E/(12 ρ)); a member of mass M on one mesh of stiffness k = c_γ b
// (ISO 6336-1: c_γ ≈ 20 N/(mm·µm) for steel, in proportion to E for other materials) moves at
// ω = √(k/M). ω ≤ ω_t gives M ≥ k/ω_t² = (c_γ/E) 12 ρ L⁴ b/(1.875⁴ s²) = 0.98 ρ b m² (E cancels;
// steel's ρ): about the steel of half a tooth. The rotation likewise at the base circle:
// J ≥ M_min r_b². A lighter gear puts the model's modes above its teeth's (a planet of
// 1e-30 kg m² at 2.4e17 Hz) and its runs' steps below any physical time scale.
void InertiaRule(TableReader& t, const GearSpec& g, const Inertia& i) {
  constexpr double kSteelDensity = 7850;                              // [kg/m³]
  constexpr double kMeshStiffnessOverModulus = 20e9 / 206e9;          // c_γ/E [-]
  constexpr double kDepth = 2.25, kThickness = std::numbers::pi / 2;  // L/m, s/m [-]
  constexpr double kClamped = 1.875 * 1.875 * 1.875 * 1.875;          // (β₁L)⁴ [-]
  const double m_min = kMeshStiffnessOverModulus * 12 * kSteelDensity * std::pow(kDepth, 4) *
                       g.face_width * g.module * g.module / (kClamped * kThickness * kThickness);
  const double r_b = 0.5 * g.module * g.teeth * std::cos(g.pressure_angle);
  const std::string why =
      ": the lightest gear the model represents, 0.98 rho b m^2 of steel (half a tooth; J: that "
      "at the base circle): lighter, it moves on its mesh faster than its teeth's own bending "
      "vibration, which the model (teeth as massless springs) does not have";
  if (i.mass > 0 && i.mass < m_min)
    t.Fail("mass_kg", io::Num(i.mass, io::kInputDigits),
           "must be 0 (not given) or >= " + io::Num(m_min, io::kInputDigits) + why);
  if (i.inertia > 0 && i.inertia < m_min * r_b * r_b)
    t.Fail("inertia_kgm2", io::Num(i.inertia, io::kInputDigits),
           "must be 0 (not given) or >= " + io::Num(m_min * r_b * r_b, io::kInputDigits) + why);
}

// The helix angle at the reference cylinder (docs/scenes.md, "Helical gears"): its magnitude,
// the hand its direction.

// A gear's helix: its own helix_angle_deg and hand, or the one the stage's [helix] table gives it
// (`given`; then the gear's table may not have them).
geometry::Helix ReadHelix(TableReader& t, const std::optional<geometry::Helix>& given) {
  if (given) {
    for (const char* key : {"helix_angle_deg", "hand"})
      if (t.Has(key))
        t.Fail(key, "given",
               "the scene's [helix] table sets every gear's helix: give it there or in each "
               "gear's table, not both");
    return *given;
  }
  geometry::Helix h;
  h.angle = geometry::Rad(t.RealOr("helix_angle_deg", 0.0, kHelixRule));
  if (!h.helical()) {
    if (t.Has("hand")) t.String("hand", {"right", "left"});  // a spur gear's hand says nothing
    return h;
  }
  if (!t.Has("hand"))
    t.Fail("hand", "missing",
           "a helical gear (helix_angle_deg > 0) needs its hand, \"right\" or \"left\"");
  h.hand = HandFromName(t.String("hand", {"right", "left"}));
  return h;
}

}  // namespace

const Rule kHelixRule = Rule::HalfOpen(0, 45).Because(
    "the helix angle at the reference cylinder, 0 (spur) up to below 45 deg; the hand gives its "
    "direction");

Inertia ReadInertia(TableReader& t) {
  Inertia i;
  i.mass = t.RealOr("mass_kg", 0.0, Rule::NonNegative());
  i.inertia = t.RealOr("inertia_kgm2", 0.0, Rule::NonNegative());
  return i;
}

geometry::Hand HandFromName(const std::string& name) {
  return name == "left" ? geometry::Hand::kLeft : geometry::Hand::kRight;
}

GearSpec ReadGear(TableReader& t, const std::string& name, GearKind kind, bool fit_target,
                  Inertia* inertia, std::vector<std::string>* warnings,
                  const std::optional<geometry::Helix>& helix) {
  GearSpec g;
  g.name = name;
  g.kind = kind;
  g.teeth = static_cast<int>(t.Integer("teeth", Rule::Closed(3, 10000)));
  const double m_mm =
      t.Real("module_mm", Rule::Closed(kModuleRangeMm[0], kModuleRangeMm[1])
                              .Because("fine-pitch to mill gears; ISO 54 lists 1 to 50 mm"));
  g.module = m_mm * kMm;
  g.face_width =
      t.Real("face_width_mm", Rule::Closed(kFaceWidthModules[0] * m_mm, kFaceWidthModules[1] * m_mm)
                                  .Because("0.5 to 100 modules; the 2D model idealises a spur gear "
                                           "of moderate width")) *
      kMm;
  g.pressure_angle = geometry::Rad(t.Real("pressure_angle_deg", Rule::Open(0, 45)));
  if (fit_target) {
    if (t.Has("profile_shift")) {
      t.Fail("profile_shift", "given",
             "this gear's shift is solved by [fit]; remove one of the two");
    }
  } else {
    g.profile_shift = t.Real("profile_shift", Rule::Closed(-2, 2));
  }
  g.tip_round_radius = t.RealOr("tip_round_radius_mm", 0.0,
                                Rule::Closed(0, 0.5 * m_mm)
                                    .Because("at most half a module: a larger round "
                                             "removes the top land")) *
                       kMm;
  g.min_tip_thickness = t.RealOr("min_tip_thickness_mm", -1e3, Rule::Any()) * kMm;
  if (g.min_tip_thickness < 0) g.min_tip_thickness = -1;
  *inertia = ReadInertia(t);
  InertiaRule(t, g, *inertia);
  if (warnings != nullptr) InertiaWarnings(t, g, *inertia, warnings);
  TableReader cutter = t.Table("cutter");
  // The tip (and a directly defined ring's root) is given as a radius, or as an addendum
  // (dedendum) coefficient from the shifted reference line: r_a = r + (x ± h_a*) m, which needs
  // the final shift and is therefore resolved after any [[fit]] (see ResolveRadii).
  auto radius_or_coefficient = [&](const std::string& radius_key, const std::string& coef_key,
                                   bool required) -> double {
    if (t.Has(radius_key) && t.Has(coef_key)) {
      t.Fail(coef_key, "given", "give either " + radius_key + " or " + coef_key + ", not both");
    }
    if (t.Has(coef_key)) return -t.Real(coef_key, Rule::Positive());  // < 0 marks a coefficient
    if (required && !t.Has(radius_key)) {
      t.Fail(radius_key, "missing", "give " + radius_key + " or " + coef_key);
    }
    return t.RealOr(radius_key, 0.0, Rule::Positive()) * kMm;
  };
  if (kind == GearKind::kExternal) {
    g.tip_radius = radius_or_coefficient("tip_radius_mm", "addendum_per_module", false);
    // The upper bound (below the root circle) is checked where the gear is made.
    const double r_mm = m_mm * g.teeth / 2.0;
    g.hub_radius = t.Real("hub_radius_mm",
                          Rule::Closed(kHubFractionOfReference * r_mm, r_mm)
                              .Because("at least a fifth of the reference radius m z/2: the FE "
                                       "bodies are meshed and checked down to such hubs; that "
                                       "it lies inside the root circle is checked with the "
                                       "gear")) *
                   kMm;
    cutter.String("type", {"rack"});
    geometry::RackCutter rack;
    const Rule depth = Rule::Closed(0.5, 2.0).Because("a generating rack of 0.5 to 2 modules");
    rack.addendum = cutter.Real("addendum_per_module", depth) * g.module;
    rack.dedendum = cutter.Real("dedendum_per_module", depth) * g.module;
    rack.tip_radius =
        cutter.Real(
            "tip_radius_per_module",
            Rule::Closed(0, 0.5).Because("at most half a module; ISO 53 profile A has 0.38")) *
        g.module;
    g.rack = rack;
  } else {
    g.tip_radius = radius_or_coefficient("tip_radius_mm", "addendum_per_module", true);
    const double r_mm = m_mm * g.teeth / 2.0;
    g.hub_radius = t.Real("rim_radius_mm",
                          Rule::Open(0, kRimFractionOfReference * r_mm)
                              .Because("at most twice the reference radius m z/2; that it lies "
                                       "beyond the root circle is checked with the gear")) *
                   kMm;
    const std::string type = cutter.String("type", {"shaper", "direct"});
    if (type == "shaper") {
      geometry::ShaperCutter s;
      s.teeth = static_cast<int>(cutter.Integer("teeth", Rule::Closed(3, 10000)));
      s.profile_shift = cutter.Real("profile_shift", Rule::Closed(-2, 2));
      s.tip_radius = cutter.Real("tip_radius_mm", Rule::Positive()) * kMm;
      s.tip_round_radius = cutter.Real("tip_round_radius_mm", Rule::Positive()) * kMm;
      g.shaper = s;
    } else {
      if (cutter.Has("root_radius_mm") == cutter.Has("dedendum_per_module")) {
        cutter.Fail("root_radius_mm", cutter.Has("root_radius_mm") ? "given" : "missing",
                    "give exactly one of root_radius_mm or dedendum_per_module");
      }
      g.root_radius = cutter.Has("root_radius_mm")
                          ? cutter.Real("root_radius_mm", Rule::Positive()) * kMm
                          : -cutter.Real("dedendum_per_module", Rule::Positive());
      g.root_round_radius = cutter.Real("root_round_radius_mm", Rule::Positive()) * kMm;
    }
  }
  cutter.Done();
  // Module, pressure angle and shift were read in the normal section (a helical gear's rack);
  // every length above is the same in the transverse section, which the generator takes.
  g.helix = ReadHelix(t, helix);
  g = geometry::TransverseSpec(std::move(g));
  ReadFlankModifications(t, g);
  return g;
}

}  // namespace epicycle::transmission::internal
