// Warnings computed from results: values the model computed but that lie outside its validity
// (docs/scenes.md, "Ranges and validity"). The scene's own warnings (errors against the backlash,
// contact ratio) are in Scene::warnings; these complement them with what only a solution shows.
#pragma once

#include <string>
#include <vector>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace epicycle::transmission {

/// One message per kind of violation over the converged positions of a quasi-static sweep, each
/// with the number of positions and the worst value:
///  - a negative load-sharing ratio LSR_i < 0: planet i is jammed (its errors exceed the backlash
///    and it is driven backwards);
///  - a transmission error |TE| r_b,sun larger than a tenth of the module: rigid rotations of that
///    size break the small-displacement assumption of the compliance (docs/model.md §5);
///  - a contact force past the local term's validity, F > ValidityLimitForce (the Hertz
///    half-width L exceeds the joining depth h, solvers/local_term.hpp).
std::vector<std::string> QuasiStaticWarnings(const geometry::Stage& stage,
                                             const std::vector<PositionResult>& results);

/// The same over the converged samples of a mesh-stiffness sweep (`epicycle stiffness`):
///  - a transmission error |θ₁| r_b1 (the mesh deflection δ_LOA) larger than a tenth of gear 1's
///    module m₁ (the small-displacement assumption, docs/model.md §5);
///  - a contact force past the local term's validity (MeshSample::local_validity_ratio > 1).
std::vector<std::string> MeshStiffnessWarnings(const geometry::GearPair& pair,
                                               const MeshStiffnessResult& result);

}  // namespace epicycle::transmission
