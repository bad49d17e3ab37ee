// The duration and outputs of a dynamic run (dynamics/run_span.hpp) on the paper's 16/24/65
// stage against hand values: at ω_c = 2π·100/65 rad/s one mesh cycle (2π/65 of carrier) lasts
// 10 ms and the mesh frequency is 100 Hz; the sun speeds where mesh harmonics meet a frequency;
// a run's summary (the one accumulator) on made-up steps and on none.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using transmission::RunRange;

TEST_CASE("run span: duration, mesh frequency and output times", "[unit][dynamics]") {
  const geometry::Stage stage(test::PaperScene().stage);
  const double wc = 2.0 * std::numbers::pi * 100.0 / 65.0;  // 100 mesh cycles per second
  const auto cycle = dynamics::MakeRunSpan(stage, wc, RunRange::kMeshCycle, 0.0, 20);
  CHECK(cycle.cycle_time == Approx(0.01).epsilon(1e-14));
  CHECK(cycle.duration == Approx(0.01).epsilon(1e-14));
  CHECK(cycle.mesh_frequency == Approx(100.0).epsilon(1e-14));
  CHECK(cycle.outputs == 20);
  const std::vector<double> t = cycle.OutputTimes();
  REQUIRE(t.size() == 20);
  CHECK(t.front() == Approx(0.0005).epsilon(1e-14));
  CHECK(t.back() == cycle.duration);
  // One planet revolution relative to the carrier: 24 mesh cycles; the sign of ω_c is ignored.
  const auto planet = dynamics::MakeRunSpan(stage, -wc, RunRange::kPlanetRevolution, 0.0, 20);
  CHECK(planet.duration == Approx(0.24).epsilon(1e-14));
  CHECK(planet.outputs == 480);
  CHECK(dynamics::MakeRunSpan(stage, wc, RunRange::kCarrierRevolution, 0.0, 1).duration ==
        Approx(0.65).epsilon(1e-14));
  // A given time replaces the range: 0.013 s = 1.3 cycles, ⌈1.3 · 4⌉ = ⌈5.2⌉ = 6 outputs.
  const auto timed = dynamics::MakeRunSpan(stage, wc, RunRange::kCarrierRevolution, 0.013, 4);
  CHECK(timed.duration == 0.013);
  CHECK(timed.outputs == 6);
  CHECK_THROWS_AS(dynamics::MakeRunSpan(stage, 0.0, RunRange::kMeshCycle, 0.0, 20),
                  std::invalid_argument);
  CHECK_THROWS_AS(dynamics::MakeRunSpan(stage, wc, RunRange::kMeshCycle, -1.0, 20),
                  std::invalid_argument);
  CHECK_THROWS_AS(dynamics::MakeRunSpan(stage, wc, RunRange::kMeshCycle, 0.0, 0),
                  std::invalid_argument);
  // 100 cycles a second at 20 outputs per cycle: 400 s are 8e5 steps, allowed; 600 s are 1.2e6,
  // more than the 1e6 a run may have: refused, saying how many steps it would be.
  CHECK(dynamics::MakeRunSpan(stage, wc, RunRange::kMeshCycle, 400.0, 20).outputs >= 800000);
  CHECK_THROWS_WITH(dynamics::MakeRunSpan(stage, wc, RunRange::kMeshCycle, 600.0, 20),
                    Catch::Contains("is 1.2e+06 output steps: more than the 1000000"));
}

TEST_CASE("mesh frequency per sun rpm and the harmonics' sun speeds", "[unit][dynamics]") {
  const geometry::Stage stage(test::PaperScene().stage);
  // f_m/n_s = z_r z_s/(60 (z_s + z_r)) = 65·16/(60·81) Hz per rpm.
  const double per_rpm = 65.0 * 16.0 / (60.0 * 81.0);
  CHECK(dynamics::MeshHzPerSunRpm(stage) == Approx(per_rpm).epsilon(1e-14));
  const std::vector<double> rpm = dynamics::HarmonicSunSpeeds(600.0, 0.5, 3);
  REQUIRE(rpm.size() == 3);
  CHECK(rpm[0] == 1200.0);
  CHECK(rpm[1] == 600.0);
  CHECK(rpm[2] == 400.0);
  CHECK(dynamics::HarmonicSunSpeeds(0.0, 0.5, 3).empty());  // a rigid-body mode
}

