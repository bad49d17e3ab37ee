// Speed sweeps of the dynamic model (docs/speed_sweeps.md): the stage run at a list of
// sun speeds, each from the quasi-static solution, and per speed the figures a gear engineer reads
// off a run-up: the dynamic mesh load factor, the dynamic factor, the transmission-error amplitude
// and the sun's orbit, with the speeds where a mesh harmonic meets a linearised natural frequency.
//
// Definitions (per speed; "window" = the measured part of the run, below):
//   K_γ        = max over window samples t and planets i of n·LSR_i(t)          (eq. 4, n planets)
//   F_m(t)     = Σ_{j ∈ mesh m} F_j,total(t): the total normal force of mesh m (sun–planet i or
//                planet i–ring), the tooth pairs' elastic force plus damping, clipped at 0 [N]
//   F_m,qs(φ)  = the same sum of the quasi-static solution at carrier angle φ [N]
//   K_v        = max over meshes m of  max_t F_m(t) / max_φ F_m,qs(φ)
//                (the dynamic factor: the largest peak of a mesh's total force in motion over
//                the peak of that mesh's quasi-static force at the same carrier angles; meshes
//                without quasi-static load are left out; the mesh that gives the max is kept)
//   TE amp.    = ½ (max_t TE − min_t TE), half the peak-to-peak dynamic transmission error at
//                the sun [rad]
//   orbit      = max_t |sun centre − nominal| [m] (0 for a fixed sun)
//   deviation  = max over window samples and planets of |LSR_i − 1/n|, with its parts at that
//                sample and planet (DecomposeLoadSharing, load_sharing_parts.hpp)
// The quasi-static reference uses the same stage model (compliance, local terms, supports, errors)
// at exactly the carrier angles of the window's samples, which are the same for every speed.
//
// The window. The run starts at the quasi-static solution (DynamicModel::QuasiStaticStart) with
// the rigid-kinematic velocities; the difference to the periodic response decays as e^{−σ_j t} in
// mode j, σ_j = ζ_j ω_j its modal decay rate. With C the linearised damping matrix (the mesh
// damping along the lines of action and the bearings' damping, from DynamicModel::Jacobian at the
// quasi-static start, C = −M ∂d̈/∂ḋ) and φ_j the M-normalised modes of DynamicModel::Linearise,
// σ_j = ½ φ_jᵀ C φ_j (first order in the damping; exact for proportional damping). The run skips
//   t_skip = ln(1/ε) / min_j σ_j
// (ε = transient_fraction, default 1e-2: the start transient is below 1 % of its initial size in
// every mode), then measures `window_cycles` mesh cycles with `outputs_per_cycle` samples each.
// The start angle is set so that the window begins at carrier angle `window_start` for every
// speed: φ_0 = window_start − ω_c t_skip.
//
// Coincidences: mesh harmonic h at the mesh frequency f_m = z_r |ω_c|/2π meets natural frequency
// f_j of the linearisation (DynamicModel::Linearise at window_start, dynamics::SolveModes; with
// SpeedSweepOptions::modal_mesh_stiffness, e.g. the tangent stiffness of MeanTangentMeshStiffness,
// which is where the resonances are found: docs/dynamic.md) at the sun speed
// n_s = 60 f_j (1 + z_r/z_s) / (h z_r) [rpm]. For equally spaced planets, Parker & Lin
// (2004, "Mesh phasing relationships in planetary and epicyclic gears", J. Mech. Des. 126(2)
// 365–370) give which harmonics the (symmetric) mesh excitation reaches: the planets' loads at
// harmonic h have phases e^{i h z_s ψ_i}, the cyclic family k ≡ ±h z_s (mod n), so rotational
// modes (k = 0) when h z_s/n is whole, translational modes (k = ±1) when (h z_s ∓ 1)/n is whole,
// planet modes otherwise. The family of a mode is read from its shape (the planets' motions'
// discrete Fourier components over the planets, ≥ 1 % of their squared amplitude), since a held
// sun turns the k = ±1 modes into "planet" modes by class. `phasing_excited` says so (errors such
// as run-out break the symmetry and excite the others weakly; always true for unequally spaced
// planets).
//
// Carried state (SpeedSweepOptions::carry): a slow run-up (kUp) or run-down (kDown) instead of
// independent speeds. The speeds run one after the other on one thread, in increasing (up) or
// decreasing (down) order; the first starts from the quasi-static solution as above, every later
// one from the state (deviations and rates) and carrier angle at the end of the previous speed's
// window, the carrier turning on without a break, and skips `skip_time` (or t_skip) before its
// window as the others do. The speed changes in a step between two speeds, so the sweep rate is
// Δn / (t_skip + window) per speed: finer steps or a longer dwell make it slower. Where several
// periodic responses coexist (docs/periodic.md §3, the jumps) the sweep stays on the one it came
// from until that one ends at a fold. A speed that fails hands on nothing: the next one starts
// from the quasi-static solution again. Each window begins where the previous ended, at carrier
// angles a whole number of mesh cycles from the plan's when the skip and the window are whole
// numbers of mesh cycles (the quasi-static reference of K_v is the plan's).
//
// Threads: every speed has its own DynamicModel (the settings carry the speed) over the shared,
// read-only stage model, and its own contact solver (inside Simulate); nothing mutable is shared.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/load_sharing_parts.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/io/enum_names.hpp"

