#include "epicycle/report/provenance.hpp"

#include <fstream>
#include <sstream>

#include "epicycle/config.h"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::report {

nlohmann::json Provenance(const std::string& backend, const transmission::Scene* scene) {
  nlohmann::json j;
  j["program"] = "epicycle";
  j["version"] = EPICYCLE_VERSION;
  j["backend"] = backend;
  if (scene) {
    j["scene"] = scene->source;
    j["scene_hash"] = scene->hash;
    if (!scene->damage.empty()) j["damage"] = scene->damage.Describe();  // healthy: no key
  }
  return j;
}

nlohmann::json FileProvenance(const std::string& backend, const std::string& path,
                              const std::string& text_hash) {
  nlohmann::json j = Provenance(backend, nullptr);
  j["input"] = path;
  j["input_hash"] = text_hash;
  return j;
}

std::string ProvenanceCsvLine(const nlohmann::json& p) {
  std::string line = "# epicycle " + p.value("version", std::string()) + "; backend " +
                     p.value("backend", std::string());
  for (const char* k : {"scene", "scene_hash", "input", "input_hash"}) {
    if (p.contains(k)) line += std::string("; ") + k + " " + p[k].get<std::string>();
  }
  if (p.contains("damage"))
    for (const auto& d : p["damage"]) line += "; " + d.get<std::string>();
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return line + "\n";
}

std::string FileHash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::ostringstream text;
  text << in.rdbuf();
  return transmission::ContentHash(text.str());
}

}  // namespace epicycle::report
