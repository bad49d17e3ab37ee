// Contact-pressure read-out (docs/model.md §9, docs/stresses.md): over many states (a sweep's
// positions, a run's output steps) the largest Hertz pressure p_H on each flank side of each gear,
// the gear's roll angle there and the contact's half-width, from each contact's line load and
// relative curvature (solvers::HertzPressure: on the line of action and at tip rounds alike).
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::transmission {

/// The largest p_H on one flank side of one gear, on the line of action (involute against
/// involute) or off it (a tip round against a flank: the corner contact that tip relief avoids).
struct FlankPressure {
  int body = 0;            ///< kSunBody, kRingBody, PlanetBody(i)
  bool drive = true;       ///< the flanks that carry the torque (false: the coast flanks)
  double pressure = 0;     ///< largest p_H [Pa]
  double half_width = 0;   ///< Hertz half-width a there [m]
  /// The gear's involute roll angle at that contact [rad]; NaN on the gear's own tip round.
  double roll = 0;
  int tooth = 0;           ///< the gear's tooth (body frame)
  std::string mesh;        ///< "sun-planet2", "planet1-ring"
  bool tip = false;        ///< a tip-round contact (off the line of action), of either gear
  double x = 0;            ///< the state's x: carrier angle [rad] or time [s]
  /// F / ValidityLimitForce at that contact [-]: above 1 the half-width exceeds the joining depth
  /// (outside the local term's validity, docs/model.md §4).
  double validity_ratio = 0;
};

/// Accumulates states; only flanks that carried load appear in the result.
class ContactPressureTracker {
 public:
  /// `contacts` and `local` of one state's contact problem, `force` its normal forces [N]. A
  /// problem without local terms (`local` empty) adds nothing.
  /// @throws std::invalid_argument if the sizes differ.
  void Add(const std::vector<StageContact>& contacts,
           const std::vector<solvers::LocalTermParameters>& local, const Eigen::VectorXd& force,
           double x);
  /// In body order, drive before coast, on the line of action before tip contacts.
  std::vector<FlankPressure> Result() const;

 private:
  // (body, 0 drive / 1 coast, 0 involute / 1 tip contact)
  std::map<std::tuple<int, int, int>, FlankPressure> flanks_;
};

}  // namespace epicycle::transmission
