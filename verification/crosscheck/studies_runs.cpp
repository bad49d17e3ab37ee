// Running studies (docs/studies.md): the same seed gives identical rows with 1 and 4 threads and
// with 1 and 2 MPI ranks (when built with MPI); a study killed while running and restarted ends
// with the rows of an uninterrupted run, none lost or duplicated; a truncated last row is dropped.
// The reference of each check is another run of the same study (threads, ranks, uninterrupted).
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>
#include <thread>

#include "epicycle/config.h"
#include "epicycle/studies/runner.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "program_runs.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;
using test::VerifyRow;

namespace {

// Pins of every planet (σ = 5 µm), a run-out of planet 2 and a torque grid: every kind of
// variable; 12 positions over the mesh cycle keep a case at a few ms.
std::string Study(long samples) {
  return test::StudyText(
      "seed = 11\nsamples = " + std::to_string(samples) + "\npositions = 12",
      "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planets\"\ndistribution = "
      "\"normal\"\nsigma_um = 5.0\n[[variable]]\nquantity = \"runout\"\ngear = \"planet2\"\n"
      "distribution = \"iso1328\"\ngrade = 6\n[[variable]]\nquantity = \"torque\"\n"
      "distribution = \"grid\"\nvalues_Nm = [-400.0, -600.0]\n");
}

// The data lines of a rows file, sorted (rows are written in completion order).
std::vector<std::string> SortedRows(const std::string& file) {
  std::istringstream in(test::FileBytes(file));
  std::vector<std::string> rows;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#' && line.rfind("case,", 0) != 0) rows.push_back(line);
  std::sort(rows.begin(), rows.end());
  return rows;
}

long Ids(const std::vector<std::string>& rows) {
  std::set<std::string> ids;
  for (const std::string& r : rows) ids.insert(r.substr(0, r.find(',')));
  return static_cast<long>(ids.size());
}

studies::RunReport Run(const studies::StudySpec& s, const std::string& file, int threads,
                       long max_cases = -1) {
  studies::RunOptions o;
  o.rows_file = file;
  o.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  o.threads = threads;
  o.max_new_cases = max_cases;
  return studies::RunStudy(s, o);
}

}  // namespace

TEST_CASE("study: identical rows with 1 and 4 threads, a restart computes only what is missing",
          "[crosscheck][studies]") {
  test::TempDir dir("study-threads");
  const studies::StudySpec s = studies::ParseStudy(Study(20), "threads.toml", "");  // 40 cases
  const auto one = Run(s, dir.File("one.csv"), 1);
  const auto four = Run(s, dir.File("four.csv"), 4);
  REQUIRE(one.computed == s.Cases());
  const auto a = SortedRows(dir.File("one.csv")), b = SortedRows(dir.File("four.csv"));
  CHECK(a.size() == static_cast<std::size_t>(s.Cases()));
  CHECK(a == b);
  long ok = 0;
  for (const auto& r : one.rows) ok += r.ok() ? 1 : 0;
  CHECK(ok == s.Cases());
  VerifyRow("study, 40 cases: rows with 4 threads against 1 thread", "the 1-thread rows",
            std::to_string(b.size()) + " rows", a == b ? "identical bytes" : "DIFFER", "identical",
            a == b);

  // Partial run (15 cases), then a restart: the union is the full run, nothing twice.
  const auto part = Run(s, dir.File("part.csv"), 2, 15);
  CHECK(part.computed == 15);
  // A run killed while writing leaves a truncated last line: dropped, recomputed.
  const std::string half = a.back().substr(0, a.back().size() / 2);
  { std::ofstream(dir.File("part.csv"), std::ios::app) << half; }
  const auto rest = Run(s, dir.File("part.csv"), 2);
  CHECK(rest.dropped_partial);
  CHECK(rest.resumed == 15);
  CHECK(rest.computed == s.Cases() - 15);
  CHECK(SortedRows(dir.File("part.csv")) == a);
  // A complete file: nothing to compute.
  CHECK(Run(s, dir.File("part.csv"), 2).computed == 0);
}

