// The scene's [face_width] table with its [[face_width.pin_tilt]] and [[face_width.lead]] arrays
// (docs/scenes.md, "Face width"; the model: docs/model.md §10).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "epicycle/io/input_file.hpp"
#include "epicycle/io/number_format.hpp"
#include "epicycle/io/toml_reader.hpp"
#include "scene_internal.hpp"

namespace epicycle::transmission::internal {

using geometry::GearSpec;

namespace {

constexpr double kDefaultSlices = 20;  // docs/scenes.md, "Face width": the convergence behind it

// The largest gap change across one mesh (A, B) of the stage, a bound of FaceWidthModel's
// (|n·t| ≤ |t|, |ℓ| ≤ r_b for the lead slope's turn of the sections), and the key that
// contributes most, for the message.
struct MeshBound {
  double change = 0;
  std::string key;
  double largest = 0;
  void Add(double part, const std::string& where) {
    change += part;
    if (part > largest) {
      largest = part;
      key = where;
    }
  }
};

// coupling = "table": W [-] from the CSV that `key` names (relative to the scene's directory):
// a header line, then one row "i,j,w" for every 0 <= i, j < S.
Eigen::MatrixXd ReadCouplingTable(TableReader& t, const std::string& key, const std::string& source,
                                  int slices) {
  const std::string value = t.String(key);
  std::filesystem::path path(value);
  if (path.is_relative()) path = std::filesystem::path(source).parent_path() / path;
  const std::string quoted = "\"" + value + "\"";
  std::string text;
  try {
    text = io::ReadInputFile(path.string(), "coupling table (CSV)", 1u << 22);
  } catch (const std::invalid_argument& e) {
    t.Fail(key, quoted, std::string("must be a readable CSV file: ") + e.what());
  }
  Eigen::MatrixXd w = Eigen::MatrixXd::Constant(slices, slices, std::nan(""));
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // the header
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \r") == std::string::npos) continue;
    std::istringstream row(line);
    long i = -1, j = -1;
    double v = std::nan("");
    char c1 = 0, c2 = 0;
    if (!(row >> i >> c1 >> j >> c2 >> v) || c1 != ',' || c2 != ',' || i < 0 || j < 0 ||
        i >= slices || j >= slices || !std::isfinite(v))
      t.Fail(key, quoted,
             "line " + std::to_string(number) + " '" + line + "': each row must be i,j,w with " +
                 "0 <= i, j < face_width.slices = " + std::to_string(slices) + " and w finite");
    w(i, j) = v;
  }
  for (int i = 0; i < slices; ++i)
    for (int j = 0; j < slices; ++j)
      if (std::isnan(w(i, j)))
        t.Fail(key, quoted,
               "has no entry (" + std::to_string(i) + ", " + std::to_string(j) +
                   "): the table gives W_ij for every pair of the face_width.slices = " +
                   std::to_string(slices) + " slices");
  const double asymmetry = (w - w.transpose()).cwiseAbs().maxCoeff();
  if (asymmetry > 1e-9 * w.cwiseAbs().maxCoeff())
    t.Fail(key, quoted,
           "must be symmetric (a compliance, Maxwell-Betti): |W_ij - W_ji| reaches " +
               io::Num(asymmetry));
  if (Eigen::LLT<Eigen::MatrixXd>(w).info() != Eigen::Success)
    t.Fail(key, quoted, "must be positive definite (a compliance: every load deflects its face)");
  return w;
}

}  // namespace

