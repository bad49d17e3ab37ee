#include "epicycle/studies/study.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "epicycle/geometry/gear.hpp"
#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/io/enum_names.hpp"
#include "epicycle/io/input_file.hpp"
#include "epicycle/io/number_format.hpp"
#include "epicycle/io/toml_reader.hpp"
#include "epicycle/studies/sampling.hpp"
#include "epicycle/studies/sobol.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::studies {

namespace {

using io::ParseDocument;
using io::Rule;
using io::TableReader;

constexpr double kUm = 1e-6;

struct QuantityInfo {
  Quantity quantity;
  const char* key;   // the study file's name
  const char* unit;  // the suffix of its value keys
  double scale;      // file unit → SI
  double to_file;    // SI → file unit, exactly 1/scale as written
};

constexpr QuantityInfo kQuantities[] = {
    {Quantity::kPinRadial, "pin_radial", "um", kUm, 1e6},
    {Quantity::kPinTangential, "pin_tangential", "um", kUm, 1e6},
    {Quantity::kRunout, "runout", "um", kUm, 1e6},
    {Quantity::kThickness, "thickness", "um", kUm, 1e6},
    {Quantity::kTorque, "torque", "Nm", 1.0, 1.0},
    {Quantity::kPitDepth, "pit_depth", "um", kUm, 1e6},
    {Quantity::kPitWidth, "pit_width", "fraction", 1.0, 1.0},
    {Quantity::kCrackDepth, "crack_depth", "mm", 1e-3, 1e3},
    {Quantity::kPinTiltRadial, "pin_tilt_radial", "um", kUm, 1e6},
    {Quantity::kPinTiltTangential, "pin_tilt_tangential", "um", kUm, 1e6},
    {Quantity::kLeadSlope, "lead_slope", "um", kUm, 1e6},
    {Quantity::kCrowning, "crowning", "um", kUm, 1e6},
};

// Quantities along the face width (the scene's [face_width]).
bool AlongFace(Quantity q) {
  return q == Quantity::kPinTiltRadial || q == Quantity::kPinTiltTangential ||
         q == Quantity::kLeadSlope || q == Quantity::kCrowning;
}
// Quantities of a planet's pin only.
bool OfPin(Quantity q) {
  return q == Quantity::kPinRadial || q == Quantity::kPinTangential ||
         q == Quantity::kPinTiltRadial || q == Quantity::kPinTiltTangential;
}

const QuantityInfo& Info(Quantity q) {
  for (const QuantityInfo& i : kQuantities)
    if (i.quantity == q) return i;
  throw std::logic_error("studies: unknown quantity");
}

}  // namespace

double FileToSi(Quantity q) { return Info(q).scale; }
double SiToFile(Quantity q) { return Info(q).to_file; }

