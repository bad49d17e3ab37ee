#include "epicycle/dynamics/vibration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "epicycle/io/number_format.hpp"

namespace epicycle::dynamics {

using io::Num;

namespace {

bool SunFloats(const DynamicModel& model) {
  return model.stage_model().setup().sun == transmission::SunSupport::kFloating;
}

}  // namespace

std::vector<VibrationChannel> VibrationChannels(const DynamicModel& model) {
  const SignalKind tor = SignalKind::kTorsional, hou = SignalKind::kHousing;
  std::vector<VibrationChannel> c = {{"te", "rad", tor},
                                     {"ring_force_x", "N", hou},
                                     {"ring_force_y", "N", hou},
                                     {"ring_torque", "N m", tor}};
  if (model.settings().ring_elastic) {
    c.push_back({"ring_acceleration_x", "m/s2", hou});
    c.push_back({"ring_acceleration_y", "m/s2", hou});
  }
  if (SunFloats(model)) {
    c.push_back({"sun_x", "m", hou});
    c.push_back({"sun_y", "m", hou});
  } else {
    c.push_back({"sun_force_x", "N", hou});
    c.push_back({"sun_force_y", "N", hou});
  }
  return c;
}

void VibrationValues(const DynamicModel& model, const DynamicSample& s, std::vector<double>* out) {
  const Evaluation& e = s.evaluation;
  std::vector<double>& v = *out;
  v.clear();
  v.push_back(s.transmission_error);
  const transmission::DynamicSettings& set = model.settings();
  const int kr = model.Find(MotionDof::kRing, MotionDof::kRotation);
  if (set.ring_elastic && kr >= 0) {
    // The springs and dampers carry the ring's deflection to the housing.
    for (int a = 1; a <= 2; ++a)
      v.push_back(set.ring_stiffness * s.d(kr + a) + set.ring_damping * s.v(kr + a));
    v.push_back(set.ring_torsional_stiffness * s.d(kr) + set.ring_torsional_damping * s.v(kr));
    v.push_back(e.acceleration(kr + 1));
    v.push_back(e.acceleration(kr + 2));
  } else {
    // A held ring passes its meshes' force and moment to the housing.
    v.push_back(e.ring_mesh_force.x());
    v.push_back(e.ring_mesh_force.y());
    v.push_back(e.ring_mesh_torque);
  }
  if (SunFloats(model)) {
    v.push_back(s.sun_centre.x());
    v.push_back(s.sun_centre.y());
  } else if (model.Find(MotionDof::kSun, MotionDof::kX) >= 0) {
    v.push_back(-e.sun_bearing_force.x());
    v.push_back(-e.sun_bearing_force.y());
  } else {
    v.push_back(e.sun_mesh_force.x());
    v.push_back(e.sun_mesh_force.y());
  }
}

SpectrumOptions RunSpectrumOptions(const RunSpan& span, const StageFrequencies& frequencies,
                                   double resolution, double skip_cycles,
                                   const SpectrumInputs& inputs) {
  const std::string& res_option = inputs.resolution_option;
  const std::string& skip_option = inputs.skip_option;
  if (!(skip_cycles >= 0) || !std::isfinite(skip_cycles))
    throw std::invalid_argument(skip_option + " = " + Num(skip_cycles) +
                                ": must be finite and >= 0 [mesh cycles]");
  if (!(resolution >= 0) || !std::isfinite(resolution))
    throw std::invalid_argument(res_option + " = " + Num(resolution) +
                                ": must be finite and >= 0 [Hz] (0: one carrier revolution)");
  if (!(span.outputs > 0 && span.duration > 0 && span.cycle_time > 0))
    throw std::invalid_argument("spectrum: the run has no output steps");
  SpectrumOptions o;
  o.sample_interval = span.duration / span.outputs;
  o.start_time = skip_cycles * span.cycle_time;
  const double dt = o.sample_interval;
  // Samples from the first output at or after start_time to the end (counted in doubles: a skip
  // far past the run's end is no count to convert).
  const double first_real = std::max(1.0, std::ceil(o.start_time / dt - 1e-9));
  const long rest = first_real > span.outputs ? 0L : span.outputs - std::lround(first_real) + 1;
  const std::string skipped =
      skip_cycles == 0 ? std::string("from the start")
      : inputs.skip_given
          ? "after " + skip_option + " = " + Num(skip_cycles) + " mesh cycles"
          : "after the first " + Num(skip_cycles) + " mesh cycles (the start transient; " +
                skip_option + " changes it)";
  const std::string run_rest = fmt::format(
      "{} runs {:.4g} s in {} output steps (dt {:.4g} s) and leaves {} of them ({:.4g} s) {}",
      inputs.run, span.duration, span.outputs, dt, rest, static_cast<double>(rest) * dt, skipped);
  if (rest < 8)
    throw std::invalid_argument("spectrum: " + run_rest +
                                "; a spectrum needs at least 8: lengthen the run" +
                                (skip_cycles > 0 ? " or skip fewer mesh cycles" : ""));
  long n = 0;
  if (resolution > 0) {
    // The segment's length in samples, as a double first: 1/(Δf Δt) of a tiny Δf is no count.
    const double samples = 1.0 / (resolution * dt);
    if (!(samples >= 7.5 && samples < static_cast<double>(rest) + 0.5))
      throw std::invalid_argument(fmt::format(
          "{} = {} Hz: must be in [{:.4g}, {:.4g}] Hz here (a segment 1/resolution long holds "
          "at least 8 output steps and at most the {} the run has after its skip: {})",
          res_option, Num(resolution), 1.0 / (static_cast<double>(rest) * dt), 1.0 / (8 * dt), rest,
          run_rest));
    n = std::lround(samples);
  } else {
    const long revolution = std::lround(std::min(1.0 / (frequencies.carrier * dt), 1e12));
    const long cycle = std::lround(span.cycle_time / dt);
    n = revolution <= rest ? revolution : cycle > 0 ? rest / cycle * cycle : rest;
    if (n < 8)
      throw std::invalid_argument(fmt::format(
          "spectrum: {}; a segment of whole mesh cycles ({} output steps each) does not fit: "
          "lengthen the run or give {} (a segment 1/resolution long, at least 8 steps)",
          run_rest, cycle, res_option));
  }
  o.segment = static_cast<int>(n);
  o.hop = std::max(1, o.segment / 2);
  o.start_time = first_real * dt;
  return o;
}

}  // namespace epicycle::dynamics
