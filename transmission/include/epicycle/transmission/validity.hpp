// Warnings computed from results: values the model computed but that lie outside its validity
// (docs/scenes.md, "Ranges and validity"). The scene's own warnings (errors against the backlash,
// contact ratio) are in Scene::warnings; these complement them with what only a solution shows.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace epicycle::transmission {

/// The checks behind QuasiStaticWarnings, one computed state at a time, so that every driver (a
/// sweep's converged positions, a dynamic run's output steps) applies the same rules and says them
/// in the same words:
///  - a negative load-sharing ratio LSR_i < 0: planet i is jammed (its errors exceed the backlash
///    and it is driven through its coast flanks);
///  - every LSR_i = 0 at once: the sun has lost contact with every planet (in motion, the teeth
///    separate and impact: rattle), so the shares and K_γ say nothing about load sharing;
///  - a transmission error |TE| r_b,sun larger than a tenth of the module: rigid rotations of that
///    size break the small-displacement assumption of the compliance (docs/model.md §4);
///  - a contact force past the local term's validity, F > ValidityLimitForce (the Hertz
///    half-width L exceeds the joining depth h, solvers/local_term.hpp).
class ValidityTally {
 public:
  /// `counted`: what a state is called in the messages ("position(s)", "output step(s)").
  ValidityTally(const geometry::Stage& stage, std::string counted);
  /// One state: the carrier angle [rad], LSR per planet [-], the transmission error at the sun
  /// [rad] (not finite: not checked), the contact forces F [N] with their local-term parameters
  /// (`local` empty: no local terms, forces not checked).
  void Add(double carrier_angle, const std::vector<double>& load_sharing, double transmission_error,
           const std::vector<solvers::LocalTermParameters>& local, const Eigen::VectorXd& force);
  /// One position of a quasi-static sweep: its state if it converged, nothing otherwise.
  void Add(const PositionResult& r);
  /// One message per kind of violation seen, with the number of states (contacts for the local
  /// term) and the worst value; empty when everything was within validity.
  std::vector<std::string> Messages() const;

 private:
  int planets_;
  double te_limit_;  ///< a tenth of the module along the sun's line of action [rad]
  std::string counted_;
  std::vector<int> lsr_count_;
  std::vector<double> lsr_worst_, lsr_at_;
  int te_count_ = 0, local_count_ = 0, free_count_ = 0;
  double free_at_ = 0;  ///< the first carrier angle where the sun touched no planet [rad]
  double te_worst_ = 0, local_worst_ratio_ = 0, local_worst_force_ = 0;
};

/// ValidityTally's messages over the converged positions of a quasi-static sweep.
std::vector<std::string> QuasiStaticWarnings(const geometry::Stage& stage,
                                             const std::vector<PositionResult>& results);

/// The same over the converged samples of a mesh-stiffness sweep (`epicycle stiffness`):
///  - a transmission error |θ₁| r_b1 (the mesh deflection δ_LOA) larger than a tenth of gear 1's
///    module m₁ (the small-displacement assumption, docs/model.md §4);
///  - a contact force past the local term's validity (MeshSample::local_validity_ratio > 1).
std::vector<std::string> MeshStiffnessWarnings(const geometry::GearPair& pair,
                                               const MeshStiffnessResult& result);

}  // namespace epicycle::transmission
