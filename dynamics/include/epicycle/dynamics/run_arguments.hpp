// The numbers a user gives a dynamic run, a speed sweep or their spectra besides the scene (the
// program's options, the Python drivers' keyword arguments), each with its range
// (geometry/argument_range.hpp): the one statement of the rule that the program and the bindings
// check. The sun speed, the carrier angles and the threads are transmission/run_arguments.hpp's.
#pragma once

#include <string>
#include <vector>

#include "epicycle/transmission/run_arguments.hpp"

namespace epicycle::dynamics {

using geometry::ArgumentInfo;
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

/// The arguments of a dynamic run (DynamicRequest), of a speed sweep (SpeedSweepRequest) and of a
/// periodic branch (BranchRequest) as the program and Python offer them (geometry::ArgumentInfo);
/// a flag's keyword is the field it sets or clears (--fd-jacobian: analytic_jacobian).
struct DynamicArguments {
  static constexpr ArgumentInfo kSpeedRpm{
      "--speed-rpm", "sun_speed_rpm",
      "Sun speed [rpm] (default: the scene's [dynamics] sun_speed_rpm, else 1500)",
      &transmission::kSunSpeedRpm};
  static constexpr ArgumentInfo kRange{
      "--range", "range",
      "Simulate one mesh cycle, one planet or sun revolution relative to the carrier, or one "
      "carrier revolution"};
  static constexpr ArgumentInfo kTime{"--time", "time_s", "Simulate this long instead [s]",
                                      &kRunTimeS};
  static constexpr ArgumentInfo kStartDeg{
      "--start-deg", "start_deg", "Carrier angle at t = 0 [deg]", &transmission::kCarrierAngleDeg};
  static constexpr ArgumentInfo kFriction{"--friction", "friction",
                                          "Override the scene's friction law"};
  static constexpr ArgumentInfo kBackend{"--backend", "backend",
                                         "Contact back end (newton, ipopt, nlopt-lbfgs, ...)"};
  static constexpr ArgumentInfo kIntegrator{"--integrator", "integrator",
                                            "cvode-bdf (default) or arkode-erk"};
  static constexpr ArgumentInfo kRtol{"--rtol", "rtol", "Relative tolerance of the integrator",
                                      &kRelativeTolerance};
  static constexpr ArgumentInfo kRateScale{
      "--rate-scale", "rate_scale",
      "Absolute tolerance of the rates = that of the positions times this [1/s] (default 1e4; 0: "
      "the stage's highest linearised natural frequency; docs/dynamic_cost.md, Error against run "
      "time)",
      &dynamics::kRateScale};
  static constexpr ArgumentInfo kContactTol{
      "--contact-tol", "contact_tol",
      "Tolerance of every contact solve on its nondimensional residual (default 1e-10)",
      &kRunContactTolerance};
  static constexpr ArgumentInfo kOutputsPerCycle{
      "--outputs-per-cycle", "outputs_per_cycle",
      "Output steps per mesh cycle (default: 10 per period of the highest natural frequency, 20 "
      "to 500; 64 in a speed sweep's window; docs/dynamic.md, Outputs)",
      &dynamics::kOutputsPerCycle};
  static constexpr ArgumentInfo kSpeedSweep{
      "--speed-sweep", "sun_speeds_rpm",
      "FROM:TO:N: run N sun speeds [rpm] from FROM to TO (ends included) in parallel; per speed "
      "K_gamma, dynamic factor, TE amplitude, sun orbit, against speed with the mesh-harmonic "
      "coincidences of the natural frequencies (--range or --window-cycles: the measured window; "
      "--start-deg: where it begins)"};
  static constexpr ArgumentInfo kPeriodic{
      "--periodic", "periodic",
      "Speed sweep: the periodic orbits instead of time integrations: shooting and "
      "pseudo-arclength continuation from FROM to TO through the folds, both branches with their "
      "Floquet stability, steps of at most 1/N of the range (docs/periodic.md)"};
  static constexpr ArgumentInfo kContinue{
      "--continue", "parameter",
      "NAME:FROM:TO:N: the periodic orbits continued over a number of the scene at the scene's (or "
      "--speed-rpm's) speed: sun_speed_rpm, sun_torque_Nm, mesh_damping_ratio, "
      "errors.pin.planetK.radial_um or tangential_um"};
  static constexpr ArgumentInfo kPeriodicPoints{
      "--periodic-points", "max_points",
      "--periodic, --continue: the most points of the branch (default 400)", &kSweepSpeeds};
  static constexpr ArgumentInfo kPeriodicMethod{
      "--periodic-method", "method",
      "--periodic, --continue: shooting (the default) or hb: harmonic balance with Hill's "
      "stability, for a stage whose orbit repeats with the mesh (docs/periodic.md)"};
  static constexpr ArgumentInfo kHbHarmonics{
      "--hb-harmonics", "harmonics",
      "--periodic-method hb: harmonics of the mesh period kept (default 24)",
      &dynamics::kHarmonics};
  static constexpr ArgumentInfo kWindowCycles{
      "--window-cycles", "window_cycles",
      "Speed sweep: mesh cycles measured per speed (replaces --range)", &dynamics::kWindowCycles};
  static constexpr ArgumentInfo kHarmonics{
      "--harmonics", "harmonics",
      "Speed sweep: mark coincidences of mesh harmonics 1..N (default: every one in range)",
      &dynamics::kHarmonics};
  static constexpr ArgumentInfo kThreads{"--threads", "threads",
                                         "Speed sweep: worker threads (default: every core)",
                                         &transmission::kThreads};
  static constexpr ArgumentInfo kCarryState{
      "--carry-state", "carry",
      "Speed sweep: up or down: a run-up or run-down, one speed after the other in that order, "
      "each from the previous speed's end state (the jumps of docs/periodic.md); none: each speed "
      "from rest (the default)"};
  static constexpr ArgumentInfo kMaxOrder{
      "--max-order", "max_order", "Largest BDF order of CVODE (1..5)", &dynamics::kMaxOrder};
  static constexpr ArgumentInfo kMaxSteps{
      "--max-steps", "max_steps",
      "Integrator steps per output interval before the run stops (default 2000000)",
      &dynamics::kMaxSteps};
  static constexpr ArgumentInfo kTimeLimit{
      "--time-limit", "time_limit_s",
      "Wall-time budget of the run [s]: when spent it stops with what it has (exit 1)",
      &kRunTimeLimitS};
  static constexpr ArgumentInfo kSpectrum{
      "--spectrum", "spectrum",
      "Also the vibration signals per step and their spectra (docs/spectra.md)"};
  static constexpr ArgumentInfo kSpectrumResolution{
      "--spectrum-resolution", "spectrum_resolution",
      "Spectrum: segment length 1/this [Hz] (default 0: one carrier revolution)",
      &dynamics::kSpectrumResolution};
  static constexpr ArgumentInfo kSpectrumSkip{
      "--spectrum-skip-cycles", "spectrum_skip_cycles",
      "Spectrum: mesh cycles left out at the start (default 4)", &kSpectrumSkipCycles};
  static constexpr ArgumentInfo kRating{
      "--rating", "rating",
      "ISO 6336 ratings with the run's K_v and the stresses in motion (needs the scene's "
      "[material] bending_limit_MPa and contact_limit_MPa; implies --stresses)"};
  static constexpr ArgumentInfo kStresses{
      "--stresses", "stresses",
      "Also each gear's root stress per output step (the scene's [model] stresses)"};
  static constexpr ArgumentInfo kFdJacobian{
      "--fd-jacobian", "analytic_jacobian",
      "CVODE's finite-difference Jacobian instead of the contact sensitivity"};
};

/// The argument of a modal analysis (ModesRequest).
struct ModesArguments {
  static constexpr ArgumentInfo kSpeedRange{
      "--speed-range-rpm", "speed_range_rpm",
      "Sun speeds LO HI [rpm] for the mesh-harmonic coincidences (default: the scene's speed / 2 "
      ".. x 2)",
      &transmission::kSunSpeedRpm};
};

struct BranchRequest;

/// The sun speeds of "FROM:TO:N" given for `option` (the program's --speed-sweep): N speeds [rpm]
/// from FROM to TO, ends included (SpeedGrid); FROM and TO by kSunSpeedRpm, N by kSweepSpeeds.
/// @throws std::invalid_argument "OPTION = SPEC: ..." naming the part and its rule.
std::vector<double> ParseSpeedSweep(const std::string& option, const std::string& spec);

/// The parameter, range and steps of a branch given for `option` as "FROM:TO:N" over the sun
/// speed (ParseSpeedSweep) when `sun_speed`, else as "NAME:FROM:TO:N" over the scene's number NAME
/// (its key path); the range of non-zero width, N >= 1; the request's parameter and steps named
/// "OPTION NAME" and "OPTION N".
/// @throws std::invalid_argument "OPTION = SPEC: ..." naming the part and its rule.
void ParseBranchRange(const std::string& option, const std::string& spec, bool sun_speed,
                      BranchRequest* request);

}  // namespace epicycle::dynamics