void ReadFaceWidth(TableReader& top, Scene& s,
                   const std::vector<std::pair<std::string, const GearSpec*>>& gears) {
  auto t = top.OptionalTable("face_width");
  if (!t) return;
  FaceWidthSpec& f = s.face_width;
  const geometry::StageSpec& st = s.stage;
  const bool pair = s.kind == SceneKind::kPair;
  // The face the slices divide: the planet's in a stage, the narrower gear's in a pair.
  const double b_planet =
      pair ? std::min(s.pair.gear1.face_width, s.pair.gear2.face_width) : st.planet.face_width;
  for (const char* key : {"pin_tilt", "pin", "carrier_torsional_stiffness_Nm_per_rad"})
    if (pair && t->Has(key))
      t->Fail(key, "given in a pair scene",
              "a planet pin's tilt and the carrier's wind-up belong to stage scenes; a pair's "
              "misalignment is a lead slope ([[face_width.lead]] slope_um of gear1 or gear2)");
  const bool has_more = t->Has("pin_tilt") || t->Has("pin") || t->Has("lead") ||
                        t->Has("carrier_torsional_stiffness_Nm_per_rad");
  f.slices = static_cast<int>(t->IntegerOr(
      "slices", has_more ? static_cast<long>(kDefaultSlices) : 1L,
      Rule::Closed(1, kMaxFaceSlices)
          .Because("slices of the face width, each a plane contact problem of its own; 1 is the "
                   "plane model")));
  auto needs_slices = [&](TableReader& r, const std::string& key) {
    if (f.slices < 2)
      r.Fail(key, "given with face_width.slices = 1",
             "a variation along the face width needs slices >= 2 (one slice has no axial "
             "extent)");
  };
  const std::string coupling =
      t->StringOr("coupling", "none", {"none", "pasternak", "table"});
  // A pair's table is its one mesh's; a stage's meshes of the two kinds (external sun-planet,
  // internal planet-ring) each have their own structure, so a stage names one table per kind.
  const std::vector<std::string> table_keys =
      pair ? std::vector<std::string>{"coupling_table"}
           : std::vector<std::string>{"coupling_table_sun_planet", "coupling_table_planet_ring"};
  const std::vector<std::string> other_keys =
      pair ? std::vector<std::string>{"coupling_table_sun_planet", "coupling_table_planet_ring"}
           : std::vector<std::string>{"coupling_table"};
  for (const std::string& key : other_keys)
    if (t->Has(key))
      t->Fail(key, "given in a " + std::string(pair ? "pair" : "stage") + " scene",
              pair ? "a pair's one mesh takes its kernel from coupling_table"
                   : "a stage's sun-planet and planet-ring meshes take their kernels from "
                     "coupling_table_sun_planet and coupling_table_planet_ring");
  if (coupling == "table") {
    needs_slices(*t, "coupling");
    for (const std::string& key : table_keys)
      if (!t->Has(key))
        t->Fail("coupling", "\"table\"",
                "needs " + key +
                    (pair ? std::string(", the pair's kernel")
                          : std::string(": a stage takes one kernel per mesh kind, "
                                        "coupling_table_sun_planet and "
                                        "coupling_table_planet_ring")));
    f.coupling = FaceCoupling::kTable;
    f.coupling_table = ReadCouplingTable(*t, table_keys[0], s.source, f.slices);
    if (!pair)
      f.coupling_table_planet_ring = ReadCouplingTable(*t, table_keys[1], s.source, f.slices);
  } else {
    for (const std::string& key : table_keys)
      if (t->Has(key))
        t->Fail(key, "given with coupling = \"" + coupling + "\"",
                "a coupling table belongs to coupling = \"table\"");
  }
  if (coupling == "pasternak") {
    f.coupling = FaceCoupling::kPasternak;
    f.coupling_length =
        t->Real("coupling_length_mm",
                Rule::Open(0, 10 * b_planet / kMm)
                    .Because("the length over which a load on one slice deflects its "
                             "neighbours (the Pasternak layer's sqrt(G/k)), up to ten face "
                             "widths")) *
        kMm;
  } else if (t->Has("coupling_length_mm")) {
    t->Fail("coupling_length_mm", "given with coupling = \"none\"",
            "a coupling length belongs to coupling = \"pasternak\"");
  }
  // The carrier's wind-up.
  if (t->Has("carrier_torsional_stiffness_Nm_per_rad")) {
    needs_slices(*t, "carrier_torsional_stiffness_Nm_per_rad");
    f.carrier_torsional_stiffness =
        t->Real("carrier_torsional_stiffness_Nm_per_rad",
                Rule::Positive().Because("the torque that twists the carrier's two plates by "
                                         "one radian against each other"));
    f.carrier_plate_distance =
        t->RealOr("carrier_plate_distance_mm", b_planet / kMm,
                  Rule{b_planet / kMm, 100 * b_planet / kMm, false, false, ""}.Because(
                      "the pins span the plates, at least the planet's face width")) *
        kMm;
    f.carrier_output_side = t->StringOr("carrier_output_side", "+z", {"+z", "-z"}) == "+z" ? 1 : -1;
  }
  for (TableReader& r : t->TableArray("pin_tilt")) {
    PinTilt p;
    p.where = r.Where("planet");
    p.planet = static_cast<int>(
                   r.Integer("planet", Rule::Closed(1, st.planets)
                                           .Because("planets are numbered 1.." +
                                                    std::to_string(st.planets)))) -
               1;
    needs_slices(r, "planet");
    const double over = r.RealOr("over_mm", b_planet / kMm,
                                 Rule::Positive().Because("the length over which the pin's "
                                                          "parallelism deviation is measured")) *
                        kMm;
    const double radial_um = r.RealOr("radial_um", 0, Rule::Any());
    const double tangential_um = r.RealOr("tangential_um", 0, Rule::Any());
    p.radial = radial_um * kUm / over;
    p.tangential = tangential_um * kUm / over;
    p.where += " (radial_um = " + io::Num(radial_um, io::kInputDigits) + ", tangential_um = " +
               io::Num(tangential_um, io::kInputDigits) + " over " + io::Num(over / kMm, io::kInputDigits) + " mm)";
    for (const PinTilt& q : f.pin_tilts)
      if (q.planet == p.planet)
        r.Fail("planet", std::to_string(p.planet + 1),
               "planet " + std::to_string(p.planet + 1) + " already has a pin tilt at " +
                   q.where + "; give one per planet");
    r.Done();
    f.pin_tilts.push_back(p);
  }
  for (TableReader& r : t->TableArray("lead")) {
    LeadSpec l;
    l.where = r.Where("gear");
    const GearSpec* spec = &NamedGear(r, gears, &l.gear);
    needs_slices(r, "gear");
    const double b = spec->face_width;
    l.slope = r.RealOr("slope_um", 0, Rule::Any()) * kUm;
    l.crowning = r.RealOr("crowning_um", 0,
                          Rule::NonNegative().Because(
                              "material removed at each end of the face width; a negative "
                              "crowning would add material")) *
                 kUm;
    l.end_relief = r.RealOr("end_relief_um", 0,
                            Rule::NonNegative().Because("material removed at each end")) *
                   kUm;
    if (l.end_relief > 0) {
      l.end_relief_length =
          r.Real("end_relief_length_mm",
                 Rule{0, 0.5 * b / kMm, true, false, ""}.Because(
                     "the relieved length at each end, at most half the face width")) *
          kMm;
    }
    for (const LeadSpec& q : f.leads)
      if (q.gear == l.gear)
        r.Fail("gear", "\"" + l.gear + "\"",
               "the gear already has a lead entry at " + q.where + "; give one per gear");
    r.Done();
    f.leads.push_back(l);
  }
  ReadPins(*t, s);
  if (f.carrier_torsional_stiffness > 0)
    f.carrier_where = t->Where("carrier_torsional_stiffness_Nm_per_rad");
  CheckFaceGapWindow(s);
  t->Done();
}

}  // namespace epicycle::transmission::internal

