#include "epicycle/dynamics/vibration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "number_format.hpp"

namespace epicycle::dynamics {

using internal::Num;

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
                                   const std::string& resolution_option,
                                   const std::string& skip_option) {
  if (!(skip_cycles >= 0) || !std::isfinite(skip_cycles))
    throw std::invalid_argument(skip_option + " = " + Num(skip_cycles) +
                                ": must be finite and >= 0 [mesh cycles]");
  if (!(resolution >= 0) || !std::isfinite(resolution))
    throw std::invalid_argument(resolution_option + " = " + Num(resolution) +
                                ": must be finite and >= 0 [Hz] (0: one carrier revolution)");
  if (!(span.outputs > 0 && span.duration > 0 && span.cycle_time > 0))
    throw std::invalid_argument("spectrum: the run has no output steps");
  SpectrumOptions o;
  o.sample_interval = span.duration / span.outputs;
  o.start_time = skip_cycles * span.cycle_time;
  // Samples from the first output at or after start_time to the end.
  const long first = std::max(1L, std::lround(std::ceil(o.start_time / o.sample_interval - 1e-9)));
  const long rest = std::max(0L, span.outputs - first + 1);
  long n = 0;
  if (resolution > 0) {
    n = std::lround(1.0 / (resolution * o.sample_interval));
  } else {
    const long revolution = std::lround(1.0 / (frequencies.carrier * o.sample_interval));
    const long cycle = std::lround(span.cycle_time / o.sample_interval);
    n = revolution <= rest ? revolution : cycle > 0 ? rest / cycle * cycle : rest;
  }
  if (n < 8 || n > rest)
    throw std::invalid_argument(resolution_option + " = " + Num(resolution) + " Hz: a segment of " +
                                std::to_string(n) + " samples (" +
                                Num(static_cast<double>(n) * o.sample_interval) +
                                " s) needs at least 8 and at most the " + std::to_string(rest) +
                                " output steps after " + skip_option + " = " + Num(skip_cycles) +
                                " (" + Num(static_cast<double>(rest) * o.sample_interval) +
                                " s): lengthen the run or ask for a coarser resolution");
  o.segment = static_cast<int>(n);
  o.hop = std::max(1, o.segment / 2);
  o.start_time = static_cast<double>(first) * o.sample_interval;
  return o;
}

}  // namespace epicycle::dynamics
