// The report library's file writers: whole lines read back as written, every failure a
// std::runtime_error naming the file and the system's reason (a missing folder: ENOENT; a full
// device, /dev/full: ENOSPC at the write), and numbers for cells that are never nan or inf.
#include <catch2/catch.hpp>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "epicycle/report/files.hpp"
#include "program_runs.hpp"

using Catch::Matchers::Contains;
using namespace epicycle;

namespace {

std::string Thrown(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("epicycle_report_test_" + name)).string();
}

}  // namespace

TEST_CASE("CsvFile writes whole lines and a text file its bytes", "[unit][report]") {
  const std::string path = TempPath("lines.csv");
  {
    report::CsvFile csv(path);
    csv.Write("# provenance\na,b\n");
    csv.WriteLine("1,2");
    csv.WriteLine("");
    // Every call is flushed: the lines are in the file before it is closed.
    CHECK(test::FileBytes(path) == "# provenance\na,b\n1,2\n\n");
    csv.Close();
    CHECK_THAT(Thrown([&] { csv.WriteLine("3,4"); }), Contains(path));
  }
  const std::string text = std::string("{\n  \"x\": 1\n}\n") + '\0' + "tail";
  report::WriteTextFile(path, text);
  CHECK(test::FileBytes(path) == text);
  std::filesystem::remove(path);
}

TEST_CASE("a failed open or write throws naming the file and the reason", "[unit][report]") {
  const std::string missing = TempPath("no_such_folder") + "/x.csv";
  const std::string enoent = std::strerror(ENOENT);
  CHECK_THAT(Thrown([&] { report::CsvFile csv(missing); }),
             Contains(missing) && Contains("cannot be written") && Contains(enoent));
  CHECK_THAT(Thrown([&] { report::WriteTextFile(missing, "x"); }),
             Contains(missing) && Contains(enoent));
  if (std::filesystem::exists("/dev/full")) {
    const std::string enospc = std::strerror(ENOSPC);
    report::CsvFile full("/dev/full");  // opens; the device refuses every write
    CHECK_THAT(Thrown([&] { full.WriteLine("1,2"); }), Contains("/dev/full") && Contains(enospc));
    CHECK_THAT(Thrown([&] { report::WriteTextFile("/dev/full", "text"); }),
               Contains("/dev/full") && Contains(enospc));
  }
}

TEST_CASE("Cell and Num format finite numbers and leave the rest missing", "[unit][report]") {
  CHECK(report::Cell(0.1) == "0.1");
  CHECK(report::Cell(1.0 / 3.0) == "0.333333333");
  CHECK(report::Figure(-2.5e-7, "{:.3e}") == "-2.500e-07");
  CHECK(report::Figure(12.3456, "{:.2f}", "-") == "12.35");
  CHECK(report::Cell(std::numeric_limits<double>::quiet_NaN()).empty());
  CHECK(report::Figure(std::numeric_limits<double>::infinity(), "{:.3e}", "not finite") ==
        "not finite");
  CHECK(report::Figure(-std::numeric_limits<double>::infinity(), "{:.2f}", "-") == "-");
}

TEST_CASE("CsvText quotes a text cell as RFC 4180 says, on one line", "[unit][report]") {
  CHECK(report::CsvText("planet tooth") == "planet tooth");  // nothing to quote
  CHECK(report::CsvText("planet tooth, both flanks") == "\"planet tooth, both flanks\"");
  CHECK(report::CsvText("say \"no\"") == "\"say \"\"no\"\"\"");  // quotes doubled
  CHECK(report::CsvText("planet #2") == "\"planet #2\"");     // pandas' comment='#' reads it whole
  CHECK(report::CsvText("a, b\nc\r\nd") == "\"a, b;c;;d\"");  // a row stays one line
  CHECK(report::CsvText("").empty());
}