namespace {

using io::Num;

// The study file's compute = "...": what a case computes.
constexpr std::array<io::EnumName<CaseKind>, 2> kCaseKindNames{{
    {CaseKind::kMeshCycle, "mesh-cycle"},
    {CaseKind::kPlanetRevolution, "planet-revolution"},
}};

const geometry::GearSpec& TargetSpec(const transmission::Scene& scene, const Target& t) {
  return t.kind == Target::Kind::kSun    ? scene.stage.sun
         : t.kind == Target::Kind::kRing ? scene.stage.ring
                                         : scene.stage.planet;
}

// A normal variable's spread against the values its cases can take, in the file's unit (the
// scene's rules: an error within a quarter module, a pit's depth in (0, m/4], its width fraction in
// (0, 1], a crack's depth in (0, m]; docs/studies.md). With mean ± sigma past them a sixth of the
// cases or more fail (the one-sided tail beyond one standard deviation holds 15.9 %): an error.
// With mean ± 3 sigma past them (0.13 % a side), or an error past the smaller backlash of the
// gear's meshes (its planet jams, the scene's warning in each such case): a warning.
void CheckSpread(TableReader& t, const transmission::Scene& scene, const Variable& v,
                 const std::string& unit, double scale, std::vector<std::string>* warnings) {
  const double m = scene.stage.sun.module / scale;  // the module in the file's unit
  double lo = 0, hi = 0, backlash = 0;
  std::string what;
  switch (v.quantity) {
    case Quantity::kPinRadial:
    case Quantity::kPinTangential:
    case Quantity::kThickness: {
      lo = -0.25 * m, hi = 0.25 * m;
      what = "an error within a quarter module";
      const geometry::StageSpec& st = scene.stage;
      const double sp = geometry::iso::NormalBacklash(
          st.sun.module, st.sun.teeth, st.planet.teeth, st.sun.profile_shift,
          st.planet.profile_shift, st.sun.pressure_angle, st.carrier_radius, false);
      const double pr = geometry::iso::NormalBacklash(
          st.planet.module, st.planet.teeth, st.ring.teeth, st.planet.profile_shift,
          st.ring.profile_shift, st.planet.pressure_angle, st.carrier_radius, true);
      backlash = (v.target.kind == Target::Kind::kSun    ? sp
                  : v.target.kind == Target::Kind::kRing ? pr
                                                         : std::min(sp, pr)) /
                 scale;
      break;
    }
    case Quantity::kPitDepth:
      hi = 0.25 * m, what = "a pit's depth in (0, m/4]";
      break;
    case Quantity::kPitWidth:
      hi = 1, what = "a pit's width fraction in (0, 1]";
      break;
    case Quantity::kCrackDepth:
      hi = m, what = "a crack's depth in (0, m]";
      break;
    default:
      return;  // a torque: the sign rule of its own
  }
  const double mean = v.mean / scale, sigma = v.sigma / scale;
  const double room = std::min(mean - lo, hi - mean);
  const std::string cases = " (the cases' values: " + what + ", [" + Num(lo, 12) + ", " + Num(hi, 12) +
                            "] " + unit + " here; mean_" + unit + " = " + Num(mean, 12) + ")";
  if (sigma > room)
    t.Fail("sigma_" + unit, Num(sigma, 12),
           "must be <= " + Num(std::max(room, 0.0), 12) + cases +
               ": a wider spread puts a sixth of the cases or more outside, and they fail");
  if (3 * sigma > room)
    warnings->push_back(t.Warning("sigma_" + unit, "mean +- 3 sigma reaches outside" + cases +
                                                       ": 0.1 % of the cases or more fail"));
  if (backlash > 0 && std::abs(mean) + 3 * sigma > backlash)
    warnings->push_back(t.Warning(
        "sigma_" + unit, "|mean| + 3 sigma = " + Num(std::abs(mean) + 3 * sigma, 12) + " " + unit +
                             " is past the normal backlash j_n = " + Num(backlash, 12) + " " + unit +
                             " of the gear's meshes: such cases close it and jam a planet (the "
                             "scene's warning); the model is meant for errors below the backlash"));
}

// One [[variable]] table: one Variable, or one per planet for gear = "planets".
std::vector<Variable> ReadVariable(TableReader& t, const transmission::Scene& scene,
                                   std::vector<std::string>* warnings) {
  std::vector<std::string> quantities;
  for (const QuantityInfo& i : kQuantities) quantities.emplace_back(i.key);
  const std::string qname = t.String("quantity", quantities);
  Variable v;
  for (const QuantityInfo& i : kQuantities)
    if (qname == i.key) v.quantity = i.quantity;
  const QuantityInfo& info = Info(v.quantity);
  const std::string unit = info.unit;
  const int n = scene.stage.planets;

  // Which gear: planets only for pin errors, none for the torque; a pit by its index.
  bool each_planet = false;
  const bool pit = v.quantity == Quantity::kPitDepth || v.quantity == Quantity::kPitWidth;
  if (v.quantity == Quantity::kTorque) {
    v.target.kind = Target::Kind::kNone;
  } else if (v.quantity == Quantity::kCrackDepth) {
    const auto cracks = static_cast<long>(scene.damage.cracks.size());
    if (cracks == 0)
      t.Fail("quantity", "\"" + qname + "\"",
             "the scene '" + scene.source + "' has no [[damage.crack]] to vary");
    v.target.kind = Target::Kind::kCrack;
    v.target.crack = static_cast<int>(t.Integer(
        "crack", Rule::Closed(0, static_cast<double>(cracks - 1))
                     .Because("the index of one of the scene's " + std::to_string(cracks) +
                              " [[damage.crack]] tables, from 0")));
  } else if (pit) {
    const auto pits = static_cast<long>(scene.damage.pits.size());
    if (pits == 0)
      t.Fail("quantity", "\"" + qname + "\"",
             "the scene '" + scene.source + "' has no [[damage.pit]] to vary");
    v.target.kind = Target::Kind::kPit;
    v.target.pit = static_cast<int>(
        t.Integer("pit", Rule::Closed(0, static_cast<double>(pits - 1))
                             .Because("the index of one of the scene's " + std::to_string(pits) +
                                      " [[damage.pit]] tables, from 0")));
  } else {
    if (AlongFace(v.quantity) && !scene.face_width.active())
      t.Fail("quantity", "\"" + qname + "\"",
             "varies along the face width: the scene '" + scene.source +
                 "' has none ([face_width] slices >= 2 needed; docs/face_width.md)");
    std::vector<std::string> allowed;
    if (!OfPin(v.quantity)) allowed = {"sun", "ring"};
    for (int i = 1; i <= n; ++i) allowed.push_back("planet" + std::to_string(i));
    allowed.emplace_back("planets");
    const std::string g = t.String("gear");
    bool ok = false;
    for (const std::string& a : allowed) ok = ok || a == g;
    if (!ok) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
      t.Fail("gear", "\"" + g + "\"",
             "must be one of " + list + " (the scene '" + scene.source + "' has " +
                 std::to_string(n) + " planets" +
                 (allowed.front() == "sun" ? "" : "; pin-hole errors exist for planets only") +
                 ")");
    }
    if (g == "sun") v.target.kind = Target::Kind::kSun;
    if (g == "ring") v.target.kind = Target::Kind::kRing;
    if (g == "planets") each_planet = true;
    if (g.rfind("planet", 0) == 0 && g != "planets") {
      v.target.kind = Target::Kind::kPlanet;
      v.target.planet = std::stoi(g.substr(6)) - 1;
    }
    if (each_planet) v.target.kind = Target::Kind::kPlanet;
  }

