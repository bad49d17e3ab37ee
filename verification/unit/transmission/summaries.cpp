// The one statistics accumulator (transmission/accumulator.hpp) on a hand-counted sequence and on
// empty input; the run ranges of a stage (transmission/run_range.hpp) against 2π/z_r, 2π z_p/z_r
// and 2π for the paper's 16/24/65 stage; the sun supports' names.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "epicycle/transmission/load_sharing.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/accumulator.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using transmission::RunRange;

TEST_CASE("the accumulator: count, sum, min, mean, max, NaN for empty input",
          "[unit][transmission]") {
  transmission::Accumulator a;
  CHECK(a.empty());
  CHECK(a.count() == 0);
  CHECK(a.sum() == 0.0);
  CHECK(std::isnan(a.min()));
  CHECK(std::isnan(a.max()));
  CHECK(std::isnan(a.mean()));
  // 3, −1, 4, 1, 5: sum 12, mean 12/5, min −1 (second), max 5 (last).
  for (double x : {3.0, -1.0, 4.0, 1.0, 5.0}) a.Add(x);
  CHECK(a.count() == 5);
  CHECK(a.sum() == 12.0);
  CHECK(a.mean() == 12.0 / 5.0);
  CHECK(a.min() == -1.0);
  CHECK(a.max() == 5.0);
  transmission::Accumulator one;
  one.Add(-0.25);
  CHECK(one.min() == -0.25);
  CHECK(one.max() == -0.25);
  CHECK(one.mean() == -0.25);
}

TEST_CASE("run ranges of the paper's stage in carrier angle and mesh cycles",
          "[unit][transmission]") {
  const geometry::Stage stage(test::PaperScene().stage);
  REQUIRE(stage.sun().teeth() == 16);
  REQUIRE(stage.planet(0).teeth() == 24);
  REQUIRE(stage.ring().teeth() == 65);
  const double pi = std::numbers::pi;
  CHECK(transmission::CarrierSpan(stage, RunRange::kMeshCycle) ==
        Approx(2 * pi / 65).epsilon(1e-15));
  CHECK(transmission::CarrierSpan(stage, RunRange::kPlanetRevolution) ==
        Approx(2 * pi * 24 / 65).epsilon(1e-15));
  CHECK(transmission::CarrierSpan(stage, RunRange::kCarrierRevolution) == 2 * pi);
  CHECK(transmission::MeshCycles(stage, RunRange::kMeshCycle) == 1.0);
  CHECK(transmission::MeshCycles(stage, RunRange::kPlanetRevolution) == 24.0);
  CHECK(transmission::MeshCycles(stage, RunRange::kCarrierRevolution) == 65.0);
  CHECK(transmission::MeshCycles(stage, RunRange::kSunRevolution) == 16.0);
  CHECK(transmission::CarrierSpan(stage, RunRange::kSunRevolution) == 2 * pi * 16 / 65);
  CHECK(transmission::RunRangeFromName("cycle") == RunRange::kMeshCycle);
  CHECK(transmission::RunRangeFromName("planet") == RunRange::kPlanetRevolution);
  CHECK(transmission::RunRangeFromName("revolution") == RunRange::kCarrierRevolution);
  CHECK(transmission::RunRangeFromName("sun") == RunRange::kSunRevolution);
  CHECK_THROWS_AS(transmission::RunRangeFromName("week"), std::invalid_argument);
  CHECK(std::string(transmission::SunSupportName(transmission::SunSupport::kFixed)) == "fixed");
  CHECK(std::string(transmission::SunSupportName(transmission::SunSupport::kFloating)) ==
        "floating");
  CHECK(std::string(transmission::SunSupportName(transmission::SunSupport::kElastic)) == "elastic");
}

TEST_CASE("a sweep's summary over its converged positions, hand-counted", "[unit][transmission]") {
  auto position = [](std::vector<double> lsr, double te, double x, double y, bool converged) {
    transmission::PositionResult r;
    r.converged = converged;
    r.load_sharing = std::move(lsr);
    r.transmission_error = te;
    r.sun_displacement = geometry::Vec2(x, y);
    return r;
  };
  const auto failed = position({9, 9, 9}, 1.0, 1.0, 1.0, false);
  const auto s =
      transmission::SummariseSweep({position({0.3, 0.3, 0.4}, 1e-6, 3e-6, 4e-6, true), failed,
                                    position({0.35, 0.35, 0.3}, -2e-6, 0.0, 1e-6, true)},
                                   3);
  CHECK(s.positions == 3);
  CHECK(s.converged == 2);
  CHECK(s.lsr_mean[0] == Approx(0.325).epsilon(1e-15));
  CHECK(s.lsr_mean[2] == Approx(0.35).epsilon(1e-15));
  CHECK(s.lsr_min[2] == 0.3);
  CHECK(s.lsr_max[2] == 0.4);
  CHECK(s.k_gamma == Approx(1.2).epsilon(1e-15));        // 3 · 0.4
  CHECK(s.k_gamma_mean == Approx(1.05).epsilon(1e-15));  // 3 · 0.35 (planet 3's mean)
  CHECK(s.transmission_error_min == -2e-6);
  CHECK(s.transmission_error_max == 1e-6);
  CHECK(s.sun_displacement_max == Approx(5e-6).epsilon(1e-15));  // |(3, 4)| µm
  // No converged position: the accumulator's rule, NaN everywhere.
  const auto none = transmission::SummariseSweep({failed}, 3);
  CHECK(none.converged == 0);
  CHECK(std::isnan(none.k_gamma));
  CHECK(std::isnan(none.k_gamma_mean));
  CHECK(std::isnan(none.lsr_mean[1]));
  CHECK(std::isnan(none.transmission_error_min));
  CHECK(std::isnan(none.sun_displacement_max));
}

TEST_CASE("load-sharing ratios: mesh moments over the input torque they balance",
          "[unit][transmission]") {
  // T_in = −600 N·m on the sun; the meshes' moments 150, 200 and 250 N·m balance it: LSR = 1/4,
  // 1/3, 5/12 (sum 1).
  const std::vector<double> lsr = transmission::LoadSharingRatios({150.0, 200.0, 250.0}, -600.0);
  REQUIRE(lsr.size() == 3);
  CHECK(lsr[0] == 0.25);
  CHECK(lsr[1] == Approx(1.0 / 3.0).epsilon(1e-15));
  CHECK(lsr[2] == Approx(5.0 / 12.0).epsilon(1e-15));
  CHECK(transmission::LoadSharingRatios({-100.0}, 100.0)[0] == 1.0);
}
