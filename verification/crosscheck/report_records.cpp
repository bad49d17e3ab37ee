// A driver's record has one definition of its fields (transmission::VisitRecord) and one
// serialisation (report::RecordJson): the summary JSON that the program writes has exactly the
// record's keys, and the program writes the record that the library's run returns for the same
// request, value for value (docs/quasistatic.md).
#include <catch2/catch.hpp>

#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "program_runs.hpp"

namespace epicycle {
namespace {

// The top-level keys a record's visit names (the keys of the objects inside a list or a
// composite belong to those).
class KeyList final : public transmission::RecordVisitor {
 public:
  std::set<std::string> keys;
  void Number(const char* key, double) override { Add(key); }
  void Integer(const char* key, long) override { Add(key); }
  void Flag(const char* key, bool) override { Add(key); }
  void Text(const char* key, const std::string&) override { Add(key); }
  void Texts(const char* key, const std::vector<std::string>&) override { Add(key); }
  void BeginList(const char* key) override {
    Add(key);
    in_list_ = true;
  }
  void Item() override {}
  void EndList() override { in_list_ = false; }
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
  bool in_list_ = false;
  void Add(const char* key) {
    if (in_list_) return;
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
template <class Record>
void CheckSameRecord(nlohmann::json program, const Record& record, nlohmann::json library) {
  KeyList fields;
  VisitRecord(record, fields);
  std::set<std::string> file_keys = Keys(program);
  file_keys.erase("provenance");
  CHECK(file_keys == fields.keys);
  DropRunDependent(&program);
  DropRunDependent(&library);
  CHECK(program == library);
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

}  // namespace epicycle
