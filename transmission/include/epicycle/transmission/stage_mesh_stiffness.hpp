// The mean stiffness of a stage's meshes from its own quasi-static solutions (docs/model.md §10,
// "Mesh stiffness of a sliced mesh"): what the dynamic model's mesh damping and the modes take
// for a helical stage, whose meshes the gear-pair driver does not resolve in turned slices.
//
// At a converged position, a mesh's loaded contacts A carry F_m = Σ_A g_j F_j (the mesh's moment
// on the planet over r_b,planet), g_j = |lever_j|/r_b,planet the contact's share of the mesh's
// approach along its transverse line of action (1 on the line of action). The stiffness is the
// gear pair's at that force (mesh_stiffness.hpp: F over the approach, and its tangent): the mesh
// alone, its own block C_AA of the compliance (the other meshes' loads left out) and its local
// terms u_j, at the stage's relative poses (its contacts' rigid overlaps δ0_A, which hold their
// unloaded gaps) moved by s along the line of action so as to carry F_m:
//   C_AA F + u(F) = δ0_A + g s,  gᵀF = F_m       (Newton from the stage's F_A and s = 0),
//   Δ = max_j δ0_j/g_j + s  (the approach from where the mesh's first contact touches),
//   secant   k_s = F_m/Δ,
//   tangent  k_t = dF_m/dΔ = gᵀ (C_AA + diag u'_j(F_j))⁻¹ g.
// For a mesh in slices every slice's contact is a row of A: k is the sum over the slices with
// their coupling.
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
  double approach = 0; ///< Δ [m] of the pair's state at F_m (header)
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
