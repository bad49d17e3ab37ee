// A value given as fields (io/spec_fields.hpp) against the fields written out by hand and the
// standard library's own reading of each field: whole fields only, empty fields kept, a number too
// large for a long refused.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/io/spec_fields.hpp"

using epicycle::io::Fields;
using epicycle::io::Real;
using epicycle::io::Whole;

TEST_CASE("Fields splits at every separator, empty fields kept", "[unit][io]") {
  CHECK(Fields("500:12000:24", ':') == std::vector<std::string>{"500", "12000", "24"});
  CHECK(Fields("3/8", '/') == std::vector<std::string>{"3", "8"});
  CHECK(Fields("a::b:", ':') == std::vector<std::string>{"a", "", "b", ""});
  CHECK(Fields("", ':') == std::vector<std::string>{""});
  CHECK(Fields("no separator", ':') == std::vector<std::string>{"no separator"});
}

TEST_CASE("Real and Whole read a whole field or throw", "[unit][io]") {
  CHECK(Real("2.5") == 2.5);
  CHECK(Real("-600") == -600.0);
  CHECK(Real("1e3") == 1000.0);
  CHECK(Whole("24") == 24);
  CHECK(Whole("-3") == -3);
  // Text after the number, no number at all, a fraction for a count: std::stod/stol stop early
  // or find nothing; the field is refused.
  CHECK_THROWS_AS(Real("12x"), std::invalid_argument);
  CHECK_THROWS_AS(Real(""), std::invalid_argument);
  CHECK_THROWS_AS(Whole("2.5"), std::invalid_argument);
  CHECK_THROWS_AS(Whole("abc"), std::invalid_argument);
  // 1e20 is past the largest long (about 9.2e18 on LP64): std::stol's out_of_range.
  CHECK_THROWS_AS(Whole("100000000000000000000"), std::out_of_range);
  CHECK_THROWS_AS(Real("1e400"), std::out_of_range);
}
