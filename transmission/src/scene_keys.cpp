#include "epicycle/transmission/scene_keys.hpp"

#include <sstream>
#include <vector>

#include <toml++/toml.h>

namespace epicycle::transmission {

SceneKeyKind FindSceneKey(const Scene& scene, const std::string& path) {
  if (scene.text.empty() || path.empty()) return SceneKeyKind::kAbsent;
  toml::table root;
  try {
    root = toml::parse(scene.text);
  } catch (const toml::parse_error&) {
    return SceneKeyKind::kAbsent;  // ReadScene parsed it: only a scene made in code gets here
  }
  std::vector<std::string> segments;
  std::stringstream in(path);
  for (std::string s; std::getline(in, s, '.');) segments.push_back(s);
  const toml::node* node = &root;
  for (const std::string& s : segments) {
    if (s.empty() || node == nullptr) return SceneKeyKind::kAbsent;
    if (const toml::table* t = node->as_table()) {
      node = t->get(s);
    } else if (const toml::array* a = node->as_array()) {
      const toml::node* found = nullptr;
      for (const toml::node& e : *a)
        if (const toml::table* entry = e.as_table())
          if (const auto gear = (*entry)["gear"].value<std::string>(); gear && *gear == s) found = &e;
      node = found;
    } else {
      return SceneKeyKind::kAbsent;
    }
  }
  if (node == nullptr) return SceneKeyKind::kAbsent;
  return node->is_integer() || node->is_floating_point() ? SceneKeyKind::kNumber
                                                         : SceneKeyKind::kOther;
}

}  // namespace epicycle::transmission
