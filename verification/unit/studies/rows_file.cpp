// A rows file with CRLF line ends (converted after it was written) is refused saying so, not as
// "written by another study" with two lines that print the same.
#include <catch2/catch.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/sampling.hpp"
#include "program_runs.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;

namespace {

// A run that computes one case into DIR/rows.csv.
studies::RunOptions OneNewCase(const test::TempDir& dir) {
  studies::RunOptions o;
  o.rows_file = dir.File("rows.csv");
  o.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  o.threads = 1;
  o.max_new_cases = 1;
  return o;
}

}  // namespace

TEST_CASE("a rows file converted to CRLF line ends is named as such", "[unit][studies]") {
  test::TempDir dir("study-crlf");
  const studies::StudySpec study = test::PinStudy("seed = 3\nsamples = 2\npositions = 4");
  const studies::RunOptions o = OneNewCase(dir);
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

// A row edited after it was written (a K_γ changed by hand) would be resumed and move the
// summary: its check field no longer matches its text. A row with a consistent check but sampled
// values that the study's seed does not give its case (copied from another run of another seed)
// is refused too, naming the column and both values. The references are the rows as written and
// the sampling itself (studies::SampleCase), not the reader.
TEST_CASE("a rows file with an edited row or foreign sampled values is refused, naming the line",
          "[unit][studies]") {
  test::TempDir dir("study-edited");
  const studies::StudySpec study = test::PinStudy("seed = 3\nsamples = 2\npositions = 4");
  const studies::RunOptions o = OneNewCase(dir);
  const studies::RunReport report = studies::RunStudy(study, o);
  REQUIRE(report.rows.size() == 1);
  const std::string written = test::FileBytes(o.rows_file);
  const std::string row = report.rows[0].Format();
  REQUIRE(written.size() > row.size());
  REQUIRE(written.substr(written.size() - row.size()) == row);
  const std::string head = written.substr(0, written.size() - row.size());
  const int line = 1 + static_cast<int>(std::count(head.begin(), head.end(), '\n'));

  SECTION("K_gamma edited") {
    std::string changed = row.substr(0, row.rfind(','));  // the row without its check
    REQUIRE(changed.find(",ok,") != std::string::npos);
    // Replace the K_γ field (3 fields after the status) by 999.
    std::size_t p = changed.find(",ok,") + 4;
    for (int f = 0; f < 2; ++f) p = changed.find(',', p) + 1;
    const std::size_t end = changed.find(',', p);
    changed.replace(p, end - p, "999");
    test::WriteText(o.rows_file, head + changed + row.substr(row.rfind(',')));
    try {
      studies::ReadRows(o.rows_file, study);
      FAIL("an edited row was resumed");
    } catch (const std::invalid_argument& e) {
      CHECK_THAT(e.what(), Catch::Contains("rows.csv:" + std::to_string(line) + ":") &&
                               Catch::Contains("changed after it was written"));
    }
  }
  SECTION("the sampled value of another seed, with a matching check") {
    studies::CaseRow foreign = report.rows[0];
    const std::vector<double> ours = studies::SampleCase(study, foreign.id);
    REQUIRE(foreign.values == ours);
    foreign.values[0] += 1.0;
    test::WriteText(o.rows_file, head + foreign.Format());
    try {
      studies::ReadRows(o.rows_file, study);
      FAIL("a row of another sampling was resumed");
    } catch (const std::invalid_argument& e) {
      CHECK_THAT(e.what(), Catch::Contains("rows.csv:" + std::to_string(line) + ":") &&
                               Catch::Contains(study.Columns()[0]) &&
                               Catch::Contains("not computed by this study"));
    }
  }
  SECTION("as written, it is resumed") {
    CHECK(studies::ReadRows(o.rows_file, study).rows.size() == 1);
  }
}
