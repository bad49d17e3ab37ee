// The geometry report of a scene as JSON (`epicycle geometry --json`; keys in docs/geometry.md):
// each gear's generated data, each mesh's operating data, the assembly of a stage and the profile
// shifts fitted to a backlash. Lengths in millimetres, angles in degrees, as the keys say.
#pragma once

#include <nlohmann/json.hpp>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::report {

/// One gear: teeth, module, radii, thickness, undercut, relief, pitch deviations, generation.
nlohmann::json GearJson(const geometry::Gear& gear);
/// One mesh: centre distance, pressure angles, backlash, contact ratios, SAP, phase.
nlohmann::json MeshJson(const geometry::MeshSummary& mesh);
/// The report of a gear-pair scene: "scene", "source", "gears", "gear_order", "meshes", "fits".
nlohmann::json PairJson(const transmission::Scene& scene, const geometry::GearPair& pair);
/// A helical stage's "helical" section (docs/geometry.md, "Helical gears"): each gear's normal and
/// transverse quantities, each mesh's α_wt, β_w, ε_α, ε_β, ε_γ, the axial forces of the scene's
/// torque shared equally and each planet's tilting moment (geometry::AxialLoads).
nlohmann::json HelicalStageJson(const transmission::Scene& scene, const geometry::Stage& stage);
/// The report of a stage scene: the same keys and "assembly" (carrier radius, planets); a helical
/// scene adds "helical" (HelicalStageJson; a pair: its gears and mesh).
nlohmann::json StageJson(const transmission::Scene& scene, const geometry::Stage& stage);

}  // namespace epicycle::report
