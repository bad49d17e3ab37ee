// A partial run of a huge study (`--max-cases`) in memory bounded by what it computes: a study of
// 1e9 samples run for 3 new cases lists and computes 3 cases (the first ids without a row, after
// a resume the next ones) and the process's peak memory stays far below the gigabytes that one
// flag, or one id, per case of the study would take.
#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <string>

#include "epicycle/studies/runner.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;

namespace {

long PeakRssKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;  // kB on Linux
}

}  // namespace

TEST_CASE("a partial run of a study of 1e9 samples computes and lists only its cases",
          "[unit][studies]") {
  test::TempDir dir("study-huge");
  const studies::StudySpec study = test::PinStudy("seed = 3\nsamples = 1000000000\npositions = 4");
  REQUIRE(study.Cases() == 1000000000L);
  studies::RunOptions o;
  o.rows_file = dir.File("rows.csv");
  o.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  o.threads = 1;
  o.max_new_cases = 3;
  const studies::RunReport first = studies::RunStudy(study, o);
  CHECK(first.computed == 3);
  REQUIRE(first.rows.size() == 3);
  for (long k = 0; k < 3; ++k) CHECK(first.rows[static_cast<std::size_t>(k)].id == k);
  const studies::RunReport second = studies::RunStudy(study, o);  // resumed: the next three
  CHECK(second.resumed == 3);
  CHECK(second.computed == 3);
  REQUIRE(second.rows.size() == 6);
  CHECK(second.rows.back().id == 5);
  // A byte per case would be 1 GB, an id per case 8 GB; the run itself needs ~0.1 GB.
  CHECK(PeakRssKb() < 500 * 1024);
}