TEST_CASE("a dynamic run's summary, hand-counted, and of no step", "[unit][dynamics]") {
  auto step = [](std::vector<double> lsr, double k_gamma, double te, double x, double y) {
    dynamics::DynamicSample s;
    s.load_sharing = std::move(lsr);
    s.k_gamma = k_gamma;
    s.transmission_error = te;
    s.sun_centre = Eigen::Vector2d(x, y);
    return s;
  };
  const auto s = dynamics::Summarise({step({0.3, 0.3, 0.4}, 1.2, 2e-6, 3e-6, 4e-6),
                                      step({0.5, 0.25, 0.25}, 1.5, -1e-6, 0.0, 1e-6)});
  CHECK(s.samples == 2);
  CHECK(s.lsr_mean[0] == Approx(0.4).epsilon(1e-15));
  CHECK(s.lsr_min[2] == 0.25);
  CHECK(s.lsr_max[0] == 0.5);
  CHECK(s.k_gamma == 1.5);
  CHECK(s.te_peak_to_peak() == Approx(3e-6).epsilon(1e-15));
  CHECK(s.orbit_radius == Approx(5e-6).epsilon(1e-15));
  CHECK(s.orbit_mean_radius == Approx(3e-6).epsilon(1e-15));  // (5 + 1)/2 µm
  CHECK(s.max_pair_force == 0.0);                             // no contact force in these steps
  const auto none = dynamics::Summarise({});
  CHECK(none.samples == 0);
  CHECK(none.lsr_mean.empty());
  CHECK(std::isnan(none.k_gamma));
  CHECK(std::isnan(none.te_min));
  CHECK(std::isnan(none.orbit_mean_radius));
  CHECK(std::isnan(none.max_pair_force));
}

TEST_CASE("run span: a run expected to take more than 1e7 steps is warned about",
          "[unit][dynamics]") {
  // The rule of run_span.hpp: 1e4 sqrt(n_s/rpm) steps per simulated second. At 1 rpm that is
  // 1e4 steps a second: 1000 s is 1e7 steps (not past the limit), 1001 s is past it; at 1500 rpm
  // the paper's planet revolution (0.075 s) is 2.9e4 steps. The measured 60 s at 1 rpm (paper
  // stage, friction on) took 3.7e5 steps against the rule's 6e5: the same order.
  dynamics::RunSpan span;
  span.duration = 1000.0;
  CHECK(dynamics::ExpectedSteps(span.duration, 1.0) == Approx(1e7).epsilon(1e-14));
  CHECK(dynamics::RunCostWarning(span, 1.0, "--time = 1000 s", "--speed-rpm = 1").empty());
  span.duration = 3600.0;
  const std::string w = dynamics::RunCostWarning(span, -1.0, "--time = 3600 s", "--speed-rpm = 1");
  CHECK_THAT(w, Catch::Contains("--time = 3600 s (3600 s of motion) at --speed-rpm = 1 (1 rpm)"));
  CHECK_THAT(w, Catch::Contains("about 3.6e+07 integrator steps expected"));
  CHECK_THAT(w, Catch::Contains("more than 1e+07"));
  CHECK_THAT(w, Catch::Contains("12 to 78 minutes"));
  span.duration = 0.075;
  CHECK(dynamics::ExpectedSteps(span.duration, 1500.0) == Approx(0.075e4 * std::sqrt(1500.0)));
  CHECK(dynamics::RunCostWarning(span, 1500.0, "--range planet", "--speed-rpm = 1500").empty());
}
