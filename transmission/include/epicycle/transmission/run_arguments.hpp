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

using geometry::ArgumentInfo;
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

/// The magnification of the relief in a drawing of one tooth pair [-].
inline constexpr ArgumentRange kReliefScale{0, 1e4, true, false, "", ""};

/// The arguments of the geometry report's drawing and of the contact listing.
struct GeometryArguments {
  static constexpr ArgumentInfo kCarrierDeg{
      "--carrier-deg", "carrier_deg",
      "Carrier angle of the drawing [deg] (gear pairs: gear 1's turn)", &kCarrierAngleDeg};
  static constexpr ArgumentInfo kReliefScale{
      "--relief-scale", "relief_scale",
      "Magnification of the relief in the zoom drawing [-] (default 200)",
      &transmission::kReliefScale};
  static constexpr ArgumentInfo kContactsCarrierDeg{
      "--carrier-deg", "carrier_deg", "Carrier angle [deg] (gear pairs: gear 1's turn)",
      &kCarrierAngleDeg};
};

/// The arguments of a quasi-static run (QuasiStaticRequest) as the program and Python offer them
/// (geometry::ArgumentInfo); flags whose keyword is the field they clear (--cold: warm_start).
struct QuasiStaticArguments {
  static constexpr ArgumentInfo kPositions{
      "--positions", "positions",
      "Positions of the sweep (default 60 per mesh cycle: docs/quasistatic.md, Positions)",
      &kSweepPositions};
  static constexpr ArgumentInfo kRange{
      "--range", "range",
      "Sweep one mesh cycle, one planet or sun revolution relative to the carrier (the period of "
      "a planet's run-out, of a sun tooth's damage), or one carrier revolution"};
  static constexpr ArgumentInfo kStartDeg{
      "--start-deg", "start_deg", "Carrier angle of the first position [deg]", &kCarrierAngleDeg};
  static constexpr ArgumentInfo kAnglesDeg{
      "--angles-deg", "angles_deg", "A given list of carrier angles [deg]", &kCarrierAngleDeg};
  static constexpr ArgumentInfo kThreads{
      "--threads", "threads",
      "Worker threads: the positions in contiguous chunks, one per thread (0: one per core)",
      &kThreadsOrZero};
  static constexpr ArgumentInfo kCold{
      "--cold", "warm_start",
      "Start every position from its kinematic poses and zero forces (no warm start from the "
      "neighbour)"};
  static constexpr ArgumentInfo kFriction{
      "--friction", "friction",
      "Friction at rest: off (default), scene (the scene's [dynamics] friction), or a law; "
      "lubricant and sliding from the scene's [lubricant] and sun_speed_rpm"};
  static constexpr ArgumentInfo kBackend{"--backend", "backend",
                                         "Contact back end (newton, ipopt, nlopt-slsqp, ...)"};
  static constexpr ArgumentInfo kNoLocal{"--no-local", "local_terms",
                                         "Structural compliance only (no local contact term)"};
  static constexpr ArgumentInfo kStresses{
      "--stresses", "stresses",
      "Also root stresses and contact pressures per position (the scene's [model] stresses)"};
  static constexpr ArgumentInfo kRating{
      "--rating", "rating",
      "ISO 6336 ratings with the run's K_gamma and stresses (needs the scene's [material] "
      "bending_limit_MPa and contact_limit_MPa; implies --stresses)"};
  static constexpr ArgumentInfo kRigidPins{
      "--rigid-pins", "pin_feedback",
      "Leave out the scene's [[face_width.pin]]: every planet held at its given tilt (the run "
      "without the tilt's feedback)"};
};

/// The arguments of a mesh-stiffness run (StiffnessRequest).
struct StiffnessArguments {
  static constexpr ArgumentInfo kMesh{"--mesh", "mesh",
                                      "Mesh of a stage: sun-planet1, planet1-ring, ..."};
  static constexpr ArgumentInfo kPositions{"--positions", "positions", "Positions per mesh cycle",
                                           &kStiffnessPositions};
  static constexpr ArgumentInfo kCycle{"--cycle", "cycle", "Sweep this one mesh cycle",
                                       &kStiffnessCycle};
  static constexpr ArgumentInfo kThreads = QuasiStaticArguments::kThreads;
  static constexpr ArgumentInfo kBackend = QuasiStaticArguments::kBackend;
  static constexpr ArgumentInfo kNoLocal = QuasiStaticArguments::kNoLocal;
  static constexpr ArgumentInfo kStresses{
      "--stresses", "stresses",
      "Also each gear's root stress per position (the scene's [model] stresses)"};
};

/// The arguments of a tolerance study (studies::StudyRequest).
struct StudyArguments {
  static constexpr ArgumentInfo kThreads{
      "--threads", "threads", "Worker threads (default: every core)", &transmission::kThreads};
  static constexpr ArgumentInfo kMaxCases{
      "--max-cases", "max_cases",
      "Compute at most this many new cases, then summarise (a partial run)", &kStudyCases};
  static constexpr ArgumentInfo kStresses{
      "--stresses", "stresses",
      "Also each gear's root stress per case (the study's or scene's stresses)"};
  static constexpr ArgumentInfo kCases{
      "--cases", "cases",
      "Only the cases I <= k < J (I:J), into the part study_cases_I_J.csv (merge the parts with "
      "`study merge`)"};
  static constexpr ArgumentInfo kShard{
      "--shard", "shard",
      "Only shard K of N (K/N, K from 0): the cases floor(K C/N) .. floor((K+1) C/N)"};
};

/// The arguments of the contact core's runs on problem files (solve, compare, stability).
struct ContactArguments {
  static constexpr ArgumentInfo kTolerance{
      "--tol", "tolerance", "tolerance on the nondimensional residual", &kContactTolerance};
  static constexpr ArgumentInfo kRepeats{
      "--repeat", "repeats", "solves per (back end, problem); the median time is reported",
      &kComparisonRepeats};
};

/// Carrier angles given as a list [deg]: their count by kSweepPositions ("NAME: 0 angles: must be
/// a whole number in [1, 1000000]"), each by kCarrierAngleDeg ("NAME = nan: ..."); the angles in
/// radians. @throws std::invalid_argument naming `name`.
std::vector<double> CheckedCarrierAngles(const std::string& name, const std::vector<double>& deg);

}  // namespace epicycle::transmission
