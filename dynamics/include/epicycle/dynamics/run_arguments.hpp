// The numbers a user gives a dynamic run, a speed sweep or their spectra besides the scene (the
// program's options, the Python drivers' keyword arguments), each with its range
// (geometry/argument_range.hpp): the one statement of the rule that the program and the bindings
// check. The sun speed, the carrier angles and the threads are transmission/run_arguments.hpp's.
#pragma once

#include "epicycle/transmission/run_arguments.hpp"

namespace epicycle::dynamics {

using geometry::ArgumentRange;
using geometry::CheckArgument;

/// A run's simulated time instead of its range [s]: from a microsecond (the shortest output step
/// of a run at 1e5 rpm and 500 outputs per mesh cycle is of that order; a shorter run has no step
/// the integrator resolves) to an hour of motion.
inline constexpr ArgumentRange kRunTimeS{1e-6,  3600,  false,
                                         false, "[s]", "a microsecond to an hour of motion"};
/// The integrator's relative tolerance [-] (below 1e-12 round-off of the contact solves governs).
inline constexpr ArgumentRange kRelativeTolerance{1e-12, 0.1, false, false, "", ""};
/// The rates' absolute tolerance over the positions' [1/s] (SimulationOptions::rate_scale).
inline constexpr ArgumentRange kRateScale{
    0, 1e12, false, false, "[1/s]", "0: the stage's highest linearised natural frequency"};
/// Every contact solve's tolerance on its nondimensional residual in a run [-].
inline constexpr ArgumentRange kRunContactTolerance{1e-14, 1e-2, false,
                                                    false, "",   "a nondimensional residual"};
/// Output steps per mesh cycle of a run or a speed sweep's window.
inline constexpr ArgumentRange kOutputsPerCycle{1, 1e5, false, true, "", ""};
/// Mesh cycles a speed sweep measures at each speed.
inline constexpr ArgumentRange kWindowCycles{0, 1e5, true, false, "", ""};
/// Mesh harmonics 1..N whose coincidences a speed sweep marks.
inline constexpr ArgumentRange kHarmonics{1, 100, false, true, "", ""};
/// CVODE's largest BDF order.
inline constexpr ArgumentRange kMaxOrder{1, 5, false, true, "", ""};
/// Speeds of a speed sweep.
inline constexpr ArgumentRange kSweepSpeeds{1, 1e5, false, true, "", ""};
/// A spectrum's frequency resolution [Hz] (0: one carrier revolution per segment).
inline constexpr ArgumentRange kSpectrumResolution{0,     1e6,    false,
                                                   false, "[Hz]", "0: one carrier revolution"};
/// The integrator's steps per output interval before it gives up (SimulationOptions::max_steps).
inline constexpr ArgumentRange kMaxSteps{1, 1e9, false, true, "", "per output interval"};
/// A run's wall-time budget [s] (SimulationOptions::time_limit): when spent the run stops with
/// what it has (up to about eleven days).
inline constexpr ArgumentRange kRunTimeLimitS{0, 1e6, true, false, "[s]", "the run's wall time"};
/// Mesh cycles a spectrum leaves out at the start of a run.
inline constexpr ArgumentRange kSpectrumSkipCycles{
    0, 1e6, false, false, "[mesh cycles]", "the start transient"};

}  // namespace epicycle::dynamics
