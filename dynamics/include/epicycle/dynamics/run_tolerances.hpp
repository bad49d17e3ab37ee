// The integrator's tolerances and contact back end of a run, as the dynamic, speed-sweep and
// periodic-branch records carry them: one struct, visited once under the same keys by each
// record (docs/records.md).
#pragma once

#include <string>

#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/transmission/record.hpp"

namespace epicycle::dynamics {

struct RunTolerances {
  double rtol = 0;         ///< the integrator's relative tolerance [-]
  double atol_length = 0;  ///< absolute tolerance of the translations [m]
  double atol_angle = 0;   ///< absolute tolerance of the rotations [rad]
  /// The rates' absolute tolerance = the positions' times this [rad/s] (0 in a speed sweep's
  /// record: each speed's highest natural frequency).
  double rate_scale = 0;
  double contact_tolerance = 0;  ///< of every contact solve, on its nondimensional residual [-]
  std::string backend;           ///< the contact back end's name
};

/// The tolerances of `options`, with the back end named `backend`.
RunTolerances TolerancesOf(const SimulationOptions& options, const std::string& backend);

/// rtol, atol_length_m, atol_angle_rad, rate_tolerance_scale_rad_per_s, contact_tolerance,
/// backend.
void VisitTolerances(const RunTolerances& tolerances, transmission::RecordVisitor& visit);

}  // namespace epicycle::dynamics
