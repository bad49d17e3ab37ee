// A driver's record has one definition of its fields (transmission::VisitRecord,
// dynamics::VisitRecord) and one serialisation (report::RecordJson): the summary JSON that the
// program writes has exactly the record's keys, and the program writes the record that the
// library's run returns for the same request, value for value (docs/quasistatic.md, docs/records.md),
// for the quasi-static, dynamic, speed-sweep, mesh-stiffness, modes, study and periodic-branch
// drivers.
#include <catch2/catch.hpp>

#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/modes_run.hpp"
#include "epicycle/dynamics/speed_sweep_run.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/solvers/backend_comparison.hpp"
#include "epicycle/studies/study_run.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "epicycle/transmission/stiffness_run.hpp"
#include "program_runs.hpp"

namespace epicycle {
namespace {

// The top-level keys a record's visit names (the keys of the objects inside a list, an object or a
// composite belong to those).
class KeyList final : public transmission::RecordVisitor {
 public:
  std::set<std::string> keys;
  void Number(const char* key, double) override { Add(key); }
  void Integer(const char* key, long) override { Add(key); }
  void Unsigned(const char* key, unsigned long long) override { Add(key); }
  void Flag(const char* key, bool) override { Add(key); }
  void Text(const char* key, const std::string&) override { Add(key); }
  void Texts(const char* key, const std::vector<std::string>&) override { Add(key); }
  void Numbers(const char* key, const std::vector<double>&) override { Add(key); }
  void Integers(const char* key, const std::vector<long>&) override { Add(key); }
  void BeginObject(const char* key) override {
    Add(key);
    ++depth_;
  }
  void EndObject() override { --depth_; }
  void BeginList(const char* key) override {
    Add(key);
    ++depth_;
  }
  void Item() override {}
  void EndList() override { --depth_; }
  void Stresses(const transmission::SweepSummary& s) override {
    if (!s.root_stress.empty()) Add("root_stress");
    if (!s.contact_pressure.empty()) Add("contact_pressure");
  }
  void Rating(const char* key, const transmission::StageRating&) override { Add(key); }
  void RootStress(const char* key, const std::vector<transmission::RootStressSummary>&,
                  const char*, double) override {
    Add(key);
  }

