// Scenes and gears shared by the geometry and transmission tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"

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

/// Every potential contact of every mesh of the stage at poses p: f(a, b, kind, contact), with a
/// and b the mesh's first and second gear (sun–planet i, or planet i–ring).
template <typename F>
void ForEachStageContact(const geometry::Stage& st, const geometry::StagePoses& p,
                         const geometry::ContactSearchOptions& opt, F&& f) {
  for (int i = 0; i < st.planets(); ++i) {
    for (geometry::MeshKind kind :
         {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
      const geometry::PosedGear a =
          kind == geometry::MeshKind::kSunPlanet ? st.Sun(p) : st.Planet(p, i);
      const geometry::PosedGear b =
          kind == geometry::MeshKind::kSunPlanet ? st.Planet(p, i) : st.Ring(p);
      for (const geometry::PotentialContact& c : st.Contacts(p, i, kind, opt)) f(a, b, kind, c);
    }
  }
}

}  // namespace epicycle::test
