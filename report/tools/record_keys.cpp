// `epicycle_record_keys`: every driver record's fields as markdown tables (docs/records.md), each
// key with its kind and the unit its name carries. The lists come from the records' own
// VisitRecord functions, visited with every optional part present (friction, stresses, a rating, a
// healthy twin), so that the docs list exactly what the summary JSON files can hold.
//
//   epicycle_record_keys > table.md        (tools/record_keys.sh writes it into docs/records.md)
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/modes_run.hpp"
#include "epicycle/dynamics/speed_sweep_run.hpp"
#include "epicycle/solvers/backend_comparison.hpp"
#include "epicycle/studies/study_run.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "epicycle/transmission/record.hpp"
#include "epicycle/transmission/stiffness_run.hpp"

namespace {

using epicycle::transmission::RecordVisitor;

// The unit a key's suffix names (docs/records.md, "Units in the keys").
std::string Unit(const std::string& key) {
  static const std::vector<std::pair<std::string, std::string>> suffixes = {
      {"_N_per_mm_um", "N/(mm·µm)"},
      {"_N_per_m", "N/m"},
      {"_Hz_per_sun_rpm", "Hz/rpm"},
      {"_rad_per_s", "rad/s"},
      {"_Nm", "N·m"},
      {"_N", "N"},
      {"_urad", "µrad"},
      {"_um", "µm"},
      {"_mm", "mm"},
      {"_MPa", "MPa"},
      {"_Hz", "Hz"},
      {"_rpm", "rpm"},
      {"_deg", "deg"},
      {"_rad", "rad"},
      {"_m", "m"},
      {"_W", "W"},
      {"_seconds", "s"},
      {"_s", "s"}};
  for (const auto& [suffix, unit] : suffixes)
    if (key.size() > suffix.size() &&
        key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0)
      return unit;
  return "";
}

// Prints one table row per field, nested fields as PARENT[].KEY (a list's items) or PARENT.KEY.
class KeyTable final : public RecordVisitor {
 public:
  void Number(const char* key, double) override { Row(key, "number"); }
  void Integer(const char* key, long) override { Row(key, "integer"); }
  void Unsigned(const char* key, unsigned long long) override { Row(key, "integer"); }
  void Flag(const char* key, bool) override { Row(key, "true/false"); }
  void Text(const char* key, const std::string&) override { Row(key, "text"); }
  void Texts(const char* key, const std::vector<std::string>&) override {
    Row(key, "list of texts");
  }
  void Numbers(const char* key, const std::vector<double>&) override {
    Row(key, "list of numbers");
  }
  void Integers(const char* key, const std::vector<long>&) override {
    Row(key, "list of integers");
  }
  void BeginObject(const char* key) override {
    Row(key, "object");
    Open(key, ".");
  }
  void EndObject() override { Close(); }
  void BeginList(const char* key) override {
    Row(key, "list of objects");
    Open(key, "[].");
  }
  void Item() override {}  // the sample records hold one item per list
  void EndList() override { Close(); }
  void Stresses(const epicycle::transmission::SweepSummary&) override {
    Row("root_stress", "object (per gear: docs/stresses.md)");
    Row("contact_pressure", "object (per gear and flank: docs/stresses.md)");
  }
  void Rating(const char* key, const epicycle::transmission::StageRating&) override {
    Row(key, "object (ISO 6336: docs/stresses.md)");
  }
  void RootStress(const char* key, const std::vector<epicycle::transmission::RootStressSummary>&,
                  const char*, double) override {
    Row(key, "object (per gear: docs/stresses.md)");
  }

