// Numbers on the command line: every numeric option has the range of the library argument it sets
// (geometry/argument_range.hpp; transmission/ and dynamics/run_arguments.hpp); a value outside it
// is bad input (exit 2) named by the option, the value as typed and the rule, checked as the
// command line is parsed, before any file is read:
//   --speed-rpm = nan: must be finite and in [1, 100000] [rpm] (...)
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "epicycle/dynamics/run_arguments.hpp"

namespace epicycle::app {

/// The values an option accepts (the library's rule of the argument it sets).
using OptionRange = geometry::ArgumentRange;

/// `text`, the value given for `option`, as a number inside `range`.
/// @throws std::invalid_argument "OPTION = TEXT: RULE" if it is not a number or not inside.
inline double CheckOption(const std::string& option, const std::string& text,
                          const OptionRange& range) {
  return geometry::CheckArgumentText(option, text, range);
}

/// Adds `name` for `target` to `cmd`, each value checked by CheckOption as it is parsed (the
/// option's help shows the range).
template <typename T>
CLI::Option* AddNumber(CLI::App* cmd, const std::string& name, T& target, const std::string& help,
                       const OptionRange& range) {
  CLI::Validator check(
      [name, range](std::string& text) {
        CheckOption(name, text, range);
        return std::string();
      },
      range.Describe().substr(sizeof("must be ") - 1));
  return cmd->add_option(name, target, help)->check(check);
}

using dynamics::kHarmonics;
using dynamics::kMaxOrder;
using dynamics::kOutputsPerCycle;
using dynamics::kRateScale;
using dynamics::kRelativeTolerance;
using dynamics::kRunContactTolerance;
using dynamics::kRunTimeS;
using dynamics::kSpectrumResolution;
using dynamics::kSpectrumSkipCycles;
using dynamics::kSweepSpeeds;
using dynamics::kWindowCycles;
using transmission::kCarrierAngleDeg;
using transmission::kComparisonRepeats;
using transmission::kContactTolerance;
using transmission::kStiffnessCycle;
using transmission::kStiffnessPositions;
using transmission::kSunSpeedRpm;
using transmission::kSweepPositions;
using transmission::kThreads;
using transmission::kThreadsOrZero;

}  // namespace epicycle::app
