// The enums read from and written as words, each through one table (io/enum_names.hpp): the words
// are those the docs give (docs/scenes.md: [dynamics] friction, [supports] sun, [model] plane;
// docs/quasistatic.md: --range, --friction; docs/solvers.md: the back ends), each once, and every
// value's word leads back to the value through the readers the scene, the programs and the
// bindings use.
#include <catch2/catch.hpp>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/friction.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/scene.hpp"

using namespace epicycle;
using Words = std::vector<std::string>;

namespace {

template <class Table>
void CheckTable(const Table& table, const Words& documented) {
  CHECK(io::Names(table) == documented);
  std::set<std::string> seen;
  for (const auto& e : table) {
    INFO(e.name);
    CHECK(seen.insert(e.name).second);
    REQUIRE(io::ValueOf(table, e.name).has_value());
    CHECK(*io::ValueOf(table, e.name) == e.value);
    CHECK(io::NameOf(table, e.value) == std::string(e.name));
  }
}

}  // namespace

TEST_CASE("every enum read from a word has one table of the documented words",
          "[unit][transmission]") {
  CheckTable(transmission::kFrictionLawNames,
             Words{"off", "constant", "xu-kahraman", "benedict-kelley"});
  CheckTable(transmission::kRunRangeNames, Words{"cycle", "planet", "sun", "revolution"});
  CheckTable(transmission::kSunSupportNames, Words{"fixed", "floating", "elastic"});
  CheckTable(solvers::kPlaneAssumptionNames, Words{"strain", "stress"});
  // The named functions read the same tables.
  for (const auto& e : transmission::kFrictionLawNames) {
    CHECK(transmission::FrictionLawName(e.value) == e.name);
    CHECK(transmission::FrictionLawFromName(e.name) == e.value);
  }
  for (const auto& e : transmission::kRunRangeNames)
    CHECK(transmission::RunRangeFromName(e.name) == e.value);
  for (const auto& e : transmission::kSunSupportNames)
    CHECK(transmission::SunSupportName(e.value) == std::string(e.name));
  for (const char* name : {"newton", "ipopt", "nlopt-slsqp", "nlopt-lbfgs", "nlopt-auglag"})
    CHECK(solvers::BackendName(solvers::BackendFromName(name)) == name);
  CHECK(transmission::RestFrictionNames() ==
        Words{"off", "scene", "constant", "xu-kahraman", "benedict-kelley"});
}

TEST_CASE("an unknown word is refused with the table's words", "[unit][transmission]") {
  CHECK_THROWS_WITH(transmission::FrictionLawFromName("dry"),
                    "friction law \"dry\": must be one of off, constant, xu-kahraman, "
                    "benedict-kelley");
  CHECK_THROWS_WITH(transmission::RunRangeFromName("week"),
                    "range = 'week': must be cycle, planet, sun or revolution");
  CHECK_THROWS_WITH(solvers::BackendFromName("simplex"),
                    "backend = 'simplex': must be one of newton, ipopt, nlopt-slsqp, "
                    "nlopt-lbfgs, nlopt-auglag");
  transmission::QuasiStaticOptions options;
  CHECK_THROWS_WITH(transmission::SetRestFriction(transmission::DynamicSettings{}, "wet", &options),
                    "friction = \"wet\": must be one of off, scene, constant, xu-kahraman, "
                    "benedict-kelley");
}
