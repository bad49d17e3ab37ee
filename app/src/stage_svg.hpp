// SVG drawing of a planetary stage at one carrier position.
#pragma once

#include <string>
#include <vector>

#include "epicycle/geometry/stage.hpp"

namespace epicycle::app {

/// Tooth outlines, base circles, the loaded lines of action and the potential contacts (colour by
/// kind) at carrier angle φ_c; the drawing is in millimetres.
std::string DrawStage(const geometry::Stage& stage, double carrier_angle, double gap_window);

}  // namespace epicycle::app
