// The arguments of a dynamic run, a speed sweep and a branch (dynamics/run_arguments.hpp): the
// speed grid and the branch's range read from text against hand values, the messages that name
// the option, its value, the part and the rule (the texts the program printed when app/ parsed
// them itself; its CLI tests hold the same), and the names a front end's messages use.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/run_arguments.hpp"

using namespace epicycle;

namespace {

// The message of the invalid_argument `f` throws ("" if none).
template <typename F>
std::string Message(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a speed sweep's FROM:TO:N: the grid and its refusals", "[unit][dynamics]") {
  // 24 speeds from 500 to 12000 rpm, ends included: steps of (12000 - 500)/23 = 500 rpm. Every
  // value on the way (11500 k, its 23rd, 500 + 500 k) is a whole number below 2^53, so exact.
  const std::vector<double> grid = dynamics::ParseSpeedSweep("--speed-sweep", "500:12000:24");
  REQUIRE(grid.size() == 24);
  for (std::size_t k = 0; k < grid.size(); ++k)
    CHECK(grid[k] == 500.0 + 500.0 * static_cast<double>(k));
  const std::string rule =
      "must be FROM:TO:N, sun speeds in rpm with N speeds, ends included (e.g. 500:12000:24)";
  for (const char* bad : {"1000:5000", "1000:5000:3:4", "1000:5000:3x", "a:5000:3", ""})
    CHECK(Message([&] { dynamics::ParseSpeedSweep("--speed-sweep", bad); }) ==
          "--speed-sweep = " + std::string(bad) + ": " + rule);
  CHECK(Message([] { dynamics::ParseSpeedSweep("--speed-sweep", "0.5:5000:3"); }) ==
        "--speed-sweep = 0.5:5000:3: FROM = 0.5: must be finite and in [1, 100000] [rpm] (slower "
        "runs are quasi-static: epicycle quasistatic; faster ones are past any gear's pitch-line "
        "speed)");
  CHECK(Message([] {
          dynamics::ParseSpeedSweep("--speed-sweep", "1000:inf:3");
        }).starts_with("--speed-sweep = 1000:inf:3: TO = inf: must be finite and in [1, 100000]"));
  CHECK(Message([] { dynamics::ParseSpeedSweep("--speed-sweep", "1000:5000:200000"); }) ==
        "--speed-sweep = 1000:5000:200000: N = 200000: must be a whole number in [1, 100000]");
  // A descending range is SpeedGrid's refusal, put after the option and its value.
  CHECK(Message([] {
          dynamics::ParseSpeedSweep("--speed-sweep", "5000:1000:3");
        }).starts_with("--speed-sweep = 5000:1000:3: last sun speed [rpm] = 1000"));
}

TEST_CASE("a branch's range: over the sun speed or a scene's number", "[unit][dynamics]") {
  dynamics::BranchRequest speed;
  dynamics::ParseBranchRange("--speed-sweep", "1000:5000:9", true, &speed);
  CHECK(speed.parameter == dynamics::StagePeriodicSystem::kSunSpeed);
  CHECK(speed.start == 1000.0);
  CHECK(speed.end == 5000.0);
  CHECK(speed.steps == 9);
  CHECK(speed.names.parameter == "--speed-sweep NAME");
  CHECK(speed.names.steps == "--speed-sweep N");

  dynamics::BranchRequest torque;
  dynamics::ParseBranchRange("--continue", "sun_torque_Nm:-600:-100:20", false, &torque);
  CHECK(torque.parameter == "sun_torque_Nm");
  CHECK(torque.start == -600.0);
  CHECK(torque.end == -100.0);
  CHECK(torque.steps == 20);

  const std::string rule =
      "must be NAME:FROM:TO:N, a number of the scene by its key path, its range and at least N "
      "steps (e.g. sun_torque_Nm:-600:-100:20, errors.pin.planet1.tangential_um:0:4:10)";
  dynamics::BranchRequest r;
  // Three fields, a fraction for N, and N past an int (std::stoi's range, 2^31 - 1).
  for (const char* bad : {"x:0:1", "x:0:1:2.5", "x:0:1:99999999999", "x:a:1:3"})
    CHECK(Message([&] { dynamics::ParseBranchRange("--continue", bad, false, &r); }) ==
          "--continue = " + std::string(bad) + ": " + rule);
  CHECK(Message([&] { dynamics::ParseBranchRange("--continue", "x:2:2:3", false, &r); }) ==
        "--continue = x:2:2:3: FROM = 2, TO = 2: a continuation's range must have non-zero width");
  CHECK(Message([&] { dynamics::ParseBranchRange("--continue", "x:0:1:0", false, &r); }) ==
        "--continue = x:0:1:0: N = 0: must be >= 1 (the largest step is 1/N of the range)");
}

TEST_CASE("a dynamic run's argument names: the program's options and Python's keywords",
          "[unit][dynamics]") {
  // The program's options as its help lists them, and the keywords of Python's dynamic().
  const dynamics::DynamicOptionNames program = dynamics::DynamicOptionNames::Program();
  CHECK(program.time == "--time");
  CHECK(program.speed == "--speed-rpm");
  CHECK(program.range == "--range");
  CHECK(program.rating == "--rating");
  CHECK(program.spectrum_resolution == "--spectrum-resolution");
  CHECK(program.spectrum_skip == "--spectrum-skip-cycles");
  CHECK(program.outputs_per_cycle == "--outputs-per-cycle");
  CHECK(program.start == "--start-deg");
  CHECK(program.rtol == "--rtol");
  CHECK(program.rate_scale == "--rate-scale");
  CHECK(program.contact_tolerance == "--contact-tol");
  CHECK(program.max_order == "--max-order");
  CHECK(program.max_steps == "--max-steps");
  CHECK(program.time_limit == "--time-limit");
  const dynamics::DynamicOptionNames python;
  CHECK(python.time == "time_s");
  CHECK(python.speed == "sun_speed_rpm");
  CHECK(python.contact_tolerance == "contact_tol");
  CHECK(python.time_limit == "time_limit_s");
  // A number checked under its keyword with its option's rule.
  CHECK(Message([] { dynamics::CheckArgument(dynamics::DynamicArguments::kRtol, 0.5); }) ==
        "rtol = 0.5: must be finite and in [1e-12, 0.1]");
}
