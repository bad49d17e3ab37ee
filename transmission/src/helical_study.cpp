// The transmission error's ripple against the overlap ratio (helical_study.hpp).
#include "epicycle/transmission/helical_study.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/sweep_summary.hpp"

namespace epicycle::transmission {

geometry::StageSpec WithHelix(geometry::StageSpec transverse, double helix_angle,
                              geometry::Hand sun_hand) {
  const geometry::Hand other =
      sun_hand == geometry::Hand::kRight ? geometry::Hand::kLeft : geometry::Hand::kRight;
  transverse.sun.helix = {helix_angle, sun_hand};
  transverse.planet.helix = {helix_angle, other};
  transverse.ring.helix = {helix_angle, other};
  return transverse;
}

double StageOverlapRatio(const geometry::Stage& stage) {
  const geometry::GearSpec& s = stage.sun().spec();
  const double b = geometry::ContactFaceWidth(stage.sun(), stage.planet(0));
  return b * std::tan(s.helix.angle) / (std::numbers::pi * s.module);
}

double TransmissionErrorRipple(const StageModel& model, const StageLoads& loads, int positions) {
  if (positions < 2)
    throw std::invalid_argument("TransmissionErrorRipple: positions = " +
                                std::to_string(positions) + ": must be >= 2");
  const double cycle = 2 * std::numbers::pi / model.stage().ring().spec().teeth;
  std::vector<double> angles;
  for (int k = 0; k < positions; ++k) angles.push_back(cycle * k / positions);
  const std::vector<PositionResult> r = Sweep(model, loads, angles, QuasiStaticOptions{});
  const SweepSummary s = SummariseSweep(r, model.planets());
  if (s.converged == 0)
    throw std::invalid_argument("TransmissionErrorRipple: no position converged");
  return s.TransmissionErrorPeakToPeak();
}

}  // namespace epicycle::transmission
