// Statistics of a quasi-static sweep over carrier positions (docs/model.md §6): the load-sharing
// ratios' mean and extremes per planet, the mesh load factor K_γ, the loaded static transmission
// error's range and the sun's largest displacement. One function shared by the `quasistatic`
// command and the tolerance studies (studies/), so both report the same numbers.
#pragma once

#include <string>
#include <vector>

#include "epicycle/transmission/contact_pressure.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "epicycle/transmission/accumulator.hpp"

namespace epicycle::transmission {

class RecordVisitor;

/// The load across the face width of one mesh over a sweep (slices of the face width:
/// PositionResult::face_loads).
struct MeshFaceSummary {
  std::string mesh;           ///< "sun-planet1", "planet1-ring"
  int planet = 0;             ///< 0-based
  bool ring_mesh = false;
  double k_h_beta_max = 0;    ///< largest K_Hβ over the positions [-]
  double k_h_beta_mean = 0;   ///< mean over the positions [-]
  double carrier_angle = 0;   ///< where the largest sits [rad]
  double largest_z = 0;       ///< the slice centre z [m] of the largest line load there
  /// max over positions of L_i K_Hβ: the peak load per unit width over the ideal stage's
  /// (equal sharing, uniform face) [-], the product every rating multiplies with.
  double k_gamma_k_h_beta_max = 0;
  /// The mesh's misalignment across its face (MeshFaceLoad's, at the first converged position)
  /// [m]: f_ma (pin tilts, lead slopes) and f_sh (the carrier's wind-up).
  double misalignment_assembly = 0, misalignment_deflection = 0;
  /// With stresses (MeshFaceLoad::root_stress not empty), over the positions and slices: the
  /// largest fillet tension of the mesh's gears [Pa], which gear ("sun", "planet1", ...), its
  /// slice centre z [m] and carrier angle [rad]; the largest Hertz pressure on the line of
  /// action [Pa], its z [m] and carrier angle [rad]. stresses false: all 0.
  bool stresses = false;
  double root_stress_max = 0;
  std::string root_stress_gear;
  double root_stress_z = 0, root_stress_angle = 0;
  double hertz_pressure_max = 0;
  double hertz_pressure_z = 0, hertz_pressure_angle = 0;
};

/// The face-load statistics of every mesh (MeshFaceSummary) gathered one state at a time: the
/// quasi-static sweep's positions and the dynamic run's output steps share it.
class FaceLoadTracker {
 public:
  /// One state's face loads (FaceLoads' order), `factors` L_i = n·LSR_i per planet [-] and the
  /// state's carrier angle [rad]. The meshes are those of the first state added.
  void Add(const std::vector<MeshFaceLoad>& loads, const std::vector<double>& factors,
           double carrier_angle);
  /// Empty when no state carried face loads.
  std::vector<MeshFaceSummary> Result() const;

