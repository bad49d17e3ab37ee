// The dynamic run's CSV files killed (SIGKILL: no chance to tidy up) at several points of a run
// of the `epicycle` program: every file holds its header and whole lines (each with the header's
// columns) but for at most a last line without its end (the system may stop a write killed at a
// page boundary of the file; a reader drops that line), and the files agree on the complete
// steps: a step is complete when its line is in dynamic_steps.csv, and the pairs and bearings
// files hold those steps and at most the next one (report/run_files.hpp, DynamicRunFiles).
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "program_runs.hpp"

namespace {

// A CSV file as a reader takes it: its column line and whole data lines ('#' provenance skipped;
// a last line without its end dropped).
struct Csv {
  std::string header;
  std::vector<std::string> rows;
};

Csv Read(const std::string& path) {
  std::string text = epicycle::test::FileBytes(path);
  Csv c;
  if (!text.empty() && text.back() != '\n') text.erase(text.rfind('\n') + 1);
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind('#', 0) == 0) continue;
    if (c.header.empty()) {
      c.header = line;
    } else {
      c.rows.push_back(line);
    }
  }
  return c;
}

// "prefix<n>" (a stream: GCC 12's -Wrestrict misfires on a literal + std::to_string).
std::string Named(const char* prefix, long n) {
  std::ostringstream s;
  s << prefix << n;
  return s.str();
}

long Columns(const std::string& line) { return std::count(line.begin(), line.end(), ',') + 1; }

std::string Time(const std::string& row) { return row.substr(0, row.find(',')); }

// Lines of steps data in the file now (-1 before its head: provenance and column lines).
long StepRows(const std::string& path) {
  const std::string text = epicycle::test::FileBytes(path);
  const long lines = std::count(text.begin(), text.end(), '\n');
  return lines < 2 ? -1 : lines - 2;
}

}  // namespace

TEST_CASE("dynamic CSVs killed at any point: whole lines, the same complete steps",
          "[unit][report][kill]") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / Named("epicycle-dynamic-kill-", ::getpid());
  std::filesystem::remove_all(dir);
  // Kill points: as soon as the steps file has its head (created last: the other files have
  // theirs), then after some steps; the run (a planet revolution at 200 outputs per mesh cycle)
  // is far longer.
  for (const long kill_after : {0L, 3L, 20L, 60L}) {
    const std::string out = (dir / Named("k", kill_after)).string();
    const std::string steps = out + "/dynamic_steps.csv";
    const pid_t pid = epicycle::test::SpawnQuiet(
        {EPICYCLE_EXE, "dynamic", std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml", "--range",
         "planet", "--outputs-per-cycle", "200", "--quiet", "--cache", EPICYCLE_TEST_CACHE_DIR,
         "--out", out});
    REQUIRE(pid > 0);
    int status = 0;
    bool exited = false;
    for (int i = 0; i < 12000; ++i) {  // at most 2 min on a loaded machine
      if (waitpid(pid, &status, WNOHANG) == pid) {
        exited = true;
        break;
      }
      if (StepRows(steps) >= kill_after) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    INFO("killed after " << kill_after << " steps seen");
    REQUIRE_FALSE(exited);  // still running: the kill interrupts it
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    REQUIRE(WIFSIGNALED(status));

    const Csv s = Read(steps), p = Read(out + "/dynamic_pairs.csv"),
              b = Read(out + "/dynamic_bearings.csv");
    for (const Csv* c : {&s, &p, &b}) {
      REQUIRE_FALSE(c->header.empty());  // written when the file was created
      for (const std::string& row : c->rows) CHECK(Columns(row) == Columns(c->header));
    }
    CHECK(s.header.rfind("time_s,carrier_deg,LSR_1", 0) == 0);
    CHECK(static_cast<long>(s.rows.size()) >= kill_after);
    // Complete steps: those of the steps file. A step is written pairs, bearings, steps: the
    // bearings file has the complete steps and at most the next one, the pairs file every
    // complete step's pairs (a loaded stage always has a loaded tooth pair) and at most those of
    // the next step, the one the bearings file has if it has one.
    REQUIRE(b.rows.size() >= s.rows.size());
    CHECK(b.rows.size() <= s.rows.size() + 1);
    std::set<std::string> complete;
    for (std::size_t k = 0; k < s.rows.size(); ++k) {
      CHECK(Time(b.rows[k]) == Time(s.rows[k]));
      complete.insert(Time(s.rows[k]));
    }
    std::set<std::string> pair_times, next;
    for (const std::string& row : p.rows) {
      pair_times.insert(Time(row));
      if (complete.count(Time(row)) == 0) next.insert(Time(row));
    }
    for (const std::string& t : complete) CHECK(pair_times.count(t) == 1);
    CHECK(next.size() <= 1);
    if (!next.empty() && b.rows.size() > s.rows.size()) CHECK(*next.begin() == Time(b.rows.back()));
    if (b.rows.size() > s.rows.size()) CHECK(next.size() == 1);  // its pairs came before it
  }
  std::filesystem::remove_all(dir);
}
