// The result files of the stage drivers, written as results are computed (CSV, one whole checked
// line at a time, the provenance line first) and at the end (SVG plots): a quasi-static sweep, a
// dynamic run and a speed sweep. Column names carry their units; a value that is not finite is an
// empty cell (docs: README "Exit status").
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/dynamic_factor.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/spectrum_files.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/stiffness_run.hpp"
#include "epicycle/transmission/sweep_summary.hpp"

namespace epicycle::report {

/// BASE_positions.csv (one line per carrier position: LSR_i, L_i, K_γ, TE, sun displacement,
/// the solve's counts and status) and BASE_pairs.csv (one line per loaded tooth pair).
class QuasiStaticFiles {
 public:
  /// `friction`: the run has friction at rest; the positions get the columns friction_power_W,
  /// input_power_W, output_power_W, efficiency, force_change at the end, the pairs friction_N and
  /// sliding_m_per_s (none without it: the files are those of the frictionless model).
  /// `root_stress` (the scene's stresses): then each position's line ends with each gear's largest
  /// tensile and compressive root stress, sigma_t_<gear>_MPa and sigma_c_<gear>_MPa, and each
  /// pair's with its Hertz pressure and half-width, hertz_pressure_MPa and hertz_half_width_um
  /// (docs/stresses.md).
  /// @throws std::runtime_error naming a file that cannot be written.
  QuasiStaticFiles(const std::string& base, const nlohmann::json& provenance, int planets,
                   bool friction = false, bool root_stress = false);
  /// The lines of one position (a failed one: its status and message, empty results).
  void Write(const transmission::PositionResult& r);
  void Close();

 private:
  CsvFile positions_, pairs_;
  bool friction_ = false;
  int bodies_ = 0;  // root-stress columns: one pair per body, 0 without
};

/// DIR/NAME.json: a position's contact problem as a problem file (category "stage", the run's
/// provenance, `description`), for `epicycle contact solve|compare` and the collection.
void WriteStageProblemFile(const std::string& dir, const std::string& name,
                           const solvers::ContactProblemData& data,
                           const nlohmann::json& provenance, const std::string& description);

/// A statistic for a JSON file: null where it has no value (JSON has no NaN), never a made-up
/// number.
nlohmann::json JsonValue(double v);

/// Root stresses over a run for its JSON summary: per gear the largest tension and compression
/// [MPa] with where they occur ("tension_<x_name>": the state's x times `x_scale`, and the tooth,
/// fillet side and arc length along the fillet [mm]) and the largest range at one fillet point.
nlohmann::json RootStressJson(const std::vector<transmission::RootStressSummary>& gears,
                              const std::string& x_name, double x_scale);
/// The same as lines of text for a console report ("" without stresses).
std::string RootStressText(const std::vector<transmission::RootStressSummary>& gears,
                           const std::string& x_name, double x_scale);


/// States of a run gathered one at a time into bins of x (time or carrier angle) of width
/// `width` from `origin` (a mesh cycle or a whole number of them): per bin its count, first, last
/// and mean x, and per value the mean (sum over the bin in the order added / count), lowest and
/// highest. x must not decrease; a bin closes when a state falls past it.
class BinEnvelope {
 public:
  struct Bin {
    long count = 0;
    double x_first = 0, x_last = 0, x_mean = 0;
    std::vector<double> mean, min, max;  ///< per value
  };
  /// @throws std::invalid_argument if values < 1 or width is not positive and finite.
  BinEnvelope(int values, double origin, double width);
  /// One state at `x` with its `values` (the constructor's number of them).
  void Add(double x, const std::vector<double>& values);
  /// The bins so far, the last one (still open) included.
  std::vector<Bin> Bins() const;

