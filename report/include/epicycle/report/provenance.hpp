// What every result file says about its origin: the program and its version, the contact back
// end, and the input (a scene, or other files) with the hash of its text.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace epicycle::transmission {
struct Scene;
}

namespace epicycle::report {

/// {"program": "epicycle", "version": "<--version>", "backend": ..., "scene": file,
///  "scene_hash": "fnv1a64:<hex of the scene text>"}; scene may be null (problem files:
/// `input`/`input_hash` name the file and the hash of its text instead).
nlohmann::json Provenance(const std::string& backend, const transmission::Scene* scene);
nlohmann::json FileProvenance(const std::string& backend, const std::string& path,
                              const std::string& text_hash);

/// The same as one CSV comment line ("# epicycle 0.1.0; backend newton; scene ...; scene_hash
/// fnv1a64:..."), written first in every CSV file (pandas: comment='#'); ends in "\n".
std::string ProvenanceCsvLine(const nlohmann::json& provenance);

/// ContentHash (transmission/scene.hpp) of a file's bytes; "" if it cannot be read.
std::string FileHash(const std::string& path);

}  // namespace epicycle::report
