// The check a driver that resolves helical stages in slices makes of its scene
// (helical_slices.hpp; docs/face_width.md, "Helical meshes").
#pragma once

#include <string>

#include "epicycle/transmission/scene.hpp"

namespace epicycle::transmission {

/// A driver that resolves a helical stage in slices of the face width (helical_slices.hpp)
/// refuses a helical scene with fewer than two slices, before its tables are built.
/// @throws std::invalid_argument naming face_width.slices (or the helix key when the scene has
///         no [face_width]), its value and the rule.
void RequireHelicalSlices(const Scene& scene, const std::string& driver);

}  // namespace epicycle::transmission