namespace epicycle::dynamics {

/// How the speeds of a sweep start (above, "Carried state").
enum class CarryState {
  kNone,  ///< every speed from the quasi-static solution, in parallel
  kUp,    ///< in increasing speed, each from the previous speed's end state
  kDown,  ///< in decreasing speed, each from the previous speed's end state
};

/// The carries' names ("none", "up", "down"): the one table of CarryStateName and
/// ParseCarryState.
inline constexpr std::array<io::EnumName<CarryState>, 3> kCarryStateNames{{
    {CarryState::kNone, "none"},
    {CarryState::kUp, "up"},
    {CarryState::kDown, "down"},
}};

inline const char* CarryStateName(CarryState carry) { return io::NameOf(kCarryStateNames, carry); }
/// The carry named `name` ("none", "up", "down").
/// @throws std::invalid_argument naming `key`, the value and the names allowed.
CarryState ParseCarryState(const std::string& key, const std::string& name);

struct SpeedSweepOptions {
  std::vector<double> sun_speeds_rpm;    ///< sun speeds [rpm], each > 0, strictly increasing
  int threads = 1;                       ///< worker threads [-], ≥ 1 (one with carry ≠ kNone)
  CarryState carry = CarryState::kNone;  ///< independent speeds, or a run-up / run-down
  double window_cycles = 4;              ///< mesh cycles measured per speed [-], > 0
  int outputs_per_cycle = 32;            ///< samples per mesh cycle in the window [-], ≥ 4
  double window_start = 0;               ///< carrier angle where the window begins [rad]
  double transient_fraction = 1e-2;      ///< ε of t_skip [-], in (0, 1)
  double skip_time = 0;                  ///< > 0: skip this long instead of t_skip [s]
  int harmonics = 0;  ///< coincidences of mesh harmonics h ≤ harmonics; 0: every one in range [-]
  /// > 0: the mesh stiffnesses {sun–planet, planet–ring} [N/m] of the linearisation that gives the
  /// modes and coincidences (e.g. MeanTangentMeshStiffness); 0: the base model's. The damping
  /// matrix always uses the base model's (its c_m is what the runs use).
  std::array<double, 2> modal_mesh_stiffness = {0.0, 0.0};
  SimulationOptions simulation;  ///< integrator, tolerances, contact back end
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

/// `count` sun speeds from `from` to `to` [rpm], ends included, equally spaced (count = 1: from).
/// @throws std::invalid_argument naming the value and the rule (from > 0, to ≥ from, count ≥ 1,
///         count = 1 only with from = to, finite).
std::vector<double> SpeedGrid(double from, double to, int count);

/// One mode's modal damping of the linearisation.
struct ModeDamping {
  Mode mode;                 ///< from SolveModes (rigid modes are left out)
  double decay_rate = 0;     ///< σ_j = ½ min over the group's shapes of φᵀ C φ [1/s]
  double damping_ratio = 0;  ///< ζ_j = σ_j / ω_j [-]
  /// The cyclic-symmetry families k (0 ≤ k ≤ n/2, k and n − k together) holding ≥ 1 % of the
  /// planets' squared amplitude: 0 rotational, 1 translational, others planet modes.
  std::vector<int> families;
};

/// Where mesh harmonic h meets natural frequency f_j.
struct Coincidence {
  double sun_speed_rpm = 0;     ///< n_s [rpm]
  double frequency = 0;         ///< f_j [Hz]
  int mode = 0;                 ///< index into SpeedSweepPlan::modes [-]
  int harmonic = 1;             ///< h [-]
  bool phasing_excited = true;  ///< Parker & Lin's rule for equally spaced planets (see above)
};

/// Parker & Lin's planet-phasing rule (above), the one place it is written: the cyclic family
/// k = h z_s mod n, in [0, n), that mesh harmonic h of a stage with `sun_teeth` z_s and `planets`
/// n equally spaced planets loads (k = 0: the planets in phase, the sun's rotation and every
/// torque; k = 1 and n − 1: the net force on the central members, turning with the carrier one
/// way or the other; docs/model.md §9 "Fault frequencies"). @throws std::invalid_argument for
/// planets < 1.
int PhasingFamily(int harmonic, int sun_teeth, int planets);

/// The planets are at ψ_i = ψ_1 + 2π(i − 1)/n (to 1e-9 rad).
bool EquallySpaced(const geometry::Stage& stage);

/// Every coincidence of a mesh harmonic with one of `modes` inside [lo_rpm, hi_rpm] of sun speed:
/// for each non-rigid mode j every harmonic h ≥ 1 with n_s = f_j/(h f_m per rpm) in the range
/// (h ≤ max_harmonic when max_harmonic > 0), marked by the phasing rule above; sorted by speed.
/// Coincidence::mode indexes `modes`. The modes are `model`'s (their shapes give the families).
/// @throws std::invalid_argument unless 0 < lo_rpm ≤ hi_rpm, both finite.
std::vector<Coincidence> FindCoincidences(const DynamicModel& model, const std::vector<Mode>& modes,
                                          double lo_rpm, double hi_rpm, int max_harmonic = 0);

/// What is fixed before the speeds run.
struct SpeedSweepPlan {
  std::vector<ModeDamping> modes;         ///< non-rigid modes, by frequency
  std::vector<Coincidence> coincidences;  ///< within [first, last speed], by speed
  double mesh_hz_per_rpm = 0;             ///< f_m per sun rpm [Hz/rpm]
  double skip_time = 0;                   ///< t_skip [s]
  double slowest_decay_rate = 0;          ///< min_j σ_j [1/s]
  std::vector<double> window_angles;      ///< carrier angles of the window's samples [rad]
  /// Mesh names in the order of geometry::Stage::meshes(): "sun-planet1", "planet1-ring", ...
  std::vector<std::string> meshes;
  /// max_φ F_m,qs per mesh [N], with the base model's friction at its speed (SolveRestReference)
  std::vector<double> qs_peak_mesh_force;
  double qs_k_gamma = 0;       ///< K_γ of the quasi-static window [-]
  double qs_te_amplitude = 0;  ///< ½ peak-to-peak of the static TE over the window [rad]
  double seconds = 0;          ///< wall time of the planning [s]
};

/// One speed's result.
struct SpeedResult {
  int index = 0;              ///< position in sun_speeds_rpm [-]
  double sun_speed_rpm = 0;   ///< [rpm]
  double mesh_frequency = 0;  ///< f_m [Hz]
  /// kCompleted: the run reached every output; else why it stopped (its start or its run).
  transmission::RunStatus status = transmission::RunStatus::kIntegratorFailure;
  bool ok() const { return status == transmission::RunStatus::kCompleted; }
  std::string message;         ///< why not
  double k_gamma = 0;          ///< K_γ over the window [-]
  double dynamic_factor = 0;   ///< K_v [-]
  int factor_mesh = -1;        ///< the mesh m that gives K_v (index into plan.meshes), −1: none
  double peak_mesh_force = 0;  ///< max_t F_m(t) of that mesh [N]
  double qs_peak_mesh_force = 0;    ///< and its quasi-static reference's at this speed [N]
  double te_amplitude = 0;          ///< ½ peak-to-peak TE over the window [rad]
  double orbit_radius = 0;          ///< largest sun-centre displacement over the window [m]
  double lsr_min = 0, lsr_max = 0;  ///< extremes of LSR_i over planets and window [-]
  /// The largest |LSR_i − 1/n| over planets and window [-], and its parts at that sample and
  /// planet (DecomposeLoadSharing, in the order of kLoadSharingPartNames; they sum to the signed
  /// deviation LSR_i − 1/n there) [-].
  double lsr_deviation = 0;
  std::array<double, kLoadSharingPartCount> deviation_parts{};
  double largest_residual = 0;  ///< the largest |residual| of the parts over planets and window [-]
  /// A helical stage: the axial forces [N] and tilting moments [N·m] over the window's samples
  /// (DynamicSample::helical), their means and largest magnitudes; empty for a spur stage.
  transmission::HelicalLoadRange helical;
  /// Results outside the model's validity over the window (DynamicWarnings); empty: none.
  std::vector<std::string> warnings;
  SimulationStats stats;    ///< of the whole run (skip and window)
  double cpu_seconds = 0;   ///< CPU of the thread that ran this speed [s]
  double wall_seconds = 0;  ///< wall time of this speed [s]
};

struct SpeedSweepResult {
  SpeedSweepPlan plan;
  std::vector<SpeedResult> speeds;  ///< in the order of sun_speeds_rpm
  double wall_seconds = 0;          ///< of the speeds' runs (the plan excluded) [s]
  int failed() const;               ///< speeds with ok = false
};

/// The plan of a sweep of `base` (its settings and mesh stiffnesses; its speed is not used):
/// modes, modal damping, t_skip, coincidences, and the quasi-static reference over the window.
/// @throws std::invalid_argument for bad options, or when the slowest mode has no damping
///         (σ ≤ 0) and no skip_time is given; std::runtime_error if a quasi-static position of
///         the window or of the start fails.
SpeedSweepPlan PlanSpeedSweep(const DynamicModel& base, const SpeedSweepOptions& options);

/// The figures of one speed from its window's samples (those at plan.window_angles); K_γ is the
/// largest DynamicSample::k_gamma of the window; K_v against `qs_peak_mesh_force` (the speed's own
/// reference, SolveRestReference; empty: the plan's).
SpeedResult SummariseSpeed(const SpeedSweepPlan& plan, const std::vector<DynamicSample>& window,
                           const std::vector<double>& qs_peak_mesh_force = {});

/// Runs every speed of `plan` (from PlanSpeedSweep with the same options) on `options.threads`
/// workers (lowest speed first: the slowest to run; with options.carry one after the other in
/// the carry's order, each from the previous speed's end state), each result handed to `on_result`
/// as soon as it is computed (under one lock, in completion order, the speed in the result). A
/// speed that fails (its start, a step) is a result with ok = false and its message, never left
/// out.
/// @throws std::invalid_argument for bad options; what `on_result` throws (after the running
///         speeds end).
SpeedSweepResult SweepSpeeds(const DynamicModel& base, const SpeedSweepOptions& options,
                             const SpeedSweepPlan& plan,
                             const std::function<void(const SpeedResult&)>& on_result = {});
/// The same with the plan made first.
SpeedSweepResult SweepSpeeds(const DynamicModel& base, const SpeedSweepOptions& options,
                             const std::function<void(const SpeedResult&)>& on_result = {});

/// Where a carried sweep (options.carry ≠ kNone) leaves the response it started on: walking the
/// speeds in the carry's order (`speeds` in the order of sun_speeds_rpm), the index of the first
/// speed whose TE amplitude lies on the other side of `te_threshold` [rad] than the first speed's
/// (a jump between two coexisting orbits whose amplitudes the threshold separates); −1 when none
/// does or a speed on the way failed.
/// @throws std::invalid_argument for carry = kNone or a threshold that is not > 0 and finite.
int JumpIndex(const std::vector<SpeedResult>& speeds, CarryState carry, double te_threshold);

/// One sun speed's dynamic model: `base` with sun_speed = rpm·π/30, the same mesh stiffnesses.
DynamicModel ModelAtSpeed(const DynamicModel& base, double sun_speed_rpm);

}  // namespace epicycle::dynamics
