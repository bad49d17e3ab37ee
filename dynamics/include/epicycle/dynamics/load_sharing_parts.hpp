// Why the planets' shares of the load differ at one output step: the deviation of each planet's
// load-sharing ratio from the ideal, LSR_i − 1/n (LSR_i of eq. 4, DynamicSample::load_sharing),
// split into parts that sum to it sample by sample (docs/dynamic.md, "Why a floating sun's
// shares differ").
//
// Notation (per planet i, all at the sample's poses): τ = −T_in (so that LSR_i = T_i/τ, T_i the
// moment on the sun of sun–planet i's contacts, Evaluation::sun_mesh_torque); F_i = Σ_j F_j the
// normal forces (with damping) of the mesh's contacts; u_i the unit direction of the force on the
// sun of a contact on the mesh's line of action (the crossed tangent of the sun's and planet i's
// base circles about their geometric centres, the one the contacts load); ℓ_i = the moment about
// the sun's rotation centre of a unit force along that line. Exactly, per planet,
//
//   T_i = ℓ_i F_i + M_off,i + M_fric,i,
//     M_off,i  = Σ_j −F_j (p_j − c_s) × n_j − ℓ_i F_i   (normal forces off the line: tip rounds,
//                                                        coast flanks),
//     M_fric,i = T_i − Σ_j −F_j (p_j − c_s) × n_j       (the friction forces' moment),
//
// and the sun's balances are (θ̈ and a the sun's rotational and translational accelerations)
//
//   J_s θ̈_s = T_in + Σ_i T_i,            m_s a_s = Σ_i F_i u_i + f_off + f_fric + f_bearing,
//
// f_off the off-line normal forces' resultant beyond Σ F_i u_i, f_fric the friction forces' and
// f_bearing the bearing's (a fixed sun: the reaction −(net mesh force); an elastic sun: its
// spring and damper; floating: 0). With A = [u_1 … u_n; 1 … 1] (3 × n) and A⁺ its pseudo-inverse
// (A⁻¹ for n = 3, where the sun's balance fixes the three forces), F − F̄ splits linearly into
//   A⁺[m_s a_s; 0] (the sun's inertial force), −A⁺[f_bearing; 0], −A⁺[f_fric; 0], −A⁺[f_off; 0],
//   and what remains (the lines of action not 120° apart: run-out, the sun's displacement; for
//   n ≠ 3 also the share the sun's balance leaves to the meshes' stiffness).
// Then, with ℓ̄ the planets' mean lever (ℓ_i = ℓ̄ for a sun without run-out),
//
//   LSR_i − 1/n = J_s θ̈_s/(n τ)                                         sun_rotation
//               + ℓ̄ (A⁺[m_s a_s; 0])_i / τ                              sun_translation
//               − ℓ̄ (A⁺[f_bearing; 0])_i / τ                            bearing
//               + ((M_fric,i − M̄_fric) − ℓ̄ (A⁺[f_fric; 0])_i) / τ      friction
//               + ((M_off,i − M̄_off) − ℓ̄ (A⁺[f_off; 0])_i) / τ         off_line
//               + geometry_i + residual_i,
//
// geometry_i = (ℓ̄ (F_i − F̄ − the force parts above) + (ℓ_i − ℓ̄) F_i − mean_k((ℓ_k − ℓ̄) F_k))/τ.
// θ̈_s is the integrator's interpolant (DynamicSample::sun_acceleration), m_s a_s the equation of
// motion's (Evaluation::acceleration: the sample does not carry the interpolant's translation),
// so residual_i = J_s (θ̈_EoM − θ̈_interp)/(n τ) = sun_torque_balance/(n τ) up to round-off,
// the same for every planet: the interpolant's and the solver's error.
#pragma once

#include <vector>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/simulation.hpp"

namespace epicycle::dynamics {

/// The parts of LSR_i − 1/n at one sample (above), each per planet [-].
struct LoadSharingParts {
  std::vector<double> deviation;        ///< LSR_i − 1/n
  /// The sun's inertial moment J_s θ̈_s and force m_s a_s: the net moment and force on the sun,
  /// i.e. its departure from the quasi-static equilibrium, whatever moves it (its ringing at its
  /// own modes included). Not the share its mass causes: they do not scale with it
  /// (docs/dynamic.md, "What the two sun parts are, and are not").
  std::vector<double> sun_rotation;     ///< J_s θ̈_s part
  std::vector<double> sun_translation;  ///< m_s a_s part
  std::vector<double> bearing;          ///< the sun's bearing (fixed or elastic sun; else 0)
  std::vector<double> friction;         ///< friction's moment and force (exactly 0 without friction)
  std::vector<double> off_line;         ///< normal forces off the lines of action
  std::vector<double> geometry;         ///< lines of action not equally spaced (see above)
  std::vector<double> residual;         ///< deviation − Σ parts (the interpolant's error)
};

/// Names of the parts in the order of Part(), for tables and file columns.
inline constexpr const char* kLoadSharingPartNames[] = {
    "sun_rotation", "sun_translation", "bearing", "friction", "off_line", "geometry", "residual"};
inline constexpr int kLoadSharingPartCount = 7;
/// Part k (0 … kLoadSharingPartCount − 1, the order of kLoadSharingPartNames).
/// @throws std::invalid_argument for k outside that range.
const std::vector<double>& Part(const LoadSharingParts& parts, int k);

/// The parts of `sample` (an output of Simulate with `model`). All zero for a sample without input
/// torque or sun–planet load.
/// @throws std::invalid_argument if the sample's sizes do not match the model.
LoadSharingParts DecomposeLoadSharing(const DynamicModel& model, const DynamicSample& sample);

}  // namespace epicycle::dynamics
