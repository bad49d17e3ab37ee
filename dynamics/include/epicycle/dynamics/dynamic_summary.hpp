// Domain results of a dynamic run, computed here (not in app/) so that studies and tests share
// them: load-sharing extremes and K_γ, transmission-error peak to peak, the sun's orbit.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "epicycle/transmission/accumulator.hpp"
#include "epicycle/transmission/validity.hpp"

namespace epicycle::dynamics {

/// Statistics over the output steps of a run (transmission::Accumulator: with no step every
/// statistic is NaN and the per-planet lists are empty).
struct DynamicSummary {
  int samples = 0;                                 ///< output steps summarised [-]
  std::vector<double> lsr_min, lsr_max, lsr_mean;  ///< per planet [-]
  double k_gamma = 0;                              ///< max over steps of max(0, max_i n·LSR_i) [-]
  double te_min = 0, te_max = 0;                   ///< dynamic transmission error [rad]
  double te_peak_to_peak() const { return te_max - te_min; }  ///< [rad]
  double orbit_radius = 0;       ///< largest |sun centre − nominal| [m]
  double orbit_mean_radius = 0;  ///< mean |sun centre − nominal| [m]
  double max_pair_force = 0;     ///< largest tooth-pair normal force (with damping), ≥ 0 [N]
  /// Per body, when the samples carry root stresses (else empty): extremes with their time [s]
  /// (RootStressSummary's x) and the largest range at one fillet point.
  std::vector<transmission::RootStressSummary> root_stress;
  /// With slices of the face width (DynamicSample::face_loads), per mesh over the steps: K_Hβ's
  /// largest and mean, the carrier angle and z of the largest, and the largest L_i·K_Hβ with
  /// L_i = n·LSR_i of the same step (transmission::MeshFaceSummary); else empty.
  std::vector<transmission::MeshFaceSummary> face_width;
  /// A helical stage: the means over the steps of DynamicSample::helical (the quasi-static
  /// record's `helical` object); no planets for a spur stage.
  transmission::HelicalLoads helical_mean;
};

/// The statistics of a run gathered one output step at a time, in the order of the steps (the
/// means are sums in that order): what it keeps does not grow with the steps, so a long run need
/// not keep its samples (SimulationOptions::keep_samples). The number of planets is that of the
/// first step's LSR list.
class DynamicAccumulator {
 public:
  /// @throws std::invalid_argument if a step has not the first step's number of LSR values.
  void Add(const DynamicSample& x);
  DynamicSummary Result() const;

 private:
  int samples_ = 0;
  std::vector<transmission::Accumulator> lsr_;
  transmission::Accumulator te_, orbit_, k_gamma_, pair_force_;
  std::optional<transmission::RootStressTracker> root_stress_;
  transmission::FaceLoadTracker faces_;
  transmission::HelicalLoads helical_sum_;
  int helical_steps_ = 0;
};

/// Summary of the samples: DynamicAccumulator over them.
DynamicSummary Summarise(const std::vector<DynamicSample>& samples);

/// DynamicWarnings gathered one output step at a time (same messages).
class DynamicWarningTally {
 public:
  explicit DynamicWarningTally(const geometry::Stage& stage);
  void Add(const DynamicSample& x);
  std::vector<std::string> Messages() const { return tally_.Messages(); }

 private:
  transmission::ValidityTally tally_;
};

/// The result warnings of the quasi-static driver (transmission::ValidityTally: a jammed planet,
/// a rotation past a tenth of the module, a contact force past the local term's validity) over
/// the output steps whose contact solve converged, counted in output steps; the forces checked
/// are the elastic contact forces F of the contact problem. DynamicWarningTally over the samples.
std::vector<std::string> DynamicWarnings(const geometry::Stage& stage,
                                         const std::vector<DynamicSample>& samples);

}  // namespace epicycle::dynamics
