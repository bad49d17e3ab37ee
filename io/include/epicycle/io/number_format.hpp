// The number format of messages: every layer writes the values it names in an error or a warning
// through here, so that a value reads the same wherever it is quoted.
#pragma once

#include <string>

namespace epicycle::io {

/// Significant digits of a value an input file gave (a scene's), quoted in a message.
inline constexpr int kInputDigits = 10;

/// `v` with `significant_digits` significant digits (at least 1), printf's "%.Ng": the text an
/// ostream of that precision writes ("1500", "0.001", "1e+20", "inf", "nan").
std::string Num(double v, int significant_digits = 6);

}  // namespace epicycle::io
