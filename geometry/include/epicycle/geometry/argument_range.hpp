// The range of a number a user gives a run besides the scene: a program option, a keyword argument
// of a Python driver. Each such number has one rule, stated once in the library that takes it
// (transmission/run_arguments.hpp, dynamics/run_arguments.hpp, Gear::kPointsPerSegment), and the
// program and the bindings check it with CheckArgument, so that their rules and messages are the
// same:
//   speed_rpm = nan: must be finite and in [1, 100000] [rpm] (slower runs are quasi-static: ...)
// It lives in geometry/, the library every other links.
#pragma once

#include <string>

namespace epicycle::geometry {

/// The values an argument accepts, in its unit: [lo, hi], or (lo, hi] with lo_open.
struct ArgumentRange {
  double lo = 0, hi = 0;
  bool lo_open = false;
  bool whole = false;     ///< a count: whole numbers only
  const char* unit = "";  ///< "[rpm]", shown after the bounds
  const char* why = "";   ///< the reason for the bounds, shown in parentheses
  /// Finite, inside the bounds and whole for a count.
  bool Holds(double value) const;
  /// "must be finite and in [1, 100000] [rpm] (why)", "must be a whole number in [1, 4096]".
  std::string Describe() const;
};

/// One argument of a run's request as both front ends offer it: the program's option (`--time`),
/// Python's keyword (`time_s`), the help both show (its unit and default), and the rule of a number
/// (null: a name, a path or a flag). Declared once beside the request it sets
/// (transmission/run_arguments.hpp, dynamics/run_arguments.hpp); the program binds it to CLI11, the
/// bindings check their keyword with it, and a run's messages name it as the front end does.
struct ArgumentInfo {
  const char* option;   ///< the program's "--time"
  const char* keyword;  ///< Python's "time_s"
  const char* help;     ///< the program's help text (the bindings' docstring of the keyword)
  const ArgumentRange* range = nullptr;  ///< a number's values; null: text or a flag
};

/// `value`, given for the argument `name`, if `range` holds it.
/// @throws std::invalid_argument "NAME = VALUE: RULE" otherwise (VALUE as the shortest decimal
/// that reads back to it: nan, inf, 1e+300, 2.5).
double CheckArgument(const std::string& name, double value, const ArgumentRange& range);

/// `text`, the value as typed for `name` (a command line), as a number inside `range`.
/// @throws std::invalid_argument "NAME = TEXT: RULE" if it is not a number or not inside.
double CheckArgumentText(const std::string& name, const std::string& text,
                         const ArgumentRange& range);

/// `value` of Python's keyword `info.keyword` if its range holds it (CheckArgument).
inline double CheckArgument(const ArgumentInfo& info, double value) {
  return CheckArgument(info.keyword, value, *info.range);
}

/// Points per profile segment of a drawn outline or sampled profile (Gear::Outline,
/// HalfProfile::Sample): 1 gives each segment's ends; 1000 puts the points of a segment a
/// micrometre or less apart on gears of modules up to a few millimetres, finer than any drawing or
/// mesh needs (and a ring of 100 teeth already has ~2e6 outline points).
inline constexpr ArgumentRange kPointsPerSegment{1, 1000, false, true, "", ""};

}  // namespace epicycle::geometry
