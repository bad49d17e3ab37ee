// The scene's stage and gear pairs, with the geometry's complaints told in the scene's terms
// (MakeStage, MakePair): the geometry names its own quantities ("sun.tip_radius_mm = 47.8: ...",
// "stage.planet_angles_deg[2] = ..."), which the user may not have written (an addendum
// coefficient gives the tip radius; a thickness error makes the root rounding too large). Only
// the error path parses the text again; building a stage costs what it did.
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "epicycle/geometry/plane.hpp"

#include "epicycle/transmission/helical_scene.hpp"
#include "epicycle/transmission/scene.hpp"
#include "scene_internal.hpp"

namespace epicycle::transmission {

namespace {

// The keys that may stand behind a quantity the geometry names (its owner's table first).
std::vector<std::string> Candidates(const std::string& owner, const std::string& key) {
  // Planet i's gear is made from [planet] (its errors aside).
  const std::string table = owner.rfind("planet", 0) == 0 ? "planet" : owner;
  if (owner == "stage") {
    if (key.rfind("planet_angles_deg", 0) == 0) return {"carrier." + key, "carrier"};
    if (key == "planets") return {"carrier.planets", "carrier"};
    if (key == "carrier_radius_mm") return {"carrier.radius_mm", "carrier"};
    return {"carrier"};
  }
  std::vector<std::string> c{table + "." + key};
  const auto tail = [&](const char* prefix) {
    return key.rfind(prefix, 0) == 0 ? key.substr(std::char_traits<char>::length(prefix)) : "";
  };
  if (key == "tip_radius_mm") c.push_back(table + ".addendum_per_module");
  if (key == "root_radius_mm") {
    c.push_back(table + ".dedendum_per_module");
    c.push_back(table + ".cutter.dedendum_per_module");
  }
  if (key == "root_round_radius_mm") c.push_back(table + ".cutter.root_round_radius_mm");
  if (const std::string t = tail("shaper."); !t.empty()) c.push_back(table + ".cutter." + t);
  if (const std::string t = tail("cutter."); !t.empty()) c.push_back(table + ".cutter." + t);
  c.push_back(table);
  return c;
}

// "source:line" of a key path in the scene's text (toml++ paths: "a.b[2].c"), empty if absent.
std::string Line(const toml::table& root, const std::string& source, const std::string& path,
                 std::string* value) {
  const toml::node* n = root.at_path(path).node();
  if (n == nullptr) return "";
  if (value != nullptr && !n->is_table() && !n->is_array()) {
    std::ostringstream o;
    o << toml::node_view<const toml::node>(n);
    *value = o.str();
  }
  return source + ":" + std::to_string(n->source().begin.line);
}

// The [[errors.<kind>]] entries of the scene's text for `owner` (every entry when no entry names
// it): "file:line: errors.thickness[0] (gear = "ring")".
std::vector<std::string> ErrorEntries(const toml::table& root, const std::string& source,
                                      const std::string& owner) {
  std::vector<std::string> all, own;
  const toml::table* errors = root["errors"].as_table();
  if (errors == nullptr) return all;
  for (const auto& [kind, node] : *errors) {
    const toml::array* entries = node.as_array();
    if (entries == nullptr) continue;
    for (std::size_t i = 0; i < entries->size(); ++i) {
      const toml::table* e = entries->get(i)->as_table();
      if (e == nullptr) continue;
      const std::string gear = (*e)["gear"].value_or(std::string());
      const std::string text = source + ":" + std::to_string(e->source().begin.line) +
                               ": errors." + std::string(kind.str()) + "[" +
                               std::to_string(i) + "] (gear = \"" + gear + "\")";
      all.push_back(text);
      if (gear == owner || (gear == "planets" && owner.rfind("planet", 0) == 0)) {
        own.push_back(text);
      }
    }
  }
  return own.empty() ? all : own;
}

// The geometry's message in the scene's terms (see MakeStage). `error_free` says whether the
// same geometry without the scene's errors builds.
std::string Reword(const Scene& scene, const std::string& message, bool error_free) {
  if (scene.text.empty() || message.rfind(scene.source + ":", 0) == 0) return message;
  const std::size_t dot = message.find('.'), eq = message.find(" = ");
  if (dot == std::string::npos || eq == std::string::npos || dot > eq) return message;
  const std::string owner = message.substr(0, dot), key = message.substr(dot + 1, eq - dot - 1);
  if (owner.find(' ') != std::string::npos || key.find(' ') != std::string::npos) return message;
  toml::table root;
  try {
    root = toml::parse(scene.text, scene.source);
  } catch (const toml::parse_error&) {
    return message;  // not the text the scene was read from
  }
  if (error_free) {
    std::string entries;
    for (const std::string& e : ErrorEntries(root, scene.source, owner))
      entries += (entries.empty() ? "" : "; ") + e;
    if (!entries.empty())
      return entries + ": with this error the geometry fails (it builds without the scene's "
                       "errors): " +
             message;
  }
  // toml++ writes array elements as key[i]; the geometry does too.
  for (const std::string& path : Candidates(owner, key)) {
    std::string value;
    const std::string where = Line(root, scene.source, path, &value);
    if (where.empty()) continue;
    if (path == owner + "." + key) return where + ": " + message;
    // The same quantity under the scene's name (stage.planet_angles_deg[2] is
    // carrier.planet_angles_deg[2]): the scene's name, the geometry's words.
    if (path.size() > key.size() && path.compare(path.size() - key.size(), key.size(), key) == 0)
      return where + ": " + path + message.substr(eq);
    if (value.empty()) return where + ": [" + path + "]: " + message;
    return where + ": " + path + " = " + value + " gives " + message;
  }
  return message;
}

}  // namespace

std::string internal::KeyAt(const Scene& scene, const std::string& path) {
  if (scene.text.empty()) return "";
  try {
    const toml::table root = toml::parse(scene.text, scene.source);
    std::string value;
    const std::string where = Line(root, scene.source, path, &value);
    return where.empty() ? "" : where + ": " + path + " = " + value;
  } catch (const toml::parse_error&) {
    return "";  // not the text the scene was read from
  }
}

namespace {

// A copy of the stage without any manufacturing or assembly error.
geometry::StageSpec ErrorFree(geometry::StageSpec s) {
  s.pin_errors.clear();
  s.planet_runouts.clear();
  s.planet_thickness_errors.clear();
  s.sun_runout = s.ring_runout = geometry::Runout{};
  for (geometry::GearSpec* g : {&s.sun, &s.planet, &s.ring}) g->thickness_error = 0;
  return s;
}

bool HasErrors(const geometry::StageSpec& s) {
  return !s.pin_errors.empty() || !s.planet_runouts.empty() || !s.planet_thickness_errors.empty() ||
         s.sun_runout.amplitude != 0 || s.ring_runout.amplitude != 0 ||
         s.sun.thickness_error != 0 || s.planet.thickness_error != 0 ||
         s.ring.thickness_error != 0;
}

}  // namespace

bool IsHelical(const Scene& scene) {
  const auto helical = [](const geometry::GearSpec& g) { return g.helix.helical(); };
  return scene.kind == SceneKind::kPair
             ? helical(scene.pair.gear1) || helical(scene.pair.gear2)
             : helical(scene.stage.sun) || helical(scene.stage.planet) || helical(scene.stage.ring);
}

void RequireSpur(const Scene& scene, const std::string& driver) {
  if (!IsHelical(scene)) return;
  const double beta =
      scene.kind == SceneKind::kPair ? scene.pair.gear1.helix.angle : scene.stage.sun.helix.angle;
  std::string where;
  for (const char* path :
       {"helix.helix_angle_deg", "sun.helix_angle_deg", "planet.helix_angle_deg",
        "ring.helix_angle_deg", "gear1.helix_angle_deg", "gear2.helix_angle_deg"})
    if (where.empty()) where = internal::KeyAt(scene, path);
  if (where.empty())
    where = scene.source + ": helix_angle_deg = " + io::Num(geometry::Deg(beta), io::kInputDigits);
  throw std::invalid_argument(
      where + ": " + driver +
      " computes the planar (spur) model only and does not take a helical scene (helix_angle_deg "
      "> 0), whose contact lines cross the face width; a helical stage runs in `epicycle "
      "quasistatic`, `dynamic` (a run, a speed sweep, the periodic branch), `modes`, `study` and "
      "`stiffness` with face_width.slices >= 2 "
      "(each slice at its own section's phase, docs/face_width.md \"Helical meshes\"), and "
      "`epicycle geometry` reports it (transverse quantities, contact ratios, axial forces and "
      "tilting moments)");
}

void RequireHelicalSlices(const Scene& scene, const std::string& driver) {
  if (!IsHelical(scene) || scene.face_width.active()) return;
  // The stage's own rules (hands, assembly) before a driver's: every driver and front end
  // reports the same first error of a scene (a prebuilt rig, Python's, has met them).
  if (scene.kind == SceneKind::kStage) (void)MakeStage(scene);
  // The key's own line names it with its value; else the helix's line, and then the rule's key.
  std::string where = internal::KeyAt(scene, "face_width.slices");
  const bool at_slices = !where.empty();
  for (const char* key : {"helix.helix_angle_deg", "sun.helix_angle_deg", "gear1.helix_angle_deg"})
    if (where.empty()) where = internal::KeyAt(scene, key);
  if (where.empty()) where = scene.source;
  if (!at_slices) where += ": face_width.slices = " + std::to_string(scene.face_width.slices);
  throw std::invalid_argument(
      where + ": " + driver +
      " resolves a helical stage in slices of the face width and needs slices >= 2 (its contact "
      "lines cross the face width; add [face_width] slices = 20, docs/face_width.md)");
}

geometry::Stage MakeStage(const Scene& scene) {
  try {
    return geometry::Stage(scene.stage);
  } catch (const std::invalid_argument& e) {
    bool error_free = false;
    if (HasErrors(scene.stage)) {
      try {
        const geometry::Stage clean(ErrorFree(scene.stage));
        error_free = true;
      } catch (const std::invalid_argument&) {
      }
    }
    throw std::invalid_argument(Reword(scene, e.what(), error_free));
  }
}

geometry::GearPair MakePair(const Scene& scene, const geometry::PairSpec& spec) {
  try {
    return geometry::GearPair(spec);
  } catch (const std::invalid_argument& e) {
    bool error_free = false;
    if (spec.gear1.thickness_error != 0 || spec.gear2.thickness_error != 0) {
      geometry::PairSpec clean = spec;
      clean.gear1.thickness_error = clean.gear2.thickness_error = 0;
      try {
        const geometry::GearPair p(clean);
        error_free = true;
      } catch (const std::invalid_argument&) {
      }
    }
    throw std::invalid_argument(Reword(scene, e.what(), error_free));
  }
}

}  // namespace epicycle::transmission
