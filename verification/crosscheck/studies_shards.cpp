// Shards of a study (docs/studies.md "Shards"): the parts of 1, 3 and 7 shards (and of uneven
// --cases ranges) joined by `epicycle study merge` are the files of a single run of the program,
// byte for byte (the summary's computed_seconds aside: the merge computed nothing); a missing,
// repeated, foreign, incomplete or truncated part is refused naming the part file and the case
// range; a shard killed while running resumes like a whole study. The reference of every check is
// a single run of the same study by the same program.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "epicycle/studies/shards.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "program_runs.hpp"
#include "study_fixtures.hpp"
#include "thrown_message.hpp"

using namespace epicycle;

namespace {

// Pins of every planet (σ = 5 µm) and a torque grid of two values: 2·samples cases of a few ms.
std::string Study(long samples, int seed = 5, int positions = 4) {
  return test::StudyText(
      "seed = " + std::to_string(seed) + "\nsamples = " + std::to_string(samples) +
          "\npositions = " + std::to_string(positions),
      "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planets\"\ndistribution = "
      "\"normal\"\nsigma_um = 5.0\n[[variable]]\nquantity = \"torque\"\n"
      "distribution = \"grid\"\nvalues_Nm = [-400.0, -600.0]\n");
}

// Runs the program to its end; its exit status.
int Program(std::vector<std::string> args) {
  args.insert(args.begin(), EPICYCLE_EXE);
  const pid_t pid = test::SpawnQuiet(args);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> StudyArgs(const std::string& file, const std::string& out) {
  return {"study", file, "--out", out, "--quiet", "--cache", EPICYCLE_TEST_CACHE_DIR};
}

std::vector<std::string> With(std::vector<std::string> a, const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// The summary JSON without computed_seconds (the merge's is 0: it computed nothing).
nlohmann::json SummaryWithoutTime(const std::string& folder) {
  nlohmann::json j = nlohmann::json::parse(test::FileBytes(folder + "/study_summary.json"));
  j.erase("computed_seconds");
  return j;
}

// The four files of a run in `folder` equal the reference's (rows and plots byte for byte).
bool SameFiles(const std::string& folder, const std::string& reference) {
  bool same = true;
  for (const char* f : {"/study_rows.csv", "/study_kgamma_hist.svg", "/study_kgamma_cdf.svg"}) {
    const std::string a = test::FileBytes(folder + f), b = test::FileBytes(reference + f);
    INFO(folder << f);
    CHECK(!b.empty());
    CHECK(a == b);
    same = same && !b.empty() && a == b;
  }
  const bool json = SummaryWithoutTime(folder) == SummaryWithoutTime(reference);
  CHECK(json);
  return same && json;
}

std::string Rows(const std::string& path) {
  std::istringstream in(test::FileBytes(path));
  std::string line, rows;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#' && line.rfind("case,", 0) != 0) rows += line + "\n";
  return rows;
}

}  // namespace

TEST_CASE("study shards: 1, 3 and 7 shards and uneven case ranges merged are a single run's files",
          "[crosscheck][studies]") {
  test::TempDir dir("study-shards");
  const std::string file = test::WriteText(dir.File("shards.toml"), Study(21));  // 42 cases
  test::Compliance("paper_stage.toml");  // the tables in the cache before the runs
  const std::string single = dir.File("single");
  REQUIRE(Program(With(StudyArgs(file, single), {"--threads", "1"})) == 0);
  for (int n : {1, 3, 7}) {
    const std::string parts = dir.File("parts" + std::to_string(n)),
                      merged = dir.File("merged" + std::to_string(n));
    for (int k = 0; k < n; ++k)  // two threads per shard: the merge orders the rows by case
      REQUIRE(Program(With(StudyArgs(file, parts),
                           {"--shard", std::to_string(k) + "/" + std::to_string(n), "--threads",
                            "2"})) == 0);
    REQUIRE(Program({"study", "merge", parts, "--out", merged}) == 0);
    INFO(n << " shards");
    const bool same = SameFiles(merged, single);
    test::VerifyRow(std::to_string(n) + " shard(s) of a 42-case study merged",
                    "a single run of the program", "rows CSV, summary JSON, two SVG",
                    same ? "identical bytes" : "DIFFER", "identical (computed_seconds aside)",
                    same);
  }
  // Uneven ranges given as --cases, each part file named on the merge's command line.
  const std::string parts = dir.File("ranges"), merged = dir.File("merged-ranges");
  for (const char* r : {"0:5", "5:40", "40:42"})
    REQUIRE(Program(With(StudyArgs(file, parts), {"--cases", r, "--threads", "1"})) == 0);
  REQUIRE(Program({"study", "merge", parts + "/study_cases_40_42.csv",
                   parts + "/study_cases_0_5.csv", parts + "/study_cases_5_40.csv", "--out",
                   merged, "--study", file}) == 0);
  CHECK(SameFiles(merged, single));
}

TEST_CASE("study shards: a missing, repeated, foreign, incomplete or truncated part is refused by "
          "name",
          "[crosscheck][studies]") {
  test::TempDir dir("study-shards-bad");
  const std::string file = test::WriteText(dir.File("bad.toml"), Study(6));  // 12 cases
  const std::string other = test::WriteText(dir.File("other.toml"), Study(6, 6));  // seed 6
  test::Compliance("paper_stage.toml");
  const std::string parts = dir.File("parts");
  for (int k = 0; k < 3; ++k)
    REQUIRE(Program(With(StudyArgs(file, parts), {"--shard", std::to_string(k) + "/3"})) == 0);
  const studies::StudySpec s = studies::ReadStudy(file);
  const std::string p0 = parts + "/study_cases_0_4.csv", p1 = parts + "/study_cases_4_8.csv",
                    p2 = parts + "/study_cases_8_12.csv";
  auto merge_error = [&](const std::vector<std::string>& given) {
    return test::ThrownMessage([&] { studies::MergeParts(s, studies::FindParts(given)); });
  };
  CHECK(merge_error({p0, p1, p2}) == "(nothing thrown)");
  // Missing: the cases between its neighbours, both named.
  CHECK_THAT(merge_error({p0, p2}),
             Catch::Contains("cases 4:8 are in no part (between " + p0 + " (cases 0:4) and " + p2 +
                             " (cases 8:12))"));
  CHECK_THAT(merge_error({p1, p2}), Catch::Contains("cases 0:4 are in no part (before " + p1));
  CHECK_THAT(merge_error({p0, p1}), Catch::Contains("cases 8:12 are in no part (after " + p1));
  // Repeated: a copy of shard 1 elsewhere, and the same file twice.
  std::filesystem::create_directories(dir.File("copy"));
  const std::string copy = dir.File("copy/study_cases_4_8.csv");
  std::filesystem::copy_file(p1, copy);
  CHECK_THAT(merge_error({parts, copy}),
             Catch::Contains(" overlap in cases 4:8") && Catch::Contains(copy + " (cases 4:8)") &&
                 Catch::Contains(p1 + " (cases 4:8)"));
  // Another study's part (another seed): named, with both study lines.
  REQUIRE(Program(With(StudyArgs(other, dir.File("other")), {"--cases", "4:8"})) == 0);
  const std::string foreign = dir.File("other/study_cases_4_8.csv");
  CHECK_THAT(merge_error({p0, foreign, p2}),
             Catch::Contains(foreign + " (cases 4:8) is a part of another study") &&
                 Catch::Contains("seed 6") && Catch::Contains("seed 5"));
  // An incomplete part (a shard stopped after 2 of its 4 cases).
  REQUIRE(Program(With(StudyArgs(file, dir.File("short")), {"--shard", "1/3", "--max-cases", "2"})) ==
          0);
  const std::string incomplete = dir.File("short/study_cases_4_8.csv");
  CHECK_THAT(merge_error({p0, incomplete, p2}),
             Catch::Contains(incomplete + " (cases 4:8) holds 2 of its 4 cases (the first "
                                          "missing: case 6)"));
  // A truncated last row (killed while writing): refused, the part left as it is.
  const std::string truncated = dir.File("short/study_cases_4_8.csv");
  const std::string text = test::FileBytes(truncated) + "6,1.5";
  test::WriteText(truncated, text);
  CHECK_THAT(merge_error({p0, truncated, p2}),
             Catch::Contains(truncated + " (cases 4:8) ends in a truncated row"));
  CHECK(test::FileBytes(truncated) == text);
  // The whole rows file of a single run is not a part.
  REQUIRE(Program(With(StudyArgs(file, dir.File("whole")), {"--threads", "1"})) == 0);
  CHECK_THAT(merge_error({dir.File("whole/study_rows.csv")}),
             Catch::Contains("study_rows.csv: not a study part"));
  // The program: exit status 2 (bad input), and nothing written.
  CHECK(Program({"study", "merge", p0, p2, "--out", dir.File("merged")}) == 2);
  CHECK(!std::filesystem::exists(dir.File("merged/study_rows.csv")));
  // The truncated part resumes: its shard run again completes it, and the merge is the single
  // run's.
  REQUIRE(Program(With(StudyArgs(file, dir.File("short")), {"--shard", "1/3"})) == 0);
  REQUIRE(Program({"study", "merge", p0, incomplete, p2, "--out", dir.File("merged")}) == 0);
  CHECK(SameFiles(dir.File("merged"), dir.File("whole")));
}

TEST_CASE("study shards: a shard killed while running resumes like a whole study",
          "[crosscheck][studies]") {
  test::TempDir dir("study-shard-kill");
  const std::string file = test::WriteText(dir.File("kill.toml"), Study(100, 5, 12));  // 200
  test::Compliance("paper_stage.toml");
  const std::string parts = dir.File("parts"), part = parts + "/study_cases_100_200.csv";
  const pid_t pid = test::SpawnQuiet(
      With({EPICYCLE_EXE}, With(StudyArgs(file, parts), {"--shard", "1/2", "--threads", "2"})));
  REQUIRE(pid > 0);
  // Kill it (SIGKILL) once 10 rows are in its part.
  long seen = 0;
  for (int i = 0; i < 30000 && seen < 10; ++i) {  // at most 5 min on a loaded machine
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const std::string rows = Rows(part);
    seen = static_cast<long>(std::count(rows.begin(), rows.end(), '\n'));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::string before = Rows(part);
  const long killed_at = static_cast<long>(std::count(before.begin(), before.end(), '\n'));
  INFO(killed_at << " rows when killed");
  REQUIRE(killed_at >= 10);
  REQUIRE(killed_at < 100);  // it was interrupted
  // The merge refuses the incomplete part; the shard run again computes only its missing cases.
  REQUIRE(Program(With(StudyArgs(file, parts), {"--shard", "0/2", "--threads", "2"})) == 0);
  CHECK(Program({"study", "merge", parts, "--out", dir.File("merged")}) == 2);
  REQUIRE(Program(With(StudyArgs(file, parts), {"--shard", "1/2", "--threads", "2"})) == 0);
  REQUIRE(Program({"study", "merge", parts, "--out", dir.File("merged")}) == 0);
  REQUIRE(Program(With(StudyArgs(file, dir.File("single")), {"--threads", "1"})) == 0);
  const bool same = SameFiles(dir.File("merged"), dir.File("single"));
  test::VerifyRow("shard 1/2 of 200 cases killed (SIGKILL) after " + std::to_string(killed_at) +
                      " of its 100 rows, run again, merged",
                  "a single run of the program", "rows CSV, summary JSON, two SVG",
                  same ? "identical bytes" : "DIFFER", "identical (computed_seconds aside)", same);
}
