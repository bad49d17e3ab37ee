// The mean stiffness of a stage's meshes from its own quasi-static solutions (docs/model.md §10,
// "Mesh stiffness of a sliced mesh"): what the dynamic model's mesh damping and the modes take
// for a helical stage, whose meshes the gear-pair driver does not resolve in turned slices.
//
// At a converged position, a mesh's loaded contacts A (F_j > 0 on its drive flanks) obey
//   (C_AA F_A)_j + u_j(F_j) = g_j Δ − e_j,
// C_AA the mesh's own block of the compliance (the pair's: the other meshes' loads left out),
// u_j the local term, Δ the mesh's approach along its transverse line of action (the planet turned
// against the sun or the ring, held, by Δ/r_b,planet), g_j = |lever_j|/r_b,planet the contact's
// share of that approach (1 on the line of action) and e_j ≥ 0 its unloaded gap, 0 for the contact
// that touches first. So
//   secant   k_s = F_m/Δ,   F_m = Σ_A g_j F_j (the mesh's moment on the planet over r_b,planet),
//            Δ = max_A [(C_AA F_A)_j + u_j(F_j)]/g_j,
//   tangent  k_t = dF_m/dΔ = gᵀ (C_AA + diag u'_j(F_j))⁻¹ g   (active set held),
// the definitions of the gear-pair driver (mesh_stiffness.hpp: F = T/r_b over the approach, and
// the tangent of F over δ), read off the stage's state. For a mesh in slices every slice's contact
// is a row of A: k is the sum over the slices and their coupling.
#pragma once

#include <array>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/stage_model.hpp"

namespace epicycle::transmission {

/// One mesh's stiffness at one converged state.
struct MeshStiffnessAt {
  double secant = 0;   ///< k_s = F_m/Δ [N/m] (0: the mesh carries no load)
  double tangent = 0;  ///< k_t = dF_m/dΔ [N/m]
  double force = 0;    ///< F_m [N]
  double approach = 0; ///< Δ [m]
};

/// The stiffness (header) of planet `planet`'s sun mesh (`ring` false) or ring mesh at the
/// converged position `r` of a stage whose planets' gears are `stage`'s.
/// @throws std::invalid_argument for a position that did not converge or a planet out of range.
MeshStiffnessAt MeshStiffnessOf(const geometry::Stage& stage, const PositionResult& r, int planet,
                                bool ring);

/// The mean over a mesh cycle of planet 1's meshes' stiffnesses, {sun–planet, planet–ring}.
struct StageMeshStiffness {
  std::array<double, 2> secant{};   ///< [N/m]
  std::array<double, 2> tangent{};  ///< [N/m]
  int positions = 0;                ///< converged positions averaged [-]
};

/// StageMeshStiffness of `model` under `loads`: the quasi-static solutions at `positions` carrier
/// angles k·(2π/z_r)/positions over one mesh cycle (one thread, warm-started in order, the
/// default contact options), each mesh's MeshStiffnessOf averaged over the converged ones.
/// @throws std::invalid_argument for positions < 2; std::runtime_error if no position converges.
StageMeshStiffness ComputeStageMeshStiffness(const StageModel& model, const StageLoads& loads,
                                             int positions = 24);

}  // namespace epicycle::transmission
