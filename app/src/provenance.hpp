// What every result file of the `epicycle` program says about its origin, and the program's exit
// rules: 0 when everything asked for was computed, 1 when a computation failed (its results are
// still written and the failures listed), 2 for bad input or usage.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace epicycle::transmission {
struct Scene;
}

namespace epicycle::app {

/// Thrown when what the user asked for could not be computed (a failed contact solve, failed
/// sweep positions). main() prints it and exits with status 1.
class ComputationFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// {"program": "epicycle", "version": "<--version>", "backend": ..., "scene": file,
///  "scene_hash": "fnv1a64:<hex of the scene text>"}; scene may be null (problem files:
/// `input`/`input_hash` name the file and the hash of its text instead).
nlohmann::json Provenance(const std::string& backend, const transmission::Scene* scene);
nlohmann::json FileProvenance(const std::string& backend, const std::string& path,
                              const std::string& text_hash);

/// The same as one CSV comment line ("# epicycle 0.1.0; backend newton; scene ...; scene_hash
/// fnv1a64:..."), written first in every CSV file (pandas: comment='#').
std::string ProvenanceCsvLine(const nlohmann::json& provenance);

/// Scene warnings (Scene::warnings plus those computed from results), printed to stdout under a
/// "WARNING" heading; nothing if the list is empty.
void PrintWarnings(const std::vector<std::string>& warnings);

/// ContentHash (transmission/scene.hpp) of a file's bytes; "" if it cannot be read.
std::string FileHash(const std::string& path);

/// A number for a report or a file: the value if finite, otherwise `missing` (never nan/inf).
std::string Finite(double v, const char* format = "{:.9g}", const char* missing = "");

}  // namespace epicycle::app
