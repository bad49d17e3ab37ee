// What the scene reader's parts share (transmission/src/scene*.cpp): the number format of its
// messages, its unit factors and the readers of the scene's sections that live in their own files.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "epicycle/io/number_format.hpp"
#include "epicycle/io/toml_reader.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::transmission::internal {

using io::Rule;
using io::TableReader;

inline constexpr double kMm = 1e-3, kUm = 1e-6;

/// "file:line: path = value" of a key the scene's text holds (a toml++ path:
/// "model.join_depth_mm"), for a message about a value only a later stage can check (the text is
/// parsed again on that error path only); "" if the scene has no text or not that key.
std::string KeyAt(const Scene& scene, const std::string& path);

/// The gear a table's `gear` key names among `gears` (its name into *name): the spec.
/// @throws std::invalid_argument naming the key, the value and the names allowed.
const geometry::GearSpec& NamedGear(
    TableReader& t, const std::vector<std::pair<std::string, const geometry::GearSpec*>>& gears,
    std::string* name);

/// A gear's table (scene_gear.cpp; docs/scenes.md, "Helical gears" and after): teeth, module,
/// pressure angle, shift, radii, flank modifications, pitch deviations and helix, the inertia into
/// *inertia; a `fit_target` gear may omit profile_shift (a [[fit]] sets it); `helix` the stage's
/// [helix] table's (then the gear's table may not name one). @throws std::invalid_argument naming
/// the key, value and rule.
geometry::GearSpec ReadGear(TableReader& t, const std::string& name, geometry::GearKind kind,
                            bool fit_target, Inertia* inertia,
                            std::vector<std::string>* warnings = nullptr,
                            const std::optional<geometry::Helix>& helix = std::nullopt);

/// A member's mass_kg and inertia_kgm2 (both >= 0, 0 when absent).
Inertia ReadInertia(TableReader& t);

/// The helix angle's rule: [0, 45) deg at the reference cylinder.
extern const Rule kHelixRule;

/// "left" or "right" (a name the reader has checked) as the hand.
geometry::Hand HandFromName(const std::string& name);

/// The scene's [[damage.pit]] and [[damage.crack]] tables (docs/scenes.md, "Damage"): `gears`
/// names the gears a damage may be on with the spec of each (a stage's planets share one spec),
/// read once the radii are final. @throws std::invalid_argument naming the key, value and rule.
void ReadDamage(TableReader& top, Scene& s,
                const std::vector<std::pair<std::string, const geometry::GearSpec*>>& gears);

/// The scene's [face_width] table (docs/scenes.md, "Face width"), read once the radii and the
/// gap window are final; `gears` as ReadDamage's. @throws std::invalid_argument naming the key,
/// value and rule.
void ReadFaceWidth(TableReader& top, Scene& s,
                   const std::vector<std::pair<std::string, const geometry::GearSpec*>>& gears);

/// The [face_width] table's [[face_width.pin]] array (scene_pin.cpp), read after its slices.
/// @throws std::invalid_argument naming the key, value and rule.
void ReadPins(TableReader& face_width, Scene& s);

}  // namespace epicycle::transmission::internal
