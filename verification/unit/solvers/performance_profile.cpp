// The Dolan–Moré performance profile on a hand-made table of three problems and two back ends.
#include <catch2/catch.hpp>

#include "epicycle/solvers/performance_profile.hpp"

using namespace epicycle::solvers;

TEST_CASE("Dolan-More profile of a hand-made table", "[unit][solvers]") {
  // Best times: P1 1 s (A), P2 1 s (B), P3 4 s (B, the only one to solve it); P4 nobody.
  const std::vector<ProfileRun> runs = {
      {"P1", "A", 1.0, true},  {"P2", "A", 2.0, true},  {"P3", "A", 0.5, false},
      {"P1", "B", 2.0, true},  {"P2", "B", 1.0, true},  {"P3", "B", 4.0, true},
      {"P4", "A", 1.0, false}, {"P4", "B", 1.0, false},
  };
  const auto p = DolanMoreProfile(runs, {"B", "A"});
  REQUIRE(p.size() == 2);
  CHECK(p[0].backend == "B");
  CHECK(p[0].ratios == std::vector<double>{1.0, 1.0, 2.0});
  CHECK(p[1].backend == "A");
  CHECK(p[1].ratios == std::vector<double>{1.0, 2.0});  // a failed run is not in its profile
  // ρ(τ) over the 4 problems: at τ = 1 B has solved 2 within the best time, A 1.
  CHECK(p[0].Fraction(1.0, 4) == 0.5);
  CHECK(p[1].Fraction(1.0, 4) == 0.25);
  CHECK(p[0].Fraction(1.99, 4) == 0.5);
  CHECK(p[0].Fraction(2.0, 4) == 0.75);
  CHECK(p[1].Fraction(1e9, 4) == 0.5);
  CHECK(p[1].Fraction(0.5, 4) == 0.0);
}
