// A number of a scene named by its key path, as a front end's user names it (docs/periodic.md §3,
// "Continued scene numbers"): the table path of the scene file, dot-separated, with an entry of an
// array of tables named by its `gear` ("errors.pin.planet1.tangential_um"), e.g. to say whether a
// name a continuation was given is a key of the scene and whether it holds a number.
#pragma once

#include <string>

#include "epicycle/transmission/scene.hpp"

namespace epicycle::transmission {

enum class SceneKeyKind { kAbsent, kNumber, kOther };

/// What `path` names in the scene's text (Scene::text): kAbsent when no such key is written (or
/// the scene was made in code), kNumber for an integer or a real, kOther for anything else (a
/// string, a boolean, an array, a table). A segment after an array of tables selects the entry
/// whose `gear` is that segment.
SceneKeyKind FindSceneKey(const Scene& scene, const std::string& path);

}  // namespace epicycle::transmission
