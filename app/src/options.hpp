// Numbers on the command line: every numeric option has a range (finite, inside its bounds, whole
// for a count); a value outside it is bad input (exit 2) named by the option, the value as typed
// and the rule, checked as the command line is parsed, before any file is read:
//   --speed-rpm = nan: must be finite and in [1, 100000] [rpm] (...)
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace epicycle::app {

/// The values an option accepts, in its unit: [lo, hi], or (lo, hi] with lo_open.
struct OptionRange {
  double lo = 0, hi = 0;
  bool lo_open = false;
  bool whole = false;     ///< a count: whole numbers only
  const char* unit = "";  ///< "[rpm]", shown after the bounds
  const char* why = "";   ///< the reason for the bounds, shown in parentheses
  bool Holds(double value) const;
  /// "must be finite and in [1, 100000] [rpm] (why)", "must be a whole number in [1, 4096]".
  std::string Describe() const;
};

/// `text`, the value given for `option`, as a number inside `range`.
/// @throws std::invalid_argument "OPTION = TEXT: RULE" if it is not a number or not inside.
double CheckOption(const std::string& option, const std::string& text, const OptionRange& range);

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

// Ranges shared by several commands.
/// Carrier (or gear 1) angles.
inline constexpr OptionRange kAngleDeg{-3600, 3600,    false,
                                       false, "[deg]", "ten revolutions either way"};
/// Sun speeds of a dynamic run or a speed sweep.
inline constexpr OptionRange kSunSpeedRpm{1,
                                          1e5,
                                          false,
                                          false,
                                          "[rpm]",
                                          "slower runs are quasi-static: epicycle quasistatic; "
                                          "faster ones are past any gear's pitch-line "
                                          "speed"};
/// Worker threads where 0 means one per core.
inline constexpr OptionRange kThreadsOrZero{0, 4096, false, true, "", "0: one per core"};
/// Worker threads.
inline constexpr OptionRange kThreads{1, 4096, false, true, "", ""};
/// A contact solve's tolerance on its nondimensional residual.
inline constexpr OptionRange kContactTolerance{0, 1, true, false, "", "a nondimensional residual"};

}  // namespace epicycle::app
