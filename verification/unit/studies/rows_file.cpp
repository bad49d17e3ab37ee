// A rows file with CRLF line ends (converted after it was written) is refused saying so, not as
// "written by another study" with two lines that print the same.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "epicycle/studies/runner.hpp"
#include "program_runs.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;

TEST_CASE("a rows file converted to CRLF line ends is named as such", "[unit][studies]") {
  test::TempDir dir("study-crlf");
  const studies::StudySpec study = test::PinStudy("seed = 3\nsamples = 2\npositions = 4");
  studies::RunOptions o;
  o.rows_file = dir.File("rows.csv");
  o.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  o.threads = 1;
  o.max_new_cases = 1;
  studies::RunStudy(study, o);
  REQUIRE(studies::ReadRows(o.rows_file, study).rows.size() == 1);  // as written: resumable
  std::string crlf;
  for (char c : test::FileBytes(o.rows_file)) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  test::WriteText(o.rows_file, crlf);
  try {
    studies::ReadRows(o.rows_file, study);
    FAIL("a CRLF rows file read");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Catch::Contains("rows.csv:1: the line ends in CR") &&
                             Catch::Contains("CRLF") && !Catch::Contains("another study"));
  }
}
