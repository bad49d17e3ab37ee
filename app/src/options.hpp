// The command line's options: each argument of a run's request is declared once, beside the
// request, with its option, help and range (geometry::ArgumentInfo in transmission/ and
// dynamics/run_arguments.hpp); Add binds it to CLI11. A number outside its range is bad input
// (exit 2) named by the option, the value as typed and the rule, checked as the command line is
// parsed, before any file is read:
//   --speed-rpm = nan: must be finite and in [1, 100000] [rpm] (...)
#pragma once

#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "epicycle/dynamics/run_arguments.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::app {

using dynamics::DynamicArguments;
using geometry::ArgumentInfo;
using transmission::QuasiStaticArguments;
using transmission::StiffnessArguments;

/// Adds the option of `info` for `target` to `cmd`: a flag for a bool; a number checked by its
/// range as it is parsed (geometry::CheckArgumentText; the help shows the range); else a text, one
/// of `choices` when they are given.
template <typename T>
CLI::Option* Add(CLI::App* cmd, const ArgumentInfo& info, T& target,
                 const std::vector<std::string>& choices = {}) {
  if constexpr (std::is_same_v<T, bool>) {
    return cmd->add_flag(info.option, target, info.help);
  } else {
    CLI::Option* option = cmd->add_option(info.option, target, info.help);
    if (info.range) {
      const std::string name = info.option;
      const geometry::ArgumentRange range = *info.range;
      option->check(CLI::Validator(
          [name, range](std::string& text) {
            geometry::CheckArgumentText(name, text, range);
            return std::string();
          },
          range.Describe().substr(sizeof("must be ") - 1)));
    }
    if (!choices.empty()) option->check(CLI::IsMember(choices));
    return option;
  }
}

/// The positional scene file, required and existing.
inline CLI::Option* AddScene(CLI::App* cmd, std::string& target,
                             const std::string& help = "Scene file (TOML) of a stage") {
  return cmd->add_option("scene", target, help)->required()->check(CLI::ExistingFile);
}

/// `--sun`: a stage's sun support instead of the scene's (an elastic one needs the scene's
/// stiffness, so only fixed and floating).
inline CLI::Option* AddSun(CLI::App* cmd, std::string& target) {
  return cmd->add_option("--sun", target, "Override the scene's sun support")
      ->check(CLI::IsMember({transmission::SunSupportName(transmission::SunSupport::kFixed),
                             transmission::SunSupportName(transmission::SunSupport::kFloating)}));
}

/// `--cache DIR` and `--no-cache`: where the influence tables are kept.
struct TableArgs {
  std::string cache;  ///< empty: the default folder
  bool no_cache = false;
  /// The run's table options.
  transmission::FeComplianceOptions Options() const {
    transmission::FeComplianceOptions o;
    if (!no_cache)
      o.cache_directory = cache.empty() ? transmission::DefaultCacheDirectory() : cache;
    return o;
  }
};

inline void AddTables(CLI::App* cmd, TableArgs& target) {
  cmd->add_option("--cache", target.cache,
                  "Influence-table cache folder (default: ~/.cache/epicycle)");
  cmd->add_flag("--no-cache", target.no_cache, "Build the influence tables in memory only");
}

}  // namespace epicycle::app
