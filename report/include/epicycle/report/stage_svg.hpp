// SVG drawing of a planetary stage at one carrier position.
#pragma once

#include <string>
#include <vector>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"

namespace epicycle::report {

/// Tooth outlines, base circles, the loaded lines of action and the potential contacts (colour by
/// kind) at carrier angle φ_c; the drawing is in millimetres.
std::string DrawStage(const geometry::Stage& stage, double carrier_angle, double gap_window);

/// A zoom on one tooth pair of a mesh (gear A external, B external or the internal gear): the
/// generated outlines (undercut fillets as cut), the form circles (start of the active involute;
/// undercut crossings marked), the line of action, the potential contacts, and each relieved
/// flank drawn offset by its relief × `relief_scale` (the relief is a few µm). Millimetres.
std::string DrawMeshZoom(const geometry::PosedGear& a, const geometry::PosedGear& b, bool internal,
                         int loaded_side, double gap_window, double relief_scale);

/// The zoom on one tooth pair of the stage's mesh named `mesh` ("sun-planet<i>", "planet<i>-ring",
/// the names of the geometry report) at carrier angle φ_c [rad].
/// @throws std::invalid_argument naming `--zoom = mesh` when the stage has no such mesh.
std::string DrawStageMeshZoom(const geometry::Stage& stage, double carrier_angle,
                              const std::string& mesh, double gap_window, double relief_scale);

/// The same for a gear pair, whose one mesh is "gear1-gear2", at gear 1's turn [rad].
/// @throws std::invalid_argument naming `--zoom = mesh` for any other name.
std::string DrawPairMeshZoom(const geometry::GearPair& pair, double turn, const std::string& mesh,
                             double gap_window, double relief_scale);

}  // namespace epicycle::report
