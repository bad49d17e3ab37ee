#include "provenance.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "epicycle/config.h"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::app {

nlohmann::json Provenance(const std::string& backend, const transmission::Scene* scene) {
  nlohmann::json j;
  j["program"] = "epicycle";
  j["version"] = EPICYCLE_VERSION;
  j["backend"] = backend;
  if (scene) {
    j["scene"] = scene->source;
    j["scene_hash"] = scene->hash;
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
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return line + "\n";
}

void PrintWarnings(const std::vector<std::string>& warnings) {
  if (warnings.empty()) return;
  std::printf(
      "\nWARNING: %zu value(s) outside the model's validity (results computed, read with "
      "care):\n",
      warnings.size());
  for (const std::string& w : warnings) std::printf("  warning: %s\n", w.c_str());
}

std::string FileHash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::ostringstream text;
  text << in.rdbuf();
  return transmission::ContentHash(text.str());
}

std::string Finite(double v, const char* format, const char* missing) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string(missing);
}

}  // namespace epicycle::app
