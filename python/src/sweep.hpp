// A quasi-static sweep's request (its arguments checked, defaults resolved) and one position's
// values in the results' units: shared by epicycle.quasistatic (every position at once) and
// epicycle.quasistatic_positions (one position at a time, stream.cpp).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "scene.hpp"

namespace epicycle::python {

/// A quasi-static run's request as the library defaults it: the one statement of the defaults the
/// program's options start from, and of the keyword defaults of quasistatic and
/// quasistatic_positions.
inline const transmission::QuasiStaticRequest& QuasiStaticDefaults() {
  static const transmission::QuasiStaticRequest defaults;
  return defaults;
}

struct SweepRequest {
  std::shared_ptr<Scene> scene;  ///< the scene run (with [model] stresses on for stresses)
  transmission::QuasiStaticOptions options;
  transmission::RunRange range = transmission::RunRange::kMeshCycle;
  int positions = 0;  ///< over the range [-] (0: transmission::DefaultPositions)
  double start_deg = 0;
  std::optional<std::vector<double>> angles;  ///< given carrier angles instead [rad]
  bool local_terms = true;
  /// The sweep's carrier angles [rad] on `stage`.
  std::vector<double> Angles(const geometry::Stage& stage) const;
};

/// Every argument by the program's rule for its option (run_arguments.hpp), before any work.
/// @throws std::invalid_argument (ValueError) naming the argument, its value and the rule.
SweepRequest MakeSweepRequest(const std::shared_ptr<Scene>& s, const std::string& range,
                              int positions, double start_deg,
                              std::optional<std::vector<double>> angles_deg, int threads,
                              bool warm_start, const std::string& backend, bool local_terms,
                              const std::string& friction, bool stresses, bool rating);

/// One position's values (NaN where not converged; the friction ones only with friction on).
struct PositionRow {
  double carrier_deg = 0;                  ///< [deg]
  bool converged = false, warm_started = false;
  std::vector<double> lsr, factor;         ///< LSR_i, L_i [-] per planet
  double k_gamma = 0;                      ///< [-]
  double te_rad = 0, sun_x_m = 0, sun_y_m = 0;  ///< [rad], [m] (the results give µrad, µm)
  int geometric_iterations = 0, contact_iterations = 0, active_contacts = 0, contacts = 0;
  double residual = 0, solve_ms = 0;       ///< [-], [ms]
  std::string status, message;
  double friction_power_W = 0, input_power_W = 0, output_power_W = 0, efficiency = 0,
         force_change = 0;
};
PositionRow RowOf(const transmission::PositionResult& r, int planets, bool with_friction);

}  // namespace epicycle::python
