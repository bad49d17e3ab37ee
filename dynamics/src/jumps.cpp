// The jumps of a stage between two coexisting periodic orbits (jumps.hpp; docs/periodic.md §3).
#include "epicycle/dynamics/jumps.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "epicycle/io/number_format.hpp"

namespace epicycle::dynamics {

namespace {

StageBranchRecord Branch(const JumpRequest& request, double from, double to) {
  BranchRequest b;
  b.run = request.run;
  b.start = from;
  b.end = to;
  b.steps = request.branch_steps;
  b.max_points = request.branch_points;
  BranchSink sink;
  StageBranchRecord r = RunBranch(b, sink).branch;
  if (r.bifurcations.empty() || r.bifurcations.front().kind != BifurcationKind::kFold)
    throw std::runtime_error("jumps: the branch from " + io::Num(from) + " to " + io::Num(to) +
                             " rpm found no fold first: " + r.message);
  return r;
}

SpeedSweepRecord Sweep(const JumpRequest& request, double step, CarryState carry) {
  SpeedSweepRequest s;
  s.run = request.run;
  const double range = request.sweep_to_rpm - request.sweep_from_rpm;
  s.sun_speeds_rpm = SpeedGrid(request.sweep_from_rpm, request.sweep_to_rpm,
                               static_cast<int>(std::lround(range / step)) + 1);
  s.window_cycles = request.window_cycles;
  s.threads = 1;
  s.carry = carry;
  SpeedSweepSink sink;
  SpeedSweepRecord r = RunSpeedSweep(s, sink);
  if (r.failed() > 0)
    throw std::runtime_error("jumps: " + std::to_string(r.failed()) + " speeds of the " +
                             CarryStateName(carry) + "-sweep in steps of " + io::Num(step) +
                             " rpm failed");
  return r;
}

double JumpSpeed(const SpeedSweepRecord& r, CarryState carry, double threshold, double step) {
  const int j = JumpIndex(r.speeds, carry, threshold);
  if (j < 0)
    throw std::runtime_error("jumps: the " + std::string(CarryStateName(carry)) +
                             "-sweep in steps of " + io::Num(step) + " rpm did not jump");
  return r.speeds[static_cast<std::size_t>(j)].sun_speed_rpm;
}

}  // namespace

JumpStudy RunJumps(const JumpRequest& request) {
  if (!(request.above_rpm > request.below_rpm))
    throw std::invalid_argument("jumps: above_rpm = " + io::Num(request.above_rpm) +
                                ": must exceed below_rpm = " + io::Num(request.below_rpm));
  JumpStudy s;
  s.from_below = Branch(request, request.below_rpm, request.above_rpm);
  s.from_above = Branch(request, request.above_rpm, request.below_rpm);
  s.upper_fold_rpm = s.from_below.bifurcations.front().parameter;
  s.lower_fold_rpm = s.from_above.bifurcations.front().parameter;
  s.te_threshold = SeparatingTeAmplitude(s.from_below, s.from_above);
  for (double step : request.steps_rpm) {
    JumpSweeps j;
    j.step_rpm = step;
    j.up = Sweep(request, step, CarryState::kUp);
    j.down = Sweep(request, step, CarryState::kDown);
    j.up_jump_rpm = JumpSpeed(j.up, CarryState::kUp, s.te_threshold, step);
    j.down_jump_rpm = JumpSpeed(j.down, CarryState::kDown, s.te_threshold, step);
    const int ju = JumpIndex(j.up.speeds, CarryState::kUp, s.te_threshold);
    j.dwell_s = j.up.plan.skip_time +
                request.window_cycles / j.up.speeds[static_cast<std::size_t>(ju)].mesh_frequency;
    s.sweeps.push_back(std::move(j));
  }
  return s;
}

}  // namespace epicycle::dynamics