  const std::string dist = t.String("distribution", {"normal", "uniform", "iso1328", "grid"});
  const bool length = info.scale == kUm;
  // Values of the quantity: lengths within a module of the gear (the errors are µm-scale
  // modifications of the geometry), a torque non-zero.
  const double module_um = scene.stage.sun.module / kUm;
  Rule value_rule =
      length ? Rule::Closed(-module_um, module_um).Because("within one module of the nominal")
             : Rule::Any();
  // A pit's values: the scene's rules (docs/scenes.md, "Damage").
  if (v.quantity == Quantity::kPitDepth)
    value_rule = Rule{0, module_um / 4, true, false, ""}.Because(
        "a pit's depth_um: more than 0, at most a quarter of the module");
  if (v.quantity == Quantity::kPitWidth)
    value_rule = Rule{0, 1, true, false, ""}.Because("a pit's width_fraction");
  // A crack's depth: positive, within a module (the crack's own rule, inside its tooth, is
  // checked per case: a case whose crack leaves the tooth fails with that message).
  if (v.quantity == Quantity::kCrackDepth)
    value_rule = Rule{0, scene.stage.sun.module / 1e-3, true, false, ""}.Because(
        "a crack's depth_mm: more than 0, at most a module");
  if (dist == "normal") {
    if (v.quantity == Quantity::kRunout)
      t.Fail("distribution", "\"normal\"",
             "a run-out amplitude is >= 0: use \"uniform\" (min_um >= 0), \"iso1328\" or \"grid\"");
    if (v.quantity == Quantity::kCrowning)
      t.Fail("distribution", "\"normal\"",
             "a crowning is >= 0: use \"uniform\" (min_um >= 0) or \"grid\"");
    v.distribution = Distribution::kNormal;
    v.mean = t.RealOr("mean_" + unit, 0.0, value_rule) * info.scale;
    v.sigma = t.Real("sigma_" + unit, Rule::NonNegative().Because("a standard deviation is >= 0")) *
              info.scale;
    CheckSpread(t, scene, v, unit, info.scale, warnings);
  } else if (dist == "uniform") {
    v.distribution = Distribution::kUniform;
    const Rule r = v.quantity == Quantity::kRunout
                       ? Rule::Closed(0, module_um).Because("a run-out amplitude is >= 0")
                   : v.quantity == Quantity::kCrowning
                       ? Rule::Closed(0, module_um).Because("a crowning is >= 0")
                       : value_rule;
    v.min = t.Real("min_" + unit, r) * info.scale;
    v.max = t.Real("max_" + unit, r) * info.scale;
    if (!(v.max > v.min))
      t.Fail("max_" + unit, Num(v.max / info.scale, 12),
             "must be > min_" + unit + " = " + Num(v.min / info.scale, 12));
  } else if (dist == "iso1328") {
    if (v.quantity != Quantity::kRunout)
      t.Fail("distribution", "\"iso1328\"",
             "ISO 1328-1 defines a tolerance for the run-out only (not for " + qname +
                 "): use \"normal\" or \"uniform\"");
    v.distribution = Distribution::kIso1328;
    v.grade = static_cast<int>(t.Integer(
        "grade", Rule::Closed(1, 11).Because("the flank tolerance classes of ISO 1328-1:2013")));
    const geometry::GearSpec& g = TargetSpec(scene, v.target);
    const double d = g.module * g.teeth;
    if (!Iso1328Applies(v.grade, d, g.module))
      t.Fail("grade", std::to_string(v.grade),
             "ISO 1328-1:2013 covers 0.5 <= m_n <= 70 mm and 5 <= d <= 15000 mm; this gear has m_n "
             "= " +
                 Num(g.module * 1e3, 12) + " mm, d = " + Num(d * 1e3, 12) + " mm");
    v.min = 0.0;
    v.max = 0.5 * Iso1328RunoutTolerance(v.grade, d, g.module);
  } else {
    v.distribution = Distribution::kGrid;
    const Rule r = v.quantity == Quantity::kRunout
                       ? Rule::Closed(0, module_um).Because("a run-out amplitude is >= 0")
                   : v.quantity == Quantity::kCrowning
                       ? Rule::Closed(0, module_um).Because("a crowning is >= 0")
                       : value_rule;
    for (double x : t.RealArray("values_" + unit, r)) v.grid.push_back(x * info.scale);
    if (v.grid.empty()) t.Fail("values_" + unit, "[]", "must list at least one value");
  }
  if (v.quantity == Quantity::kTorque) {
    auto nonzero_same_sign = [&](double x, const std::string& key) {
      if (!(x * scene.loads.sun_torque > 0))
        t.Fail(key, Num(x, 12),
               "must be non-zero with the sign of the scene's sun_torque_Nm = " +
                   Num(scene.loads.sun_torque, 12) + " (the loaded flanks are the scene's)");
    };
    if (v.distribution == Distribution::kGrid)
      for (double x : v.grid) nonzero_same_sign(x, "values_Nm");
    if (v.distribution == Distribution::kUniform) {
      nonzero_same_sign(v.min, "min_Nm");
      nonzero_same_sign(v.max, "max_Nm");
    }
    if (v.distribution == Distribution::kNormal) nonzero_same_sign(v.mean, "mean_Nm");
  }
  t.Done();
  if (!each_planet) return {v};
  std::vector<Variable> out;
  for (int i = 0; i < n; ++i) {
    out.push_back(v);
    out.back().target.planet = i;
  }
  return out;
}

