// Replays fuzz inputs through the harnesses without libFuzzer, deterministically: every file of
// the given directories (recursively) or files; files under a "study" or "studies" folder and
// files named study_*.toml go to the study-file harness, files under an "options" folder to the
// command-line harness, other *.toml and files under a "scene" folder to the scene harness,
// *.json and files under a "contact" folder to the contact-problem harness. A finding aborts (the test fails); otherwise prints how many inputs of each kind ran.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "harness.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const fs::path p(argv[i]);
    if (fs::is_directory(p)) {
      for (const auto& e : fs::recursive_directory_iterator(p))
        if (e.is_regular_file()) files.push_back(e.path());
    } else if (fs::is_regular_file(p)) {
      files.push_back(p);
    } else {
      std::fprintf(stderr, "replay: %s: no such file or directory\n", argv[i]);
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  int scenes = 0, problems = 0, studies = 0, options = 0;
  for (const fs::path& f : files) {
    const std::string s = f.string();
    const bool option = s.find("/options/") != std::string::npos;
    const bool study = !option && (s.find("/study/") != std::string::npos ||
                       s.find("/studies/") != std::string::npos ||
                       (f.extension() == ".toml" && f.filename().string().rfind("study_", 0) == 0));
    const bool scene =
        !option && !study && (f.extension() == ".toml" || s.find("/scene/") != std::string::npos);
    const bool contact =
        !option && (f.extension() == ".json" || s.find("/contact/") != std::string::npos);
    if (!option && !study && !scene && !contact) continue;
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    if (option) {
      epicycle::fuzz::FuzzOptions(data, bytes.size());
      ++options;
    } else if (study) {
      epicycle::fuzz::FuzzStudy(data, bytes.size());
      ++studies;
    } else if (scene) {
      epicycle::fuzz::FuzzScene(data, bytes.size());
      ++scenes;
    } else {
      epicycle::fuzz::FuzzContactProblem(data, bytes.size());
      ++problems;
    }
  }
  std::printf(
      "replayed %d scene inputs, %d contact-problem inputs, %d study-file inputs and %d command "
      "lines without a finding\n",
      scenes, problems, studies, options);
  if (scenes + problems + studies + options == 0) {
    std::fprintf(stderr, "replay: no input found\n");
    return 2;
  }
  return 0;
}