 private:
  std::vector<std::string> prefix_;
  std::vector<std::string> units_;  // the unit of each open object or list ("" for none)
  void Open(const char* key, const char* separator) {
    prefix_.push_back(std::string(key) + separator);
    units_.push_back(KeyUnit(key));
  }
  void Close() {
    prefix_.pop_back();
    units_.pop_back();
  }
  // A key's unit: its own, or for a statistic of a quantity (a study's mean, its interval, a
  // percentile's value) the quantity's.
  std::string KeyUnit(const std::string& key) const {
    const std::string own = Unit(key);
    static const std::vector<std::string> statistics = {"mean", "mean_ci", "std", "min",
                                                        "max",  "value",   "ci",  "percentiles"};
    if (!own.empty() || units_.empty()) return own;
    for (const std::string& s : statistics)
      if (key == s) return units_.back();
    return "";
  }
  void Row(const std::string& key, const char* kind) {
    std::string name;
    for (const std::string& p : prefix_) name += p;
    name += key;
    const std::string unit = KeyUnit(key);
    std::printf("| `%s` | %s | %s |\n", name.c_str(), kind, unit.empty() ? "-" : unit.c_str());
  }
};

// The axial loads of a helical stage with one planet (its keys listed once).
epicycle::transmission::HelicalLoads OnePlanetLoads() {
  epicycle::transmission::HelicalLoads loads;
  loads.planets.resize(1);
  return loads;
}

void Table(const char* title, const char* file, const auto& record) {
  std::printf("### %s\n\n%s\n\n| key | kind | unit |\n|---|---|---|\n", title, file);
  KeyTable table;
  VisitRecord(record, table);
  std::printf("| `provenance` | object (the program's: version, build, inputs) | - |\n\n");
}

}  // namespace

