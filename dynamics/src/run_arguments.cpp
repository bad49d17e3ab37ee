// A speed sweep's and a branch's ranges given as text (run_arguments.hpp): the fields read whole,
// each checked by its rule and named by its part of the text.
#include "epicycle/dynamics/run_arguments.hpp"

#include <cmath>
#include <stdexcept>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/io/number_format.hpp"
#include "epicycle/io/spec_fields.hpp"

namespace epicycle::dynamics {

std::vector<double> ParseSpeedSweep(const std::string& option, const std::string& spec) {
  const std::string given = option + " = " + spec + ": ";
  const std::string rule =
      "must be FROM:TO:N, sun speeds in rpm with N speeds, ends included (e.g. 500:12000:24)";
  const std::vector<std::string> fields = io::Fields(spec, ':');
  if (fields.size() != 3) throw std::invalid_argument(given + rule);
  double from = 0, to = 0;
  long n = 0;
  try {
    from = io::Real(fields[0]);
    to = io::Real(fields[1]);
    n = io::Whole(fields[2]);
  } catch (const std::logic_error&) {
    throw std::invalid_argument(given + rule);
  }
  const ArgumentRange& speed = transmission::kSunSpeedRpm;
  if (!speed.Holds(from))
    throw std::invalid_argument(given + "FROM = " + fields[0] + ": " + speed.Describe());
  if (!speed.Holds(to))
    throw std::invalid_argument(given + "TO = " + fields[1] + ": " + speed.Describe());
  if (!kSweepSpeeds.Holds(static_cast<double>(n)) && n > 0)
    throw std::invalid_argument(given + "N = " + std::to_string(n) + ": " +
                                kSweepSpeeds.Describe());
  try {
    return SpeedGrid(from, to, static_cast<int>(n));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(given + e.what());
  }
}

void ParseBranchRange(const std::string& option, const std::string& spec, bool sun_speed,
                      BranchRequest* request) {
  const std::string given = option + " = " + spec + ": ";
  double from = 0, to = 0;
  int steps = 0;
  if (sun_speed) {
    const std::vector<double> grid = ParseSpeedSweep(option, spec);
    request->parameter = StagePeriodicSystem::kSunSpeed;
    from = grid.front();
    to = grid.back();
    steps = static_cast<int>(grid.size());
  } else {
    const std::string rule =
        "must be NAME:FROM:TO:N, a number of the scene by its key path, its range and at least N "
        "steps (e.g. sun_torque_Nm:-600:-100:20, errors.pin.planet1.tangential_um:0:4:10)";
    const std::vector<std::string> parts = io::Fields(spec, ':');
    if (parts.size() != 4) throw std::invalid_argument(given + rule);
    request->parameter = parts[0];
    try {
      from = io::Real(parts[1]);
      to = io::Real(parts[2]);
      const long n = io::Whole(parts[3]);
      if (n != static_cast<int>(n)) throw std::out_of_range(parts[3]);  // as std::stoi
      steps = static_cast<int>(n);
    } catch (const std::logic_error&) {
      throw std::invalid_argument(given + rule);
    }
  }
  if (!std::isfinite(from) || !std::isfinite(to) || from == to)
    throw std::invalid_argument(given + "FROM = " + io::Num(from, 9) + ", TO = " + io::Num(to, 9) +
                                ": a continuation's range must have non-zero width");
  if (steps < 1)
    throw std::invalid_argument(given + "N = " + std::to_string(steps) +
                                ": must be >= 1 (the largest step is 1/N of the range)");
  request->start = from;
  request->end = to;
  request->steps = steps;
  request->names.parameter = option + " NAME";
  request->names.steps = option + " N";
}

}  // namespace epicycle::dynamics
