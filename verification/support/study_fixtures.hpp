// Study files and folders shared by the studies suite's tests.
#pragma once

#include <unistd.h>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "epicycle/studies/study.hpp"
#include "program_runs.hpp"

namespace epicycle::test {

/// A [study] table on the paper's stage (absolute scene path) followed by `rest`.
inline std::string StudyText(const std::string& study_keys, const std::string& rest) {
  return "[study]\nname = \"test\"\nscene = \"" + std::string(EPICYCLE_SCENES_DIR) +
         "/paper_stage.toml\"\n" + study_keys + "\n" + rest;
}

/// The study of tangential pin-hole errors σ = 5 µm on every planet of the paper's stage, with
/// `keys` of its [study] table ("seed = 3\nsamples = 2\npositions = 4").
inline studies::StudySpec PinStudy(const std::string& keys) {
  return studies::ParseStudy(StudyText(keys,
                                       "[[variable]]\nquantity = \"pin_tangential\"\ngear = "
                                       "\"planets\"\ndistribution = \"normal\"\nsigma_um = 5.0\n"),
                             "pins.toml", "");
}

inline std::string WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

/// The message of the std::invalid_argument that ParseStudy throws for `text` ("" if none).
inline std::string StudyError(const std::string& text) {
  try {
    studies::ParseStudy(text, "bad.toml", "");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace epicycle::test