int main() {
  using namespace epicycle;
  // Every optional part present, so that every field the record can hold is listed.
  transmission::QuasiStaticRecord quasistatic;
  quasistatic.summary.lsr_mean = quasistatic.summary.lsr_min = quasistatic.summary.lsr_max = {0};
  quasistatic.summary.friction = true;
  quasistatic.summary.root_stress.resize(1);
  quasistatic.summary.contact_pressure.resize(1);
  quasistatic.summary.face_width.resize(1);
  quasistatic.summary.face_width[0].stresses = true;
  quasistatic.summary.helical_mean.planets.resize(1);
  quasistatic.summary.pin_tilts.resize(1);
  quasistatic.friction = transmission::FrictionLaw::kConstant;
  quasistatic.rating.emplace();
  quasistatic.failures_not_listed = 1;
  transmission::StiffnessRecord stiffness;
  stiffness.result.root_stress.resize(1);
  stiffness.result.slices = 2;
  stiffness.result.helical = true;
  stiffness.helix_angle = 0.1;
  stiffness.healthy = stiffness.result;
  dynamics::ModesRecord modes;
  modes.modes.resize(1);
  modes.coincidences.resize(1);

  Table("Quasi-static run (`epicycle quasistatic`, Python `quasistatic(...)[\"record\"]`)",
        "OUT/quasistatic_summary.json; `failures_not_listed` only when failures were not listed, "
        "`friction` and the efficiency keys only with friction at rest, `root_stress` and "
        "`contact_pressure` only with stresses, `rating` only when asked, `face_width` only with "
        "slices of the face width (its root stress and Hertz pressure keys only with stresses), "
        "`helical` only for a helical stage, `pins` only with pins of finite stiffness.",
        quasistatic);
  Table("Mesh stiffness (`epicycle stiffness`, Python `mesh_stiffness(...)[\"record\"]`)",
        "OUT/stiffness_MESH.json; `root_stress` only with stresses, the `slices` and K_Hbeta keys "
        "only with slices of the face width, `peak_slice_pair_stiffness_N_per_mm_um`, "
        "`helix_angle_deg` and `overlap_ratio` only for a helical pair, `healthy` only beside a "
        "damaged tooth's cycles.",
        stiffness);
  studies::StudyRecord study;
  study.summary.k_gamma.percentiles.resize(1);
  study.summary.k_gamma_exceedance.resize(1);
  study.summary.root_stress.resize(1);
  study.summary.root_stress[0].s_f.count = study.summary.root_stress[0].s_h.count = 1;
  study.summary.face_width.resize(1);
  study.summary.columns = {"COLUMN"};
  study.summary.spearman = {0};
  study.summary.helical.push_back({"HELICAL_COLUMN", {}});
  studies::SobolSummary sobol;
  sobol.variables = {"VARIABLE"};
  sobol.outputs.push_back({"OUTPUT", {}});
  sobol.outputs[0].estimate.first.resize(1);
  sobol.outputs[0].estimate.total.resize(1);
  study.summary.sobol = sobol;

  Table("Natural modes (`epicycle modes --json FILE`, Python `modes(...)[\"record\"]`)", "FILE.",
        modes);
  Table("Tolerance study (`epicycle study`, Python `study(...)[\"record\"]`)",
        "OUT/study_summary.json; `K_gamma_exceedance` only with the study's k_gamma_limit, "
        "`root_stress` only with stresses (`S_F`, `S_H` only when rated), `face_width` only with "
        "slices of the face width, `helical` only for a helical stage (HELICAL_COLUMN: each of "
        "its rows' axial-load columns, docs/studies.md), `sobol` only with the Sobol design. `spearman_K_gamma` has one "
        "key per sampled-value column (COLUMN), "
        "`sobol.outputs` one object per rows-file result column (OUTPUT).",
        study);
  dynamics::DynamicRecord dynamic;
  dynamic.summary.lsr_mean = dynamic.summary.lsr_min = dynamic.summary.lsr_max = {0};
  dynamic.summary.root_stress.resize(1);
  dynamic.summary.face_width.resize(1);
  dynamic.summary.helical_mean.planets.resize(1);
  dynamic.rating.emplace();
  Table("Dynamic run (`epicycle dynamic`, Python `dynamic(...)[\"record\"]`)",
        "OUT/dynamic_summary.json; `root_stress` only with stresses, `rating` only when asked, "
        "`face_width` only with slices of the face width, `helical` only for a helical stage (the "
        "means over the steps written).",
        dynamic);
  dynamics::SpeedSweepRecord sweep;
  sweep.plan.meshes = {"MESH"};
  sweep.plan.qs_peak_mesh_force = {0};
  sweep.plan.modes.resize(1);
  sweep.plan.coincidences.resize(1);
  sweep.speeds.resize(1);
  sweep.speeds[0].status = transmission::RunStatus::kCompleted;
  sweep.speeds[0].helical.Add(OnePlanetLoads());
  Table("Speed sweep (`epicycle dynamic --speed-sweep`, Python `speed_sweep(...).record`)",
        "OUT/speed_sweep_summary.json; MESH is each mesh's name (`sun-planet1`, ...); a speed "
        "that did not complete has only `speeds[]`'s keys up to `warnings` (its status and "
        "message, no figures); `speeds[].helical` only for a helical stage (over the window).",
        sweep);
  dynamics::BranchRecord branch;
  branch.branch.parameter = "PARAMETER";  // not the sun speed: both columns listed
  branch.branch.points.resize(1);
  branch.branch.points[0].helical.Add(OnePlanetLoads());
  branch.branch.bifurcations.resize(1);
  Table("Branch of periodic orbits (`epicycle dynamic --speed-sweep ... --periodic`, `--continue`; "
        "Python `periodic_branch(...).record`)",
        "OUT/periodic_branch_summary.json; PARAMETER is the continued parameter's name "
        "(`sun_speed_rpm`, `sun_torque_Nm` or `mesh_damping_ratio`, docs/periodic.md §3), "
        "`points[].sun_speed_rpm` beside it only when it is another, `points[].helical` only "
        "for a helical stage (over the period).",
        branch);
  solvers::ComparisonRecord comparison;
  comparison.summaries.resize(1);
  comparison.runs.resize(1);
  Table("Comparison of contact back ends (`epicycle contact compare --json FILE`, Python "
        "`compare_backends(...).record`)",
        "FILE; errors and residuals nondimensional (docs/solvers.md), an error null where not "
        "computed (a back end that threw).",
        comparison);
  return 0;
}