// The Sobol design's rules (studies/sobol.hpp): random variables only, N within what the
// bootstrap needs and the study's case count can hold.
void CheckSobolStudy(const TableReader& st, const StudySpec& s) {
  const auto d = static_cast<long>(s.variables.size());
  if (d == 0)
    st.Fail("design", "\"sobol\"",
            "a Sobol design needs at least one random [[variable]] (its indices are per variable)");
  for (const Variable& v : s.variables)
    if (v.distribution == Distribution::kGrid)
      st.Fail("design", "\"sobol\"",
              "variable " + v.Columns().front() +
                  " has distribution \"grid\": a Sobol design samples random variables only "
                  "(run one study per grid value)");
  const long most = 1000000000L / (d + 2);
  if (s.samples < kSobolMinSamples || s.samples > most)
    st.Fail("samples", std::to_string(s.samples),
            "with design = \"sobol\" the base sample N must be a whole number in [" +
                std::to_string(kSobolMinSamples) + ", " + std::to_string(most) +
                "] (N rows of A and B for its bootstrap intervals; the study has N (d + 2) = N x " +
                std::to_string(d + 2) + " cases, d = " + std::to_string(d) +
                " variables, at most 1e9)");
}

}  // namespace

std::string Target::Name() const {
  switch (kind) {
    case Kind::kSun:
      return "sun";
    case Kind::kRing:
      return "ring";
    case Kind::kPlanet:
      return "planet" + std::to_string(planet + 1);
    case Kind::kPit:
      return "pit" + std::to_string(pit);
    case Kind::kCrack:
      return "crack" + std::to_string(crack);
    case Kind::kNone:
      break;
  }
  return "stage";
}