 private:
  std::vector<MeshFaceSummary> faces_;
  std::vector<Accumulator> mean_;
};

/// The summaries' `face_width` list of a record (its keys are the same in every driver's).
void VisitFaceWidth(RecordVisitor& visit, const std::vector<MeshFaceSummary>& faces);

/// Statistics over the converged positions of a sweep. With no converged position every
/// statistic is NaN (callers print "-" or null, never the NaN).
struct SweepSummary {
  int positions = 0;             ///< positions of the sweep [-]
  int converged = 0;             ///< of which converged [-]
  std::vector<double> lsr_mean;  ///< mean over positions of LSR_i [-], per planet
  std::vector<double> lsr_min;   ///< min over positions of LSR_i [-], per planet
  std::vector<double> lsr_max;   ///< max over positions of LSR_i [-], per planet
  double k_gamma = 0;            ///< K_γ = max over positions and planets of L_i = n·LSR_i [-]
  /// K̄_γ = max_i (mean over positions of L_i) [-]: the mesh-cycle-mean load factor, the quantity
  /// the linear load-sharing theory predicts (docs/model.md §8).
  double k_gamma_mean = 0;
  double transmission_error_min = 0;  ///< [rad]
  double transmission_error_max = 0;  ///< [rad]
  double sun_displacement_max = 0;    ///< largest |sun centre displacement| [m] (sun orbit)
  /// Friction at rest (the positions were solved with it, PositionResult::friction); the rest NaN
  /// without it or without a converged position.
  bool friction = false;
  double efficiency_mean = 0;       ///< mean over positions of η = P_out/P_in [-]
  double efficiency_min = 0;        ///< smallest η [-]
  double friction_power_mean = 0;   ///< mean over positions of P_f [W]
  double friction_iterations_mean = 0;  ///< mean geometric-and-friction iterations per position [-]
  /// Peak-to-peak loaded static transmission error [rad].
  double TransmissionErrorPeakToPeak() const {
    return transmission_error_max - transmission_error_min;
  }
  /// Smallest and largest LSR_i over planets and positions [-].
  double LsrMin() const;
  double LsrMax() const;
  /// Per body (sun, ring, planets: body order), when the results carry root stresses (else
  /// empty): the extremes over the converged positions, the carrier angles [rad] where they occur
  /// (RootStressSummary's x), and the largest range at one fillet point.
  std::vector<RootStressSummary> root_stress;
  /// With the root stresses (stresses on), the largest Hertz pressure per gear and flank side over
  /// the converged positions (x: the carrier angle [rad]); else empty.
  std::vector<FlankPressure> contact_pressure;
  /// With slices of the face width, per mesh (sun–planet meshes, then planet–ring); else empty.
  std::vector<MeshFaceSummary> face_width;
  /// A helical stage's axial forces and tilting moments, each the mean over the converged
  /// positions (helical_slices.hpp); no planets for a spur stage.
  HelicalLoads helical_mean;
  /// With pins of finite stiffness (pin.hpp; else empty): per planet, its tilt on its pin in the
  /// carrier frame (radial, tangential) [rad], the mean and the extremes over the converged
  /// positions; and the iterations of the positions (geometric and tilt together) [-].
  struct PinTiltSummary {
    double radial_mean = 0, radial_min = 0, radial_max = 0;
    double tangential_mean = 0, tangential_min = 0, tangential_max = 0;
  };
  std::vector<PinTiltSummary> pin_tilts;
  double pin_iterations_mean = 0, pin_iterations_max = 0;
};

/// The statistics of a sweep of a stage with `planets` planets gathered one position at a time,
/// in the order of the positions (the means are sums in that order): what it keeps does not grow
/// with the positions (a streamed sweep, SweepEach, needs no result after its Add).
class SweepAccumulator {
 public:
  /// @throws std::invalid_argument if planets < 1.
  explicit SweepAccumulator(int planets);
  /// One position; one that did not converge only counts.
  /// @throws std::invalid_argument if a converged result has not `planets` load-sharing ratios.
  void Add(const PositionResult& r);
  SweepSummary Result() const;

 private:
  int planets_ = 0, positions_ = 0;
  bool friction_ = false;
  std::vector<Accumulator> lsr_;
  Accumulator te_, displacement_, k_gamma_, efficiency_, friction_power_, iterations_;
  RootStressTracker root_stress_;
  ContactPressureTracker pressure_;
  FaceLoadTracker faces_;
  HelicalLoads helical_sum_;
  int helical_count_ = 0;
  std::vector<Accumulator> pin_radial_, pin_tangential_;
  Accumulator pin_iterations_;
};

/// The statistics of `results` (a sweep of a stage with `planets` planets): SweepAccumulator over
/// them; positions that did not converge are left out. @throws std::invalid_argument if planets <
/// 1 or a converged result has not `planets` load-sharing ratios.
SweepSummary SummariseSweep(const std::vector<PositionResult>& results, int planets);

}  // namespace epicycle::transmission
