// Quasi-static solution of the stage at one carrier position (docs/model.md §5–6): contact search →
// compliance → contact problem with equilibrium equalities → back end → forces and rigid
// displacements; the members are moved by the displacements and the search repeated until the
// displacements stop changing (the geometry is nonlinear in the positions). A sweep starts each
// position from its neighbour's converged state and runs contiguous chunks of positions on
// several threads (docs/quasistatic.md, "Sweep cost").
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/dynamic_settings.hpp"
#include "epicycle/transmission/friction.hpp"
#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "epicycle/transmission/stage_model.hpp"

namespace epicycle::transmission {

struct QuasiStaticOptions {
  solvers::Backend backend = solvers::Backend::kActiveSetNewton;
  solvers::ContactOptions contact;
  int max_geometric_iterations = 30;   ///< [-]
  double geometric_tolerance = 1e-11;  ///< largest rigid-displacement increment at convergence [m]
  /// Accept a contact solve whose status is converged-inaccurate (residual ≤ 100× tolerance), for
  /// back ends whose own stopping rule ends just above the tolerance; such positions keep the
  /// status in their report and a note in their message. Default: only converged.
  bool accept_inaccurate = false;
  /// Sweep: start each position from its neighbour's converged state: the members displaced from
  /// their kinematic poses by the neighbour's rigid displacements (rotations, the floating sun's
  /// and elastic planets' translations), and the contact solve from the neighbour's forces on the
  /// same potential contacts (StageContact::SameAs). The converged result does not depend on it
  /// beyond the contact and geometric tolerances (docs/quasistatic.md). false: every position
  /// from its kinematic poses and zero forces, as SolvePosition.
  bool warm_start = true;
  /// Sweep: worker threads [-]; 0: std::thread::hardware_concurrency(). The angles are split into
  /// contiguous chunks, one per thread, each chunk warm-started in sequence from its own first,
  /// cold, position; so results depend on the thread count within the tolerances (bit-identical
  /// across thread counts only with warm_start = false).
  int threads = 0;
  /// Friction at rest (docs/model.md §9, docs/quasistatic.md "Friction at rest"): the law, its
  /// coefficient and lubricant, the dynamic model's (FrictionOptions). Default off: no friction
  /// code runs and the results are those of the frictionless model, bit for bit.
  FrictionOptions friction = NoFriction();
  /// |ω_s| [rad/s] of the rigid kinematics that give each contact its surface velocities when
  /// friction is on (the scene's [dynamics] sun_speed_rpm): finite and > 0; unused when off.
  double sun_speed = 0;
  /// @throws std::invalid_argument naming the field (iterations < 1, tolerance not > 0, threads
  ///         < 0, bad contact options, bad friction options, friction on without a speed > 0).
  void Validate() const;
};

struct PositionResult {
  double carrier_angle = 0;               ///< φ_c [rad]
  bool converged = false;                 ///< contact solves and geometric iterations converged
  StageStatus status = StageStatus::kOk;  ///< what stopped it when not converged
  std::string message;                    ///< why not, when not converged
  int geometric_iterations = 0;
  int contact_iterations = 0;  ///< back-end iterations summed over the geometric iterations [-]
  bool warm_started = false;   ///< started from a neighbour's state (Sweep with warm_start)
  std::vector<double> load_sharing;  ///< LSR_i = T_mesh(P_i–S)/T_input [-], per planet
  /// With slices of the face width (face_width.hpp): each mesh's load per unit width and K_Hβ
  /// (sun–planet meshes, then planet–ring meshes); empty with one slice.
  std::vector<MeshFaceLoad> face_loads;
  /// A helical stage's axial forces and each planet's tilting moment (helical_slices.hpp); no
  /// planets for a spur stage.
  HelicalLoads helical;
  /// With pins of finite stiffness (pin.hpp; else empty): each planet's tilt on its pin under
  /// the load of this position, t [-] in the inertial frame (GearPose::axis_slope of `poses`)
  /// and in the carrier frame (radial outward, tangential counter-clockwise at +z), and the last
  /// tilt update's change of the gap across the face b |Δt| [m] (settled: ≤ the geometric
  /// tolerance; the iterations are geometric_iterations).
  std::vector<Eigen::Vector2d> pin_tilts, pin_tilts_carrier;
  double pin_tilt_change = 0;
  double transmission_error = 0;     ///< loaded static TE: sun rotation from kinematic [rad]
  geometry::Vec2 sun_displacement = geometry::Vec2::Zero();  ///< [m] (floating sun)
  std::vector<double> planet_rotations;                      ///< from kinematic [rad]
  std::vector<geometry::Vec2> planet_displacements;  ///< bearing deflections [m] (elastic pins)
  StageProblem problem;                              ///< the last contact problem
  solvers::ContactSolution solution;                 ///< its forces [N] and multipliers
  solvers::ContactReport report;                     ///< its back-end report and residuals
  geometry::StagePoses poses;                        ///< the loaded poses
  /// Rigid displacements from the kinematic poses, per DOF of the model's dofs() [rad] or [m]
  /// (the values the named fields above read out; empty if no contact problem was solved).
  Eigen::VectorXd displacements;
  /// The root stresses of the converged state (docs/model.md §9) when the compliance has them
  /// (the scene's [model] stresses), else empty: of the normal forces, and with friction at rest
  /// of the friction forces too.
  std::vector<compliance::FilletStress> fillet_stress;
  /// Each gear's extremes of fillet_stress (SummariseRootStress, body order; empty with it).
  std::vector<GearRootStress> root_stress;
  /// Friction at rest (options.friction on; otherwise false, empty and 0). With it, load_sharing
  /// is the whole sun-mesh torque's share, the friction moments included (paper eq. 4).
  bool friction = false;
  Eigen::VectorXd friction_force;  ///< φ_j = μ_s F_j [N] per contact of `problem` (friction.hpp)
  Eigen::VectorXd sliding_velocity;  ///< v_s = u_A − u_B [m/s] per contact of `problem`
  /// t_j [-], unit, inertial frame: φ_j acts on body B along t_j, on A along −t_j.
  std::vector<Eigen::Vector2d> friction_tangent;
  double force_change = 0;    ///< the fixed point's last relative force change [-]
  double friction_power = 0;  ///< P_f = Σ_j φ_j v_s,j [W], ≥ 0: the power friction dissipates
  double input_power = 0;     ///< P_in = T_s ω_s [W] (the sun's input torque at its speed)
  /// P_out = ω_c Σ_i (pin_i × F_i) [W]: the power the planets deliver to the carrier through
  /// their pins, F_i the net contact force (normal and friction) on planet i.
  double output_power = 0;
  double Efficiency() const { return output_power / input_power; }  ///< η = P_out/P_in [-]
};

/// The choices of SetRestFriction: "off", "scene" (the scene's own law), then every law's name
/// (kFrictionLawNames).
std::vector<std::string> RestFrictionNames();

/// Friction at rest as a command or a binding asks for it (docs/quasistatic.md, "Friction at
/// rest"): "off" (none: options->friction off), "scene" (the scene's law), or a law's name
/// (FrictionLawFromName) replacing it; the coefficient, the lubricant and the speed of the rigid
/// kinematics are always the scene's (`scene`, its [dynamics] and [lubricant] settings).
/// @throws std::invalid_argument naming the value and the allowed names.
void SetRestFriction(const DynamicSettings& scene, const std::string& choice,
                     QuasiStaticOptions* options);

/// The stage model's quasi-static equilibrium at one carrier position under `loads`.
/// @throws std::invalid_argument for bad input; numerical trouble is reported in the result.
PositionResult SolvePosition(const StageModel& model, double carrier_angle, const StageLoads& loads,
                             const QuasiStaticOptions& options);
/// The same started from a neighbouring position's converged result `neighbour` (a warm start:
/// see QuasiStaticOptions::warm_start); null, or a neighbour that did not converge: cold.
PositionResult SolvePosition(const StageModel& model, double carrier_angle, const StageLoads& loads,
                             const QuasiStaticOptions& options, const PositionResult* neighbour);

/// L_i = n·LSR_i [-], the load-sharing factors (ideal 1).
std::vector<double> LoadSharingFactors(const PositionResult& r);
/// K_γ = max_i L_i [-].
double MeshLoadFactor(const PositionResult& r);

/// The memory one result holds [bytes], approximately: its contact problem (the N×N compliance,
/// the equalities, local terms, labels), the potential contacts, forces and poses.
std::size_t ResultBytes(const PositionResult& r);

/// Refuses a sweep of `positions` whose results, all kept (Sweep, about `sample`'s ResultBytes
/// each), would take more than half of the memory `memory_bytes` available.
/// @throws std::invalid_argument "a sweep of N positions keeps about X GB of results in memory
///         (Y kB per position: Z potential contacts), more than half of the M GB available: at
///         most K positions".
void CheckSweepMemory(const PositionResult& sample, std::size_t positions,
                      std::size_t memory_bytes);

/// The memory available to a new allocation on this machine now [bytes]: MemAvailable of
/// /proc/meminfo, else the physical memory (0 if unknown).
std::size_t AvailableMemoryBytes();

/// Carrier angle of position k of a sweep of `count` positions over [start, start + span) [rad]:
/// start + span·k/count.
double SweepAngle(double start, double span, int k, int count);
/// Carrier angles of a sweep: SweepAngle(start, span, k, count) for k in [0, count) [rad].
/// @throws std::invalid_argument if count < 1.
std::vector<double> SweepAngles(double start, double span, int count);

/// Positions a streamed sweep holds at most at once (solved, or being solved, and not yet handed
/// on): its memory is that many results whatever the number of positions (docs/quasistatic.md,
/// "Memory").
inline constexpr int kSweepInFlight = 4096;

/// Solves the positions k in [0, count) at the carrier angles angle(k) and hands each result to
/// on_result(result, k), in the order of k, as soon as it and every earlier one are computed
/// (called under a lock, from any of the workers); a result is not kept after that, so the memory
/// does not grow with `count` (at most kSweepInFlight results are held). A position that does not
/// converge (a geometric outcome or a failed solve: its status) is reported in its result
/// (converged = false, status, message) and the sweep goes on.
/// The positions run on options.threads workers in contiguous chunks, each warm-started in
/// sequence from its own first, cold, position (options.warm_start): one chunk per worker up to
/// kSweepInFlight positions, chunks of kSweepInFlight/workers positions beyond. An exception from
/// on_result or another exception from a position stops the workers and is rethrown.
/// `start` (with options.warm_start): position 0 is warm-started from it as from a neighbour (a
/// converged result of the same stage's DOFs near angle(0): another case of a study at the same
/// angle); ignored if it did not converge; nullptr: position 0 cold.
/// @throws std::invalid_argument for options that fail Validate() or count < 0.
void SweepEach(const StageModel& model, const StageLoads& loads, int count,
               const std::function<double(int)>& angle, const QuasiStaticOptions& options,
               const std::function<void(const PositionResult&, int)>& on_result,
               const PositionResult* start = nullptr);

/// SweepEach over `carrier_angles`, every result kept and returned (for a few thousand positions:
/// a sweep of more than 10 000 positions is checked by CheckSweepMemory from its first result
/// and stopped with its message if the results would not fit). `on_result` (if given) sees every
/// result as SweepEach's does.
/// @throws std::invalid_argument for options that fail Validate(), or from CheckSweepMemory.
std::vector<PositionResult> Sweep(
    const StageModel& model, const StageLoads& loads, const std::vector<double>& carrier_angles,
    const QuasiStaticOptions& options,
    const std::function<void(const PositionResult&, int)>& on_result = {});

}  // namespace epicycle::transmission