 private:
  Bin Close(const Bin& open) const;
  int values_;
  double origin_, width_;
  long key_ = 0;
  Bin open_;  // sums in `mean`, x sum in x_mean
  std::vector<Bin> closed_;
};

class RunFigures;

/// BASE_lsr.svg, BASE_te.svg and BASE_sun_path.svg of a sweep's converged positions, gathered one
/// position at a time. With `cycle_deg` > 0 (the carrier rotation of a mesh cycle [deg]) and a
/// sweep of at least 8 mesh cycles, LSR_i and TE are drawn per bin of mesh cycles as their mean
/// (line) and lowest to highest (band), and the sun path's mean per bin over the path; bins of
/// ⌈cycles/(kPlotPoints/2)⌉ mesh cycles. Otherwise, and for the raw path: a sweep of up to
/// kPlotPoints positions draws every one; a longer one, in bins of ⌈positions/(kPlotPoints/2)⌉
/// positions, each bin's lowest and highest LSR_i and TE (and the sun path's points nearest to and
/// farthest from the centre), so that the figures stay the same size whatever the number of
/// positions.
class QuasiStaticPlots {
 public:
  static constexpr long kPlotPoints = 4000;
  /// `positions`: the sweep's positions (converged or not); `span_deg`: the carrier rotation they
  /// cover [deg] (with `cycle_deg`).
  QuasiStaticPlots(const std::string& base, int planets, long positions, double cycle_deg = 0,
                   double span_deg = 0);
  ~QuasiStaticPlots();
  QuasiStaticPlots(const QuasiStaticPlots&) = delete;
  QuasiStaticPlots& operator=(const QuasiStaticPlots&) = delete;
  /// The next position of the sweep (drawn if converged).
  void Add(const transmission::PositionResult& r);
  /// @throws std::runtime_error naming a file that cannot be written.
  void Write(const std::string& scene_name, const std::string& sun_name);

 private:
  std::unique_ptr<RunFigures> figures_;
};

/// BASE_steps.csv (one line per output step: LSR_i, L_i, K_γ, TE, sun centre, the sun's torque
/// balance, work and energies, contacts, friction power), BASE_pairs.csv (one line per loaded
/// tooth pair per step) and BASE_bearings.csv (bearing forces per step). Each file's head is
/// written as it is created; each step's lines go to each file in one write (CsvFile), pairs,
/// bearings, then steps: a step is complete when its line is in BASE_steps.csv, and the other two
/// files hold at most the next step more. A killed run leaves whole lines but for at most a last
/// line without its end (see CsvFile), which a reader drops.
class DynamicRunFiles {
 public:
  /// @throws std::runtime_error naming a file that cannot be written.
  /// `root_stress` (the scene's stresses): each step's line ends with each gear's largest
  /// tensile and compressive root stress, sigma_t_<gear>_MPa and sigma_c_<gear>_MPa.
  /// `face_meshes` (slices of the face width; StageFaceMeshes' names): each step's line ends with
  /// each mesh's K_Hbeta_<mesh> and largest_z_mm_<mesh> (the centre of its most loaded slice).
  /// `helical` (a helical stage, docs/model.md §10): then the axial forces along +z,
  /// sun_axial_force_N, ring_axial_force_N, carrier_axial_force_N, and per planet i
  /// sun_mesh_axial_force_N_<i>, tilting_moment_radial_Nm_<i>, tilting_moment_tangential_Nm_<i>
  /// (DynamicSample::helical).
  DynamicRunFiles(const std::string& base, const nlohmann::json& provenance, int planets,
                  bool root_stress = false, std::vector<std::string> face_meshes = {},
                  bool helical = false);
  void Write(const dynamics::DynamicSample& s);
  void Close();

 private:
  CsvFile pairs_, bearings_, steps_;  // created, and written per step, in this order
  int bodies_ = 0;                     // root-stress columns: one pair per body, 0 without
  std::size_t face_meshes_ = 0;        // face-load columns: one pair per mesh, 0 without
  int helical_planets_ = 0;            // axial-load columns: 3 + 3 per planet, 0 without
};

/// BASE_lsr.svg, BASE_te.svg and BASE_orbit.svg of a run over `span`, gathered one output step
/// at a time (bounded like QuasiStaticPlots, against time [ms]): a run of at least 8 mesh cycles
/// draws LSR_i and TE per bin of mesh cycles as their mean (line) and lowest to highest (band) and
/// the orbit's mean per bin over the raw orbit; a shorter run draws every output.
class DynamicPlots {
 public:
  DynamicPlots(const std::string& base, int planets, const dynamics::RunSpan& span);
  ~DynamicPlots();
  DynamicPlots(const DynamicPlots&) = delete;
  DynamicPlots& operator=(const DynamicPlots&) = delete;
  void Add(const dynamics::DynamicSample& s);
  /// @throws std::runtime_error naming a file that cannot be written.
  void Write(const std::string& scene_name, const std::string& sun_name);