namespace epicycle::transmission {

namespace {

// Refuses a mesh whose gap changes across the face by more than half the search's window.
void CheckMeshBound(const internal::MeshBound& bound, const std::string& mesh, const Scene& s) {
  if (bound.change > 0.5 * s.gap_window)
    throw std::invalid_argument(
        bound.key + ": the gap changes by up to " +
        io::Num(bound.change / internal::kUm, io::kInputDigits) +
        " um between the mid-plane and an end of the " + mesh +
        " mesh, more than half the contact search's gap window (contact.gap_window_um = " +
        io::Num(s.gap_window / internal::kUm, io::kInputDigits) +
        "): the search runs in the mid-plane and would miss a slice's contact; widen the "
        "window or reduce the misalignment");
}

// A lead entry named for the gap-window message: the entry with the values that change the gap
// (l.where names its `gear` key: "file:line: face_width.lead[k].gear").
std::string LeadValues(const LeadSpec& l) {
  const std::string suffix = ".gear";
  std::string entry = l.where;
  if (entry.size() > suffix.size() && entry.ends_with(suffix))
    entry.resize(entry.size() - suffix.size());
  return entry + " (gear = \"" + l.gear +
         "\", slope_um = " + io::Num(l.slope / internal::kUm, io::kInputDigits) +
         ", crowning_um = " + io::Num(l.crowning / internal::kUm, io::kInputDigits) +
         ", end_relief_um = " + io::Num(l.end_relief / internal::kUm, io::kInputDigits) + ")";
}

}  // namespace

// The gap change across each mesh against the contact search's window: the search runs in the
// mid-plane and finds the contacts whose gap there is within the window; a slice closer than the
// mid-plane by more than half the window could carry where the search found nothing.
void CheckFaceGapWindow(const Scene& s) {
  const FaceWidthSpec& f = s.face_width;
  const geometry::StageSpec& st = s.stage;
  if (!f.active()) return;
  if (s.kind == SceneKind::kPair) {
    internal::MeshBound bound;
    for (const LeadSpec& l : f.leads)
      bound.Add(0.5 * std::abs(l.slope) + l.crowning + l.end_relief, LeadValues(l));
    CheckMeshBound(bound, "gear1-gear2", s);
    return;
  }
  const double b_planet = st.planet.face_width;
  const double ratio = static_cast<double>(st.ring.teeth) / st.sun.teeth;
  const double carrier_torque = std::abs(s.loads.sun_torque) * (1 + ratio);
  const double wind_up = f.carrier_torsional_stiffness > 0
                             ? carrier_torque / f.carrier_torsional_stiffness * st.carrier_radius /
                                   f.carrier_plate_distance
                             : 0.0;
  auto lead_of = [&](const std::string& gear) -> const LeadSpec* {
    for (const LeadSpec& l : f.leads)
      if (l.gear == gear) return &l;
    return nullptr;
  };
  for (int i = 0; i < st.planets; ++i) {
    const std::string planet = "planet" + std::to_string(i + 1);
    for (const std::string& mate : {std::string("sun"), std::string("ring")}) {
      const geometry::GearSpec& other = mate == "sun" ? st.sun : st.ring;
      const double b = std::min(b_planet, other.face_width);
      internal::MeshBound bound;
      auto add = [&](double change, const std::string& key) { bound.Add(change, key); };
      for (const PinTilt& p : f.pin_tilts)
        if (p.planet == i) add(0.5 * b * std::hypot(p.radial, p.tangential), p.where);
      if (wind_up > 0)
        add(0.5 * b * wind_up,
            f.carrier_where + " = " + io::Num(f.carrier_torsional_stiffness, io::kInputDigits) +
                " (every pin tilted by " + io::Num(wind_up * 1e6, io::kInputDigits) +
                " urad under the carrier torque " + io::Num(carrier_torque, io::kInputDigits) +
                " N m)");
      for (const std::string& g : {planet, mate}) {
        if (const LeadSpec* l = lead_of(g))
          add(0.5 * std::abs(l->slope) + l->crowning + l->end_relief, LeadValues(*l));
      }
      CheckMeshBound(bound, mate == "sun" ? "sun-" + planet : planet + "-ring", s);
    }
  }
}

}  // namespace epicycle::transmission