TEST_CASE("study: rows of another study are refused", "[crosscheck][studies]") {
  test::TempDir dir("study-other");
  const auto s = studies::ParseStudy(Study(2), "a.toml", "");
  Run(s, dir.File("rows.csv"), 1, 1);
  const auto other = studies::ParseStudy(Study(3), "b.toml", "");
  try {
    Run(other, dir.File("rows.csv"), 1);
    FAIL("no error");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(),
               Catch::Contains("rows.csv:1") && Catch::Contains("written by another study"));
  }
}

TEST_CASE("study: killed while running and restarted, the rows of an uninterrupted run",
          "[crosscheck][studies]") {
  test::TempDir dir("study-kill");
  const std::string file = test::WriteText(dir.File("kill.toml"), Study(150));  // 300 cases
  const studies::StudySpec s = studies::ReadStudy(file);
  const std::string out = dir.File("out"), rows = out + "/study_rows.csv";
  auto program = [&](const std::string& folder) {
    return std::vector<std::string>{EPICYCLE_EXE, "study",   file,      "--out",
                                    folder,       "--quiet", "--cache", EPICYCLE_TEST_CACHE_DIR,
                                    "--threads",  "2"};
  };
  const auto spawn = test::SpawnQuiet;
  test::Compliance("paper_stage.toml");  // the tables in the cache before the clock starts
  const pid_t pid = spawn(program(out));
  REQUIRE(pid > 0);
  // Kill it (SIGKILL: no chance to tidy up) once 40 rows are in the file.
  long seen = 0;
  for (int i = 0; i < 30000 && seen < 40; ++i) {  // at most 5 min on a loaded machine
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    seen = static_cast<long>(SortedRows(rows).size());
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  const auto before = SortedRows(rows);
  INFO(before.size() << " rows when killed");
  REQUIRE(before.size() >= 40);
  REQUIRE(before.size() < static_cast<std::size_t>(s.Cases()));  // it was interrupted
  // Restart to the end; the reference is an uninterrupted run of the program.
  const pid_t again = spawn(program(out));
  waitpid(again, &status, 0);
  CHECK(WEXITSTATUS(status) == 0);
  const pid_t whole = spawn(program(dir.File("whole")));
  waitpid(whole, &status, 0);
  CHECK(WEXITSTATUS(status) == 0);
  const auto after = SortedRows(rows),
             reference = SortedRows(dir.File("whole") + "/study_rows.csv");
  CHECK(after.size() == static_cast<std::size_t>(s.Cases()));
  CHECK(Ids(after) == s.Cases());  // no case twice
  CHECK(after == reference);
  VerifyRow(
      "study killed (SIGKILL) after " + std::to_string(before.size()) + " of 300 rows, restarted",
      "an uninterrupted run's rows",
      std::to_string(after.size()) + " rows, " + std::to_string(Ids(after)) + " distinct cases",
      after == reference ? "identical bytes" : "DIFFER", "identical, none twice",
      after == reference && Ids(after) == s.Cases());
}

#if EPICYCLE_HAVE_MPI
TEST_CASE("study: identical rows with 1 and 2 MPI ranks (mpirun)", "[crosscheck][studies][mpi]") {
  test::TempDir dir("study-mpi");
  const std::string file = test::WriteText(dir.File("mpi.toml"), Study(20));
  const studies::StudySpec s = studies::ReadStudy(file);
  Run(s, dir.File("one.csv"), 1);
  // Root in containers and CI: OpenMPI refuses it without these two variables.
  const std::string cmd = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " +
                          std::string(EPICYCLE_MPIEXEC) + " --oversubscribe -np 2 " + EPICYCLE_EXE +
                          " study " + file + " --out " + dir.File("mpi") +
                          " --quiet --threads 1 --cache " + EPICYCLE_TEST_CACHE_DIR + " > " +
                          dir.File("mpi.log") + " 2>&1";
  const int rc = std::system(cmd.c_str());
  INFO(test::FileBytes(dir.File("mpi.log")));
  REQUIRE(rc == 0);
  const auto a = SortedRows(dir.File("one.csv"));
  const auto b = SortedRows(dir.File("mpi") + "/study_rows.csv");
  CHECK(a.size() == static_cast<std::size_t>(s.Cases()));
  CHECK(a == b);
  VerifyRow("study, 40 cases: rows with 2 MPI ranks against 1 process", "the 1-process rows",
            std::to_string(b.size()) + " rows", a == b ? "identical bytes" : "DIFFER", "identical",
            a == b);
}

// A rank that cannot build its tables (here its cache folder lies under a regular file: a node
// whose shared folder is not mounted) must not leave rank 0 waiting for its rows: rank 0 finishes
// its own share, names the rank and its reason, exits non-zero, and a rerun computes the rest.
// `timeout` turns a hang into a failure; the reference is the 1-process run.
TEST_CASE("study: a rank that fails stops the run with its message, and a rerun completes it",
          "[crosscheck][studies][mpi]") {
  test::TempDir dir("study-mpi-fail");
  const std::string file = test::WriteText(dir.File("mpi.toml"), Study(20));
  const studies::StudySpec s = studies::ReadStudy(file);
  Run(s, dir.File("one.csv"), 1);
  const std::string not_a_folder = test::WriteText(dir.File("plain"), "a file\n");
  auto rank = [&](const std::string& cache) {
    return std::string(" -np 1 ") + EPICYCLE_EXE + " study " + file + " --out " + dir.File("mpi") +
           " --quiet --threads 1 --cache " + cache;
  };
  const std::string launch =
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 300 " +
      std::string(EPICYCLE_MPIEXEC) + " --oversubscribe";
  const int failed =
      std::system((launch + rank(EPICYCLE_TEST_CACHE_DIR) + " :" + rank(not_a_folder + "/cache") +
                   " > " + dir.File("fail.log") + " 2>&1")
                      .c_str());
  const std::string log = test::FileBytes(dir.File("fail.log"));
  INFO(log);
  REQUIRE(WIFEXITED(failed));
  CHECK(WEXITSTATUS(failed) != 0);
  CHECK(WEXITSTATUS(failed) != 124);  // not timed out: rank 0 did not wait for the failed rank
  CHECK_THAT(log, Catch::Contains("rank 1 stopped") && Catch::Contains("Not a directory") &&
                      Catch::Contains("run the study again"));
  const auto reference = SortedRows(dir.File("one.csv"));
  const auto partial = SortedRows(dir.File("mpi") + "/study_rows.csv");
  // Rank 0's share: ids at even positions of the 40 missing ones; each row exactly as 1 process.
  CHECK(partial.size() == reference.size() / 2);
  for (const std::string& r : partial)
    CHECK(std::binary_search(reference.begin(), reference.end(), r));
  const int rerun = std::system((launch + " -np 2 " + EPICYCLE_EXE + " study " + file + " --out " +
                                 dir.File("mpi") + " --quiet --threads 1 --cache " +
                                 EPICYCLE_TEST_CACHE_DIR + " > " + dir.File("rerun.log") + " 2>&1")
                                    .c_str());
  INFO(test::FileBytes(dir.File("rerun.log")));
  REQUIRE(rerun == 0);
  const auto after = SortedRows(dir.File("mpi") + "/study_rows.csv");
  CHECK(after == reference);
  VerifyRow("study, 40 cases, 2 MPI ranks, rank 1's tables fail", "the 1-process rows",
            std::to_string(partial.size()) + " rows, then " + std::to_string(after.size()) +
                " after a rerun",
            after == reference ? "identical bytes" : "DIFFER", "rank 0's half, then identical",
            after == reference);
}
#endif