 private:
  std::unique_ptr<RunFigures> figures_;
};

/// The console summary of a dynamic run with `planets` planets: LSR mean, min and max per planet,
/// K_γ, the TE's range, the sun's orbit, the integrator's counts and times, and the root
/// stresses if any ("-" for a statistic without an output step).
std::string DynamicRunText(const dynamics::DynamicSummary& summary,
                           const dynamics::SimulationStats& stats, int planets);

/// PATH.csv of a speed sweep: one line per speed as it completes (a failed speed: its speed,
/// status and message, empty figures). A helical stage's `helical_planets` > 0 planets add, before
/// the counts, the window's axial loads (SpeedResult::helical) as <name>_mean_<unit> and
/// <name>_max_abs_<unit>: sun_axial_force, ring_axial_force, carrier_axial_force [N], and per
/// planet i sun_mesh_axial_force, ring_mesh_axial_force [N], tilting_moment_radial,
/// tilting_moment_tangential [N·m] with the suffix _<i>.
class SpeedSweepFile {
 public:
  /// @throws std::runtime_error naming the file if it cannot be written.
  SpeedSweepFile(const std::string& path, const nlohmann::json& provenance,
                 int helical_planets = 0);
  void Write(const dynamics::SpeedResult& r, const dynamics::SpeedSweepPlan& plan);
  void Close();

 private:
  CsvFile csv_;
  int helical_planets_ = 0;
};

/// PATH_k_gamma.svg, _dynamic_factor.svg, _te_amplitude.svg and _orbit.svg against sun speed,
/// the coincidences of mesh harmonics and natural frequencies marked (dashed: not excited by a
/// symmetric stage's planet phasing), the quasi-static references drawn.
void WriteSpeedSweepPlots(const std::string& path, const std::string& scene_name,
                          const dynamics::SpeedSweepPlan& plan,
                          const std::vector<dynamics::SpeedResult>& speeds);

/// BASE.csv of `epicycle stiffness`: one line per loaded tooth pair per position (the position's
/// columns repeat on each), a position without a loaded pair on one line; per unit face width
/// `face_width` [m] in N/(mm µm).
class MeshStiffnessFile {
 public:
  /// `stress_gears` (the pair's MeshPairSetup::gears when the run has root stresses, else empty):
  /// each line ends with each gear's largest tensile and compressive root stress of the position,
  /// each followed by where it is: sigma_t_<gear>_MPa, sigma_t_<gear>_tooth, sigma_t_<gear>_fillet
  /// (+ or -: the σ = ±1 side), sigma_t_<gear>_arc_mm (from the space centre line), the same for
  /// sigma_c_<gear>.
  /// @throws std::runtime_error naming the file if it cannot be written.
  /// `slices` > 1 (slices of the face width): each line ends with the position's K_Hbeta and
  /// largest_z_mm (the centre of its most loaded slice).
  MeshStiffnessFile(const std::string& path, const nlohmann::json& provenance, double face_width,
                    const std::vector<std::string>& stress_gears = {}, int slices = 1);
  void Write(const transmission::MeshSample& s);
  void Close();

 private:
  CsvFile csv_;
  double face_width_;
  int bodies_ = 0;  // root-stress columns: one group per gear, 0 without
  bool faces_ = false;  // face-load columns
};

/// The console summary of `epicycle stiffness`: mean and peak single-pair stiffness beside ISO
/// 6336-1's c_γα and c′ with their ratios, the range and contact ratio (or that no position
/// converged), the failed positions, and with root stresses RootStressText against the gear-1
/// rotation [deg].
std::string MeshStiffnessText(const transmission::StiffnessRecord& record);

/// The mesh stiffness and each tooth pair's stiffness over the cycle per unit face width
/// `face_width` [m] (N/(mm µm) against gear 1's rotation in degrees), the converged positions
/// only, with horizontal references `references` [N/(mm µm)] (ISO 6336's c_γα and c′), as SVG.
void WriteMeshStiffnessPlot(const std::string& path, const std::string& title,
                            const transmission::MeshStiffnessResult& result, double face_width,
                            std::vector<double> references);

}  // namespace epicycle::report
