// Formatting shared by the sweep and time-integration commands: numbers for CSV cells (empty when
// not finite, so that no NaN or inf reaches a result file) and the progress bar on stderr.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include <fmt/format.h>

namespace epicycle::app {

inline std::string Num(double v, const char* format = "{:.9g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : "";
}

/// "[#####     ] done/total what, failed failed, s s" on one rewritten stderr line.
inline void Progress(int done, int total, int failed, double seconds, const char* what) {
  const int width = 30, filled = total > 0 ? width * done / total : width;
  std::fprintf(stderr, "\r  [%s%s] %d/%d %s, %d failed, %.1f s", std::string(filled, '#').c_str(),
               std::string(width - filled, ' ').c_str(), done, total, what, failed, seconds);
  if (done == total) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace epicycle::app