std::vector<std::string> Variable::Columns() const {
  const QuantityInfo& i = Info(quantity);
  const std::string base = target.Name() + "." + i.key;
  if (quantity == Quantity::kRunout) return {base + "_amplitude_um", base + "_phase_deg"};
  return {base + "_" + i.unit};
}

long StudySpec::GridPoints() const {
  long g = 1;
  for (const Variable& v : variables)
    if (v.distribution == Distribution::kGrid) g *= static_cast<long>(v.grid.size());
  return g;
}

long StudySpec::Cases() const {
  if (design == Design::kSobol) return samples * (static_cast<long>(variables.size()) + 2);
  return GridPoints() * samples;
}

std::vector<std::string> StudySpec::FaceMeshes() const {
  std::vector<std::string> m;
  if (!scene.face_width.active()) return m;
  for (const geometry::MeshKind kind :
       {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing})
    for (int i = 0; i < scene.stage.planets; ++i) m.push_back(geometry::MeshName(i, kind));
  return m;
}

std::vector<std::string> StudySpec::HelicalColumns() const {
  std::vector<std::string> c;
  if (!transmission::IsHelical(scene)) return c;
  for (const std::string& m : FaceMeshes()) c.push_back("F_a_" + m + "_N");
  for (int i = 1; i <= scene.stage.planets; ++i)
    for (const char* a : {"radial", "tangential"})
      c.push_back(std::string("M_tilt_") + a + "_planet" + std::to_string(i) + "_Nm");
  if (!scene.face_width.pins.empty())
    for (int i = 1; i <= scene.stage.planets; ++i)
      for (const char* a : {"radial", "tangential"})
        c.push_back(std::string("tilt_") + a + "_planet" + std::to_string(i) + "_urad");
  return c;
}

bool StudySpec::VariesBodies() const {
  for (const Variable& v : variables)
    if (v.quantity == Quantity::kCrackDepth) return true;
  return false;
}

std::vector<std::string> StudySpec::Columns() const {
  std::vector<std::string> c;
  for (const Variable& v : variables)
    for (const std::string& s : v.Columns()) c.push_back(s);
  return c;
}

std::vector<std::string> StudySpec::StressGears() const {
  if (!scene.model.stresses) return {};
  return transmission::BodyNames(transmission::PlanetBody(scene.stage.planets));
}

bool StudySpec::Rated() const {
  return scene.model.stresses && scene.material.bending_limit > 0 &&
         scene.material.contact_limit > 0;
}

