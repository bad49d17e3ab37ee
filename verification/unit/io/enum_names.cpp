// The enums' name tables (io/enum_names.hpp): both directions read one table, so every value's
// name leads back to the value and every name not in the table is refused; the lists in messages
// are the table's names in order.
#include <catch2/catch.hpp>

#include <array>
#include <string>
#include <vector>

#include "epicycle/io/enum_names.hpp"

using namespace epicycle;

namespace {

enum class Colour { kRed, kGreen, kBlue, kUnnamed };
constexpr std::array<io::EnumName<Colour>, 3> kColourNames{
    {{Colour::kRed, "red"}, {Colour::kGreen, "green"}, {Colour::kBlue, "blue"}}};

}  // namespace

TEST_CASE("a name table: value to name and back, unknown names refused, lists", "[unit][io]") {
  for (const auto& e : kColourNames) {
    CHECK(io::NameOf(kColourNames, e.value) == std::string(e.name));
    REQUIRE(io::ValueOf(kColourNames, e.name).has_value());
    CHECK(*io::ValueOf(kColourNames, e.name) == e.value);
  }
  CHECK(io::NameOf(kColourNames, Colour::kUnnamed) == nullptr);
  CHECK_FALSE(io::ValueOf(kColourNames, "Red").has_value());
  CHECK_FALSE(io::ValueOf(kColourNames, "").has_value());
  CHECK(io::Names(kColourNames) == std::vector<std::string>{"red", "green", "blue"});
  CHECK(io::NameList(kColourNames) == "red, green, blue");
  CHECK(io::NameList(kColourNames, " or ") == "red, green or blue");
  static_assert(*io::ValueOf(kColourNames, "blue") == Colour::kBlue);
}