 private:
  int depth_ = 0;  // inside a list or an object: not a top-level key
  void Add(const char* key) {
    if (depth_ > 0) return;
    const bool fresh = keys.insert(key).second;
    INFO("key " << key);
    CHECK(fresh);  // each field once
  }
};

class NoSink final : public transmission::QuasiStaticSink {};
class NoDynamicSink final : public dynamics::DynamicSink {};

std::set<std::string> Keys(const nlohmann::json& j) {
  std::set<std::string> out;
  for (const auto& item : j.items()) out.insert(item.key());
  return out;
}

// What two runs may differ in: their wall times and the program's provenance.
void DropRunDependent(nlohmann::json* j) {
  for (const char* k : {"sweep_seconds", "table_seconds", "setup_seconds", "wall_seconds",
                        "evaluation_seconds", "provenance"})
    j->erase(k);
}

// The program's summary JSON `program` against the library's `record` (`library`: its JSON): the
// file's keys are the record's fields (the provenance is the program's, not the run's), and every
// value is the same bit for bit (the JSON numbers are written with 17 digits and read back
// exactly), the wall times aside.
// The file's top-level keys against the record's fields (the provenance is the program's).
template <class Record>
void CheckKeys(const nlohmann::json& program, const Record& record) {
  KeyList fields;
  VisitRecord(record, fields);
  std::set<std::string> file_keys = Keys(program);
  file_keys.erase("provenance");
  CHECK(file_keys == fields.keys);
}

template <class Record>
void CheckSameRecord(nlohmann::json program, const Record& record, nlohmann::json library) {
  CheckKeys(program, record);
  DropRunDependent(&program);
  DropRunDependent(&library);
  CHECK(program == library);
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE(
    "quasi-static record: the program's summary JSON has exactly the record's fields and the "
    "library run's values (rating, friction, stresses, a list of angles)",
    "[crosscheck][report][records]") {
  const test::TempDir temp("quasistatic-record");
  const std::string scene_file =
      std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_runout_rated.toml";
  REQUIRE(
      test::ExitStatus({EPICYCLE_EXE, "quasistatic", scene_file, "--rating", "--friction",
                        "xu-kahraman", "--angles-deg", "0", "1.5", "3", "--threads", "1", "--cache",
                        EPICYCLE_TEST_CACHE_DIR, "--quiet", "--out", temp.path.string()}) == 0);
  std::ifstream in(temp.File("quasistatic_summary.json"));
  REQUIRE(in.good());
  nlohmann::json program = nlohmann::json::parse(in);

  transmission::QuasiStaticRequest request;
  request.scene = transmission::ReadScene(scene_file);
  request.rating = true;
  request.friction = "xu-kahraman";
  request.angles_deg = {0.0, 1.5, 3.0};
  request.threads = 1;
  request.tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  NoSink sink;
  const transmission::QuasiStaticRecord record = transmission::RunQuasiStatic(request, sink);
  REQUIRE(record.converged_positions == 3);
  REQUIRE(record.rating.has_value());
  REQUIRE(record.friction.has_value());

  CheckSameRecord(program, record, report::QuasiStaticRecordJson(record, nlohmann::json()));
}

// The dynamic run's record: one mesh cycle with stresses and a rating (the fields that only some
// runs have: root_stress, rating), the same request through the program and through the library.
TEST_CASE(
    "dynamic record: the program's summary JSON has exactly the record's fields and the library "
    "run's values (stresses, rating)",
    "[crosscheck][report][records]") {
  const test::TempDir temp("dynamic-record");
  const std::string scene_file =
      std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_runout_rated.toml";
  REQUIRE(test::ExitStatus({EPICYCLE_EXE, "dynamic", scene_file, "--range", "cycle",
                            "--outputs-per-cycle", "24", "--rating", "--cache",
                            EPICYCLE_TEST_CACHE_DIR, "--quiet", "--out",
                            temp.path.string()}) == 0);
  std::ifstream in(temp.File("dynamic_summary.json"));
  REQUIRE(in.good());
  nlohmann::json program = nlohmann::json::parse(in);

  dynamics::DynamicRequest request;
  request.scene = transmission::ReadScene(scene_file);
  request.range = transmission::RunRange::kMeshCycle;
  request.outputs_per_cycle = 24;
  request.rating = true;
  request.tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  NoDynamicSink sink;
  const dynamics::DynamicRecord record = dynamics::RunDynamic(request, sink);
  REQUIRE(record.completed());
  REQUIRE(record.rating.has_value());
  REQUIRE_FALSE(record.summary.root_stress.empty());
  CHECK(record.summary.samples == 24);

  CheckSameRecord(program, record, report::DynamicRecordJson(record, nlohmann::json()));
}

TEST_CASE(
    "stiffness record: the program's summary JSON has exactly the record's fields and the "
    "library run's values (root stresses)",
    "[crosscheck][report][records]") {
  const test::TempDir temp("stiffness-record");
  const std::string scene_file = std::string(EPICYCLE_SCENES_DIR) + "/iso_pair_20_40.toml";
  REQUIRE(test::ExitStatus({EPICYCLE_EXE, "stiffness", scene_file, "--positions", "6",
                            "--stresses", "--threads", "1", "--cache", EPICYCLE_TEST_CACHE_DIR,
                            "--out", temp.path.string()}) == 0);
  nlohmann::json program = ReadJson(temp.File("stiffness_gear1-gear2.json"));

  transmission::StiffnessRequest request;
  request.scene = transmission::ReadScene(scene_file);
  request.positions = 6;
  request.stresses = true;
  request.threads = 1;
  request.tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  transmission::StiffnessSink sink;
  const transmission::StiffnessRecord record = transmission::RunStiffness(request, sink);
  REQUIRE(record.result.failed == 0);
  REQUIRE_FALSE(record.result.root_stress.empty());

  KeyList fields;
  transmission::VisitRecord(record, fields);
  std::set<std::string> file_keys = Keys(program);
  file_keys.erase("provenance");  // the program's, not the run's
  CHECK(file_keys == fields.keys);
  CHECK(fields.keys.count("root_stress") == 1);
  // Every value bit for bit (17 significant digits written and read back).
  program.erase("provenance");
  CHECK(program == report::RecordJson(record));
}

TEST_CASE(
    "modes record: the program's JSON has exactly the record's fields and the library run's "
    "values (modes, coincidences)",
    "[crosscheck][report][records]") {
  const test::TempDir temp("modes-record");
  const std::string scene_file = std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml";
  REQUIRE(test::ExitStatus({EPICYCLE_EXE, "modes", scene_file, "--sun", "floating",
                            "--speed-range-rpm", "100", "20000", "--cache",
                            EPICYCLE_TEST_CACHE_DIR, "--json", temp.File("modes.json")}) == 0);
  nlohmann::json program = ReadJson(temp.File("modes.json"));

  dynamics::ModesRequest request;
  request.scene = transmission::ReadScene(scene_file);
  request.sun = transmission::SunSupport::kFloating;
  request.speed_range_rpm = std::array<double, 2>{100, 20000};
  request.tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  dynamics::ModesSink sink;
  const dynamics::ModesRecord record = dynamics::RunModes(request, sink);
  REQUIRE_FALSE(record.modes.empty());
  REQUIRE_FALSE(record.coincidences.empty());

  CheckKeys(program, record);
  program.erase("provenance");
  CHECK(program == report::RecordJson(record));
}

TEST_CASE(
    "study record: the program's summary JSON has exactly the record's fields and the library "
    "run's values (exceedances, Spearman columns)",
    "[crosscheck][report][records]") {
  const test::TempDir temp("study-record");
  const std::string study_file =
      std::string(EPICYCLE_TEST_DATA_DIR) + "/studies/kgamma_limit_small.toml";
  REQUIRE(test::ExitStatus({EPICYCLE_EXE, "study", study_file, "--threads", "1", "--cache",
                            EPICYCLE_TEST_CACHE_DIR, "--quiet", "--out",
                            temp.File("program")}) == 0);
  nlohmann::json program = ReadJson(temp.File("program/study_summary.json"));

  studies::StudyRequest request;
  request.study = studies::ReadStudy(study_file);
  request.study_path = study_file;
  request.threads = 1;
  request.rows_file = temp.File("library_rows.csv");
  request.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  studies::StudySink sink;
  const studies::StudyRun run = studies::RunStudy(request, sink);
  REQUIRE(run.record.has_value());
  REQUIRE(run.record->summary.cases == 4);
  REQUIRE(run.record->summary.k_gamma_exceedance.size() == 2);

  CheckKeys(program, *run.record);
  // The values, the wall time of the computation aside.
  nlohmann::json library = report::RecordJson(*run.record);
  for (nlohmann::json* j : {&program, &library})
    for (const char* k : {"provenance", "computed_seconds"}) j->erase(k);
  CHECK(program == library);
}

// The speed sweep's record: two speeds of one mesh cycle each (the modes, the coincidences, each
// speed's figures and the load-sharing parts), the same request through the program and through
// the library; the times (the plan's, the speeds' wall and CPU) differ between two runs.
TEST_CASE(
    "speed-sweep record: the program's summary JSON has exactly the record's fields and the "
    "library run's values (modes, coincidences, speeds)",
    "[crosscheck][report][records]") {
  const test::TempDir temp("speed-sweep-record");
  const std::string scene_file = std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml";
  REQUIRE(test::ExitStatus({EPICYCLE_EXE, "dynamic", scene_file, "--speed-sweep", "1000:3000:2",
                            "--window-cycles", "1", "--outputs-per-cycle", "8", "--threads", "2",
                            "--cache", EPICYCLE_TEST_CACHE_DIR, "--quiet", "--out",
                            temp.path.string()}) == 0);
  nlohmann::json program = ReadJson(temp.File("speed_sweep_summary.json"));

  dynamics::SpeedSweepRequest request;
  request.run.scene = transmission::ReadScene(scene_file);
  request.run.outputs_per_cycle = 8;
  request.run.tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  request.sun_speeds_rpm = {1000, 3000};
  request.window_cycles = 1;
  request.threads = 2;
  dynamics::SpeedSweepSink sink;
  const dynamics::SpeedSweepRecord record = dynamics::RunSpeedSweep(request, sink);
  REQUIRE(record.failed() == 0);
  REQUIRE(record.speeds.size() == 2);
  REQUIRE_FALSE(record.plan.modes.empty());

  CheckKeys(program, record);
  nlohmann::json library = report::RecordJson(record);
  for (nlohmann::json* j : {&program, &library}) {
    for (const char* k :
         {"provenance", "plan_seconds", "wall_seconds", "cpu_seconds_in_speeds", "cpu_over_wall"})
      j->erase(k);
    for (nlohmann::json& speed : (*j)["speeds"])
      for (const char* k : {"cpu_s", "wall_s"}) speed.erase(k);
  }
  CHECK(program == library);
}

// The periodic branch's record: the sun speed from 4000 to 4100 rpm in steps of at most half the
// range (docs/periodic.md §3), the same request through the program and through the library; the
// continuation's CPU and wall times differ between two runs.
TEST_CASE(
    "periodic-branch record: the program's summary JSON has exactly the record's fields and the "
    "library run's values (points, bifurcations)",
    "[crosscheck][report][records]") {
  const test::TempDir temp("branch-record");
  const std::string scene_file = std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml";
  REQUIRE(test::ExitStatus({EPICYCLE_EXE, "dynamic", scene_file, "--speed-sweep", "4000:4100:2",
                            "--periodic", "--cache", EPICYCLE_TEST_CACHE_DIR, "--quiet", "--out",
                            temp.path.string()}) == 0);
  nlohmann::json program = ReadJson(temp.File("periodic_branch_summary.json"));

  dynamics::BranchRequest request;
  request.run.scene = transmission::ReadScene(scene_file);
  request.run.tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  request.parameter = dynamics::StagePeriodicSystem::kSunSpeed;
  request.start = 4000;
  request.end = 4100;
  request.steps = 2;
  dynamics::BranchSink sink;
  const dynamics::BranchRecord record = dynamics::RunBranch(request, sink);
  REQUIRE(record.ok());
  REQUIRE(record.branch.points.size() >= 2);

  CheckKeys(program, record);
  nlohmann::json library = report::RecordJson(record);
  for (nlohmann::json* j : {&program, &library})
    for (const char* k : {"provenance", "cpu_seconds", "wall_seconds"}) j->erase(k);
  CHECK(program == library);
}

TEST_CASE(
    "comparison record: `contact compare --json` has exactly the record's fields and the library "
    "comparison's values (a failed run included)",
    "[crosscheck][report][records]") {
  // Two problems of the collection, one with a reference that cannot converge at 1e-12
  // (stiff_cond1e10_s1: cond(C) = 1e10) and every back end at --tol 1e-30, so that the failures'
  // list and the not-solved runs are in the record too.
  const test::TempDir temp("comparison-record");
  const std::string data = std::string(EPICYCLE_TEST_DATA_DIR) + "/contact/";
  const std::vector<std::string> inputs = {data + "cf_two_symmetric.json",
                                           data + "stiff_cond1e10_s1.json"};
  REQUIRE(test::ExitStatus({EPICYCLE_EXE, "contact", "compare", inputs[0], inputs[1], "--tol",
                            "1e-30", "--repeat", "1", "--json",
                            temp.File("compare.json")}) == 1);
  nlohmann::json program = ReadJson(temp.File("compare.json"));

  solvers::ComparisonRequest request;
  request.inputs = inputs;
  request.options.tolerance = 1e-30;
  request.repeats = 1;
  class NoComparisonSink final : public solvers::ComparisonSink {
    void Failure(const std::string&) override {}
    void Run(const solvers::ComparisonRun&) override {}
  } sink;
  const solvers::ComparisonRecord record = solvers::RunComparison(request, sink);
  REQUIRE(!record.failures.empty());

  CheckKeys(program, record);
  nlohmann::json library = report::RecordJson(record);
  // The wall times are the only values two runs may differ in.
  for (nlohmann::json* j : {&program, &library}) {
    j->erase("provenance");
    for (const char* list : {"backends", "runs"})
      for (nlohmann::json& item : (*j)[list]) item.erase("median_seconds");
  }
  CHECK(program == library);
  CHECK(program["runs"].size() == record.files.size() * record.backends.size());
  CHECK(program["failures"].size() == record.failures.size());
}

}  // namespace epicycle
