// The numbers a user gives a quasi-static run, a mesh-stiffness run or a contact listing besides
// the scene (the program's options, the Python drivers' keyword arguments), each with its range
// (geometry/argument_range.hpp): the one statement of the rule that the program, the bindings and
// the scene reader (dynamics.sun_speed_rpm) check. A value outside is bad input:
//   start_deg = nan: must be finite and in [-3600, 3600] [deg] (ten revolutions either way)
// The dynamic runs' are in dynamics/run_arguments.hpp.
#pragma once

#include <string>
#include <vector>

#include "epicycle/geometry/argument_range.hpp"

namespace epicycle::transmission {

using geometry::ArgumentRange;
using geometry::CheckArgument;

/// A carrier angle (or a pair's gear-1 angle) [deg].
inline constexpr ArgumentRange kCarrierAngleDeg{-3600, 3600,    false,
                                                false, "[deg]", "ten revolutions either way"};
/// A sun speed [rpm]: a dynamic run's, a speed sweep's, the scene's dynamics.sun_speed_rpm.
inline constexpr ArgumentRange kSunSpeedRpm{
    1,
    1e5,
    false,
    false,
    "[rpm]",
    "slower runs are quasi-static: epicycle quasistatic; faster ones are past any "
    "gear's pitch-line speed"};
/// Worker threads where 0 means one per core.
inline constexpr ArgumentRange kThreadsOrZero{0, 4096, false, true, "", "0: one per core"};
/// Worker threads.
inline constexpr ArgumentRange kThreads{1, 4096, false, true, "", ""};
/// Positions of a quasi-static sweep, also the count of a list of carrier angles (every position
/// is kept for the summary: 1e6 is about 1 GB of results).
inline constexpr ArgumentRange kSweepPositions{1, 1e6, false, true, "", ""};
/// Positions per mesh cycle of a mesh-stiffness run (2: the cycle's two ends at least).
inline constexpr ArgumentRange kStiffnessPositions{2, 1e5, false, true, "", ""};
/// The mesh cycle a mesh-stiffness run sweeps (0: the first).
inline constexpr ArgumentRange kStiffnessCycle{0, 1e6, false, false, "", ""};
/// A contact solve's tolerance on its nondimensional residual (the contact commands' --tol,
/// Python's solve_contact; a run's contact solves: dynamics/run_arguments.hpp).
inline constexpr ArgumentRange kContactTolerance{0,     1,  true,
                                                 false, "", "a nondimensional residual"};
/// The iterations and the time one contact solve may take (Python's solve_contact).
inline constexpr ArgumentRange kContactIterations{1, 1e6, false, true, "", ""};
inline constexpr ArgumentRange kContactTimeLimitS{0, 86400, true, false, "[s]", "up to a day"};
/// Solves per (back end, problem) of a comparison of back ends (`contact compare --repeat`,
/// Python's compare_backends(repeats=)).
inline constexpr ArgumentRange kComparisonRepeats{1, 1000, false, true, "", ""};
/// New cases a tolerance study (of quasi-static sweeps, studies/) computes before it summarises.
inline constexpr ArgumentRange kStudyCases{0, 1e9, false, true, "", ""};

/// Carrier angles given as a list [deg]: their count by kSweepPositions ("NAME: 0 angles: must be
/// a whole number in [1, 1000000]"), each by kCarrierAngleDeg ("NAME = nan: ..."); the angles in
/// radians. @throws std::invalid_argument naming `name`.
std::vector<double> CheckedCarrierAngles(const std::string& name, const std::vector<double>& deg);

}  // namespace epicycle::transmission