StudySpec ParseStudy(const std::string& text, const std::string& source,
                     const std::string& directory) {
  const toml::table root = ParseDocument(text, source);
  StudySpec s;
  s.source = source;
  s.hash = transmission::ContentHash(text);
  TableReader top(root, "", source);
  TableReader st = top.Table("study");
  s.name = st.String("name");
  s.scene_file = st.String("scene");
  std::filesystem::path scene_path(s.scene_file);
  if (scene_path.is_relative() && !directory.empty())
    scene_path = std::filesystem::path(directory) / scene_path;
  if (!std::filesystem::is_regular_file(scene_path))
    st.Fail("scene", "\"" + s.scene_file + "\"",
            "must name a scene file (TOML), relative to the study file; '" + scene_path.string() +
                "' is not a file");
  s.scene_file = scene_path.string();
  s.scene = transmission::ReadScene(s.scene_file);
  if (s.scene.kind != transmission::SceneKind::kStage)
    st.Fail("scene", "\"" + s.scene_file + "\"", "must be a stage scene, not a gear pair");
  s.seed = static_cast<std::uint64_t>(st.IntegerOr("seed", 0, Rule::NonNegative()));
  s.samples = st.IntegerOr("samples", 1, Rule::Closed(1, 1e9).Because("cases per grid point"));
  s.design = st.StringOr("design", "monte-carlo", {"monte-carlo", "sobol"}) == "sobol"
                 ? Design::kSobol
                 : Design::kMonteCarlo;
  s.compute =
      *io::ValueOf(kCaseKindNames, st.StringOr("compute", "mesh-cycle", io::Names(kCaseKindNames)));
  s.positions = static_cast<int>(st.IntegerOr(
      "positions", s.compute == CaseKind::kMeshCycle ? 36 : 360, Rule::Closed(1, 100000)));
  s.start_angle = st.RealOr("start_deg", 0.0, Rule::Closed(-360, 360)) * std::numbers::pi / 180.0;
  const std::string sun =
      st.StringOr("sun", "scene",
                  {"scene", transmission::SunSupportName(transmission::SunSupport::kFixed),
                   transmission::SunSupportName(transmission::SunSupport::kFloating)});
  if (const auto support = io::ValueOf(transmission::kSunSupportNames, sun)) s.sun = *support;
  s.scene.model.stresses = st.BoolOr("stresses", s.scene.model.stresses);
  if (const toml::node* limit = root["study"]["k_gamma_limit"].node()) {
    const double n = s.scene.stage.planets;
    const Rule rule = Rule::Closed(1, n).Because(
        "K_gamma = max_i n LSR_i lies in [1, n] (n = " + Num(n) +
        " planets): a design value outside is always or never exceeded");
    s.k_gamma_limits = limit->is_array() ? st.RealArray("k_gamma_limit", rule)
                                         : std::vector<double>{st.Real("k_gamma_limit", rule)};
    if (s.k_gamma_limits.empty()) st.Fail("k_gamma_limit", "[]", "must list at least one value");
  }
  s.backend_name = st.StringOr("backend", "newton");
  try {
    s.backend = solvers::BackendFromName(s.backend_name);
  } catch (const std::invalid_argument& e) {
    st.Fail("backend", "\"" + s.backend_name + "\"", e.what());
  }
  st.Done();
  for (TableReader& t : top.TableArray("variable"))
    for (Variable& v : ReadVariable(t, s.scene, &s.warnings)) s.variables.push_back(std::move(v));
  top.Done();
  if (s.design == Design::kSobol) CheckSobolStudy(st, s);
  // A gear's quantity sampled twice would give two columns writing one value.
  for (std::size_t a = 0; a < s.variables.size(); ++a)
    for (std::size_t b = 0; b < a; ++b)
      if (s.variables[a].Columns() == s.variables[b].Columns())
        throw std::invalid_argument(source + ": variable " + s.variables[a].Columns().front() +
                                    " is given twice: each gear's quantity can vary once");
  if (s.variables.empty())
    s.warnings.push_back(source + ": no [[variable]]: every case is the base scene");
  for (const std::string& w : s.scene.warnings) s.warnings.push_back(w);
  return s;
}

StudySpec ReadStudy(const std::string& path) {
  // A study file is a page of keys, as a scene is.
  return ParseStudy(io::ReadInputFile(path, "study file (TOML)", 1u << 20),
                    path, std::filesystem::path(path).parent_path().string());
}

}  // namespace epicycle::studies
