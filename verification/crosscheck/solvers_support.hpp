// Shared helpers of the contact cross-check suites: the collection, the expected-failure table.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::solvers::test {

inline std::string ContactDataDir() { return std::string(EPICYCLE_TEST_DATA_DIR) + "/contact"; }

inline std::string CaseFile(const char* name) {
  std::string path = ContactDataDir();
  path.append("/").append(name).append(".json");
  return path;
}

inline std::vector<std::string> CollectionFiles() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(ContactDataDir()))
    if (e.path().extension() == ".json" && e.path().filename() != "expected_failures.json")
      files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

struct ExpectedFailure {
  std::string backend, name, kind;
};

// A deliberately small reader for expected_failures.json (flat objects of string values), so
// that the test does not share the parser it checks.
inline std::vector<ExpectedFailure> ReadExpectedFailures() {
  std::ifstream in(ContactDataDir() + "/expected_failures.json");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  auto value = [](const std::string& obj, const std::string& key) {
    const auto k = obj.find("\"" + key + "\"");
    if (k == std::string::npos) return std::string();
    const auto q1 = obj.find('"', obj.find(':', k) + 1);
    const auto q2 = obj.find('"', q1 + 1);
    return obj.substr(q1 + 1, q2 - q1 - 1);
  };
  std::vector<ExpectedFailure> out;
  const auto start = text.find("\"entries\"");
  std::size_t pos = start;
  while ((pos = text.find('{', pos)) != std::string::npos) {
    const auto end = text.find('}', pos);
    const std::string obj = text.substr(pos, end - pos);
    out.push_back({value(obj, "backend"), value(obj, "case"), value(obj, "kind")});
    pos = end;
  }
  return out;
}

inline bool Matches(const std::string& pattern, const std::string& s) {
  if (!pattern.empty() && pattern.back() == '*')
    return s.compare(0, pattern.size() - 1, pattern, 0, pattern.size() - 1) == 0;
  return pattern == s;
}

inline bool IsExpected(const std::vector<ExpectedFailure>& table, Backend b,
                       const std::string& name, const std::string& kind) {
  for (const auto& e : table)
    if (e.kind == kind && Matches(e.backend, BackendName(b)) && Matches(e.name, name)) return true;
  return false;
}

}  // namespace epicycle::solvers::test
