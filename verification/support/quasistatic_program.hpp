// The `quasistatic` program as an independent path for the study crosschecks (needs Catch2 and
// the EPICYCLE_EXE and EPICYCLE_TEST_CACHE_DIR definitions of the test targets).
#pragma once

#include <sys/wait.h>

#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "program_runs.hpp"

namespace epicycle::test {

/// The summary JSON of the `quasistatic` program on `scene` over one mesh cycle of `positions`,
/// fixed sun, one thread, the tests' table cache, `extra` options added (the study crosschecks'
/// independent path); its output folder `out`. Fails the test if the program fails.
inline std::string QuasiStaticCycleSummary(const std::string& scene, int positions,
                                           const std::string& out,
                                           const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{EPICYCLE_EXE,
                                "quasistatic",
                                scene,
                                "--range",
                                "cycle",
                                "--positions",
                                std::to_string(positions),
                                "--sun",
                                "fixed",
                                "--threads",
                                "1",
                                "--quiet",
                                "--cache",
                                EPICYCLE_TEST_CACHE_DIR,
                                "--out",
                                out};
  args.insert(args.end(), extra.begin(), extra.end());
  const pid_t pid = SpawnQuiet(args);
  int status = 0;
  waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);
  return FileBytes(out + "/quasistatic_summary.json");
}

}  // namespace epicycle::test
