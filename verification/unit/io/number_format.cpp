// The number format of messages (io/number_format.hpp) against the standard stream of the same
// precision, the reference the layers' messages were written with: the same text for every
// precision from 1 to 17 digits, for ordinary, tiny, huge and non-finite values.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "epicycle/io/number_format.hpp"

using epicycle::io::Num;

namespace {

std::string Stream(double v, int precision) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

}  // namespace

TEST_CASE("Num writes what a stream of that precision writes", "[unit][io]") {
  const double inf = std::numeric_limits<double>::infinity();
  for (double v : {0.0, -0.0, 1.0, -1500.0, 0.1 + 0.2, 1e-300, 6.02214076e23, 1e300,
                   std::nextafter(1.0, 2.0), 123456789.0123, inf, -inf}) {
    for (int p = 1; p <= 17; ++p) {
      INFO("v = " << Stream(v, 17) << ", precision " << p);
      CHECK(Num(v, p) == Stream(v, p));
    }
    // A stream's default precision is 6 (the standard's ios_base::init), Num's too.
    CHECK(Num(v) == Stream(v, 6));
  }
  CHECK(Num(std::nan("")) == Stream(std::nan(""), 6));
  // Hand-checked texts of the forms the messages show.
  CHECK(Num(1500.0) == "1500");
  CHECK(Num(0.001) == "0.001");
  CHECK(Num(1e20) == "1e+20");
  CHECK(Num(2.0 / 3.0, 10) == "0.6666666667");
}
