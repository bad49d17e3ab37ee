// The fuzz harnesses of the readers and of the command line, shared by the libFuzzer targets
// (fuzz_scene.cpp, fuzz_contact_problem.cpp, fuzz_study.cpp, fuzz_options.cpp;
// EPICYCLE_BUILD_FUZZERS, tools/fuzz.sh) and by the
// deterministic replay of the committed corpus in the suite (replay.cpp). Bad input must end in
// std::invalid_argument; any other exception, a crash, a sanitizer report or a converged answer
// with non-finite or negative forces is a finding (std::abort).
#pragma once

#include <cstddef>
#include <cstdint>

namespace epicycle::fuzz {

/// Reads `data` as a scene (TOML) and, if it loads, makes its stage or gear pair.
void FuzzScene(const std::uint8_t* data, std::size_t size);

/// Reads `data` as a contact problem file (JSON) and, if it loads and is small, solves it with
/// the active-set Newton back end.
void FuzzContactProblem(const std::uint8_t* data, std::size_t size);

/// Reads `data` as a study file (TOML; a relative scene path is relative to scenes/studies/, so
/// that the shipped studies load) and, if it loads, samples its first and last case: every
/// sampled value must be finite.
void FuzzStudy(const std::uint8_t* data, std::size_t size);

/// Reads `data` as a command line, one argument per line (at most 64 of 256 bytes), and parses it
/// with the program's commands (app/: RegisterCommands) without running any: a parse must end in
/// success, CLI11's usage error or std::invalid_argument (an option's range), and every number a
/// numeric option accepted must be finite.
void FuzzOptions(const std::uint8_t* data, std::size_t size);

}  // namespace epicycle::fuzz
