// Contact problem files: a versioned JSON format so that solver studies need no gear code and a
// user can send in a problem that failed. Keys are documented in docs/solvers.md.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::solvers {

inline constexpr const char* kContactFileFormat = "epicycle-contact-problem";
inline constexpr int kContactFileVersion = 1;

/// A problem file: the problem plus metadata of the collection it belongs to.
struct ContactProblemFile {
  ContactProblemData data;
  std::string category;     ///< "closed-form", "random", "gear-like", "stiff" or free text
  std::string description;  ///< how the case was made, what it tests
  std::optional<std::uint64_t> seed;        ///< generator seed, if generated
  std::optional<ContactSolution> expected;  ///< an independent solution (closed form), if any
  std::string expected_note;                ///< where `expected` comes from
  /// What wrote the file (optional "provenance" object of strings: program, version, backend,
  /// scene, scene_hash for problems dumped by `epicycle quasistatic --dump-problems`).
  std::map<std::string, std::string> provenance;
};

/// @throws std::invalid_argument naming the file, the key and the rule (bad JSON, wrong format
/// or version, unknown key, wrong type or size), or the ContactProblem validation message.
ContactProblemFile ReadContactProblemFile(const std::string& path);
ContactProblemFile ParseContactProblemFile(const std::string& json_text, const std::string& source);
/// The problem files of `inputs`: a file as given, a directory's `*.json` files (sorted, without
/// `expected_failures.json`). @throws std::invalid_argument when there are none.
std::vector<std::string> ListProblemFiles(const std::vector<std::string>& inputs);

/// Also validates (constructs a ContactProblem) before writing. @throws std::invalid_argument,
/// std::runtime_error if the file cannot be written.
void WriteContactProblemFile(const ContactProblemFile& file, const std::string& path);
std::string FormatContactProblemFile(const ContactProblemFile& file);

}  // namespace epicycle::solvers
