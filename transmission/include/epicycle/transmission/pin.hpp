// A planet's pin as a load-dependent tilt (docs/model.md §10, "The planet's pin"): the planet
// turns on a bearing centred on its pin at the stage's mid-plane z = 0 and follows the slope of
// the pin's axis there. The pin takes the planet's net transverse force P [N] (the sum of its
// meshes' forces on it) and the moment M [N·m] of all its meshes' forces about its centre
// (the axial forces of helical meshes and the transverse forces at their slices' z), both in the
// plane. An Euler–Bernoulli pin of bending stiffness EI answers with the rotation of its axis at
// the bearing centre,
//   φ = c_M M + c_P (ẑ × P) s,   the axis slope t = φ × ẑ = (φ_y, −φ_x),
// that is, t = c_M (M_y, −M_x) + c_P s P:
//   - straddle (held in both carrier plates, clamped at both, the planet at mid-span of a span L):
//     c_P = 0 (the pin bows symmetrically: no slope at mid-span), c_M = L/(16 EI) (a moment at
//     the middle of a clamped–clamped beam: each half a propped cantilever of L/2 under M/2);
//   - cantilever (clamped in one plate, the bearing centre at the distance a from it):
//     c_P = a²/(2 EI), c_M = a/(EI), s = +1 when the clamped plate is at −z (the free end
//     towards +z), −1 when it is at +z;
//   - a given tilting stiffness k_tilt: c_M = 1/k_tilt, c_P = 0.
// EI = E π (D⁴ − d⁴)/64 of a pin of diameter D with a bore d. The planet's tilt adds to its
// pin's given tilt and the carrier's wind-up (face_width.hpp's t_X), and enters both of its
// meshes' gaps through n·(t_A − t_B). The quasi-static driver iterates tilt → gaps → forces →
// P, M → tilt to a fixed point per position (quasistatic.hpp).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/geometry/stage.hpp"

namespace epicycle::transmission {

struct StageContact;

/// How a pin is held in the carrier.
enum class PinMounting {
  kStiffness,   ///< a given tilting stiffness k_tilt (no slope from the force)
  kStraddle,    ///< clamped in both plates, the planet at mid-span
  kCantilever,  ///< clamped in one plate
};

/// One planet's pin (the scene's [[face_width.pin]]).
struct PinSpec {
  int planet = -1;  ///< 0-based; −1: every planet without its own entry
  PinMounting mounting = PinMounting::kStiffness;
  double tilting_stiffness = 0;  ///< k_tilt [N·m/rad], kStiffness (+∞: rigid)
  double diameter = 0;           ///< D [m], straddle or cantilever
  double bore = 0;               ///< d [m], 0 ≤ d < D
  /// Straddle: the span L between the plates [m]; cantilever: the distance a from the clamping
  /// plate to the planet's bearing centre [m].
  double length = 0;
  double youngs_modulus = 0;  ///< E [Pa]
  int clamped_side = -1;      ///< cantilever: the clamping plate at z < 0 (−1) or z > 0 (+1)
  std::string where;          ///< "file:line: face_width.pin[0]" for messages
};

/// The rotation compliances of a pin at the planet's bearing centre (header).
struct PinCompliance {
  double moment = 0;  ///< c_M [rad/(N·m)]
  double force = 0;   ///< c_P [rad/N]
  int side = 1;       ///< s [-]: the free end's direction along z (cantilever)
  bool rigid() const { return moment == 0 && force == 0; }
};

/// EI [N·m²] of a solid (bore 0) or hollow round pin.
double PinBendingStiffness(double youngs_modulus, double diameter, double bore);

/// The compliances of `pin` (header). @throws std::invalid_argument naming pin.where for a
/// stiffness not > 0 (kStiffness), or a diameter, length or modulus not > 0, a bore outside
/// [0, D).
PinCompliance PinCompliances(const PinSpec& pin);

/// What the pin carries from one planet's meshes, in the inertial frame.
struct PinLoad {
  Eigen::Vector2d force = Eigen::Vector2d::Zero();   ///< P [N], the meshes' net force on the planet
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();  ///< (M_x, M_y) [N·m] about its centre at z = 0
};

/// The pins' loads of every planet from the forces `force` [N] of the sliced contacts
/// `contacts` at `poses`: the transverse forces at their slices' z, and for a helical stage the
/// axial forces (helical_slices.hpp's HelicalLoadsOf).
std::vector<PinLoad> PinLoadsOf(const geometry::Stage& stage, const geometry::StagePoses& poses,
                                const std::vector<StageContact>& contacts,
                                const Eigen::VectorXd& force);

/// The planets' pins resolved against a stage: the compliances per planet.
class PinModel {
 public:
  PinModel() = default;
  /// @throws std::invalid_argument as PinCompliances, or for a planet the stage lacks.
  PinModel(const std::vector<PinSpec>& pins, int planets);
  /// True when some planet's pin is not rigid: the quasi-static driver iterates its tilt.
  bool active() const { return active_; }
  const PinCompliance& compliance(int planet) const { return pins_.at(static_cast<std::size_t>(planet)); }
  /// t [-] of `planet`'s axis in the inertial frame under `load` (header).
  Eigen::Vector2d Tilt(int planet, const PinLoad& load) const;

 private:
  std::vector<PinCompliance> pins_;
  bool active_ = false;
};

}  // namespace epicycle::transmission
