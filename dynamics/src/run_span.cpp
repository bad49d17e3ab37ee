#include "epicycle/dynamics/run_span.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/io/units.hpp"

namespace epicycle::dynamics {

std::vector<double> RunSpan::OutputTimes() const {
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(std::max(outputs, 0)));
  for (int i = 1; i <= outputs; ++i) times.push_back(duration * i / outputs);
  return times;
}

RunSpan MakeRunSpan(const geometry::Stage& stage, double carrier_speed,
                    transmission::RunRange range, double time, int outputs_per_cycle) {
  if (!(carrier_speed != 0) || !std::isfinite(carrier_speed))
    throw std::invalid_argument("run span: carrier speed = " + std::to_string(carrier_speed) +
                                " rad/s: must be finite and non-zero");
  if (!(time >= 0) || !std::isfinite(time))
    throw std::invalid_argument("run span: time = " + std::to_string(time) +
                                " s: must be finite and >= 0 (0: the range)");
  if (outputs_per_cycle < 1)
    throw std::invalid_argument(
        "run span: outputs per cycle = " + std::to_string(outputs_per_cycle) + ": must be >= 1");
  const double wc = std::abs(carrier_speed);
  RunSpan s;
  s.cycle_time = stage.mesh_cycle() / wc;
  s.duration = time > 0 ? time
               : range == transmission::RunRange::kMeshCycle
                   ? s.cycle_time
                   : transmission::CarrierSpan(stage, range) / wc;
  s.mesh_frequency = stage.ring().teeth() * wc / (2.0 * std::numbers::pi);
  // Whole output intervals within round-off count as whole (a time of exactly N mesh cycles
  // computed in decimal gives N·outputs_per_cycle, not one more: the spectra need Δt exact).
  const double outputs = std::ceil(s.duration / s.cycle_time * outputs_per_cycle * (1 - 1e-12));
  if (!(outputs <= kMaxRunOutputs)) {
    char text[300];
    std::snprintf(text, sizeof text,
                  "run span: %.4g s of %.4g s mesh cycles at %d outputs per cycle is %.4g output "
                  "steps: more than the %d a run may have (every step is kept for the summary "
                  "and written); shorten the run or give fewer outputs per cycle",
                  s.duration, s.cycle_time, outputs_per_cycle, outputs, kMaxRunOutputs);
    throw std::invalid_argument(text);
  }
  s.outputs = std::max(1, static_cast<int>(outputs));
  return s;
}

double ExpectedSteps(double duration, double sun_rpm) {
  return duration * kStepsPerSecondAtOneRpm * std::sqrt(std::abs(sun_rpm));
}

std::string RunCostWarning(const RunSpan& span, double sun_rpm, const std::string& duration_source,
                           const std::string& speed_source) {
  const double steps = ExpectedSteps(span.duration, sun_rpm);
  if (!(steps > kStepsWarning)) return "";
  char text[600];
  std::snprintf(text, sizeof text,
                "%s (%.4g s of motion) at %s (%.4g rpm): about %.2g integrator steps expected "
                "(%.0f steps per simulated second x sqrt(speed/rpm), the rate measured on the "
                "paper's stage; friction can take several times more), more than %.0e: at "
                "20-130 us a step %.0f to %.0f minutes; shorten the run, or use quasistatic at "
                "speeds this low",
                duration_source.c_str(), span.duration, speed_source.c_str(), std::abs(sun_rpm),
                steps, kStepsPerSecondAtOneRpm, kStepsWarning, steps * 20e-6 / 60,
                steps * 130e-6 / 60);
  return text;
}

double MeshHzPerSunRpm(const geometry::Stage& stage) {
  return io::RpmToRevolutionsPerSecond(stage.ring().teeth() / stage.sun_ratio());
}

std::vector<double> HarmonicSunSpeeds(double frequency, double hz_per_rpm, int harmonics) {
  std::vector<double> rpm;
  for (int h = 1; h <= harmonics && frequency > 0; ++h) rpm.push_back(frequency / (h * hz_per_rpm));
  return rpm;
}

int DefaultOutputsPerCycle(double highest_mode_hz, double mesh_hz) {
  if (!(mesh_hz > 0) || !std::isfinite(mesh_hz))
    throw std::invalid_argument("DefaultOutputsPerCycle: mesh frequency = " +
                                std::to_string(mesh_hz) + " Hz: must be positive and finite");
  const double wanted = std::ceil(kOutputsPerModePeriod * std::max(0.0, highest_mode_hz) / mesh_hz);
  const double most = kOutputsPerModePeriod * kMaxResolvedHarmonic;
  return static_cast<int>(std::min(std::max(std::isfinite(wanted) ? wanted : most, 20.0), most));
}

int DefaultOutputsPerCycle(const DynamicModel& model, double highest_mode_hz) {
  const double rpm = io::RadPerSecondToRpm(std::abs(model.sun_speed()));
  return DefaultOutputsPerCycle(highest_mode_hz,
                                MeshHzPerSunRpm(model.stage_model().stage()) * rpm);
}

double HighestModeFrequency(const DynamicModel& model) {
  Eigen::MatrixXd m, k;
  model.Linearise(0.0, &m, &k);
  double top = 0;
  for (const Mode& mode : SolveModes(m, k, model.ModeLayout())) top = std::max(top, mode.frequency);
  return top;
}

}  // namespace epicycle::dynamics
