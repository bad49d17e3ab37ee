// Scenes shared by the tests of the layers above geometry (they read scene files through
// transmission/); geometry_fixtures.hpp builds the same stages without the scene reader.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"
#include "geometry_fixtures.hpp"

namespace epicycle::test {

inline std::string SceneText(const std::string& file) {
  std::ifstream in(std::string(EPICYCLE_SCENES_DIR) + "/" + file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Replace every occurrence of `from` by `to` (the test's edit of a scene).
inline std::string Replace(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t p = text.find(from); p != std::string::npos;
       p = text.find(from, p + to.size())) {
    text.replace(p, from.size(), to);
  }
  return text;
}

inline transmission::Scene PaperScene() {
  return transmission::ParseScene(SceneText("paper_stage.toml"), "paper_stage.toml");
}

/// The paper's stage with both meshes fitted to zero backlash.
inline transmission::Scene ZeroBacklashPaperScene() {
  return transmission::ParseScene(Replace(SceneText("paper_stage.toml"),
                                          "normal_backlash_um = 150.0", "normal_backlash_um = 0.0"),
                                  "paper_stage.toml (zero backlash)");
}

}  // namespace epicycle::test
