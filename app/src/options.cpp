#include "options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <fmt/format.h>

#include "commands.hpp"
#include "epicycle/config.h"

namespace epicycle::app {

bool OptionRange::Holds(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (!(v <= hi)) return false;
  return !whole || v == std::floor(v);
}

std::string OptionRange::Describe() const {
  std::string text =
      fmt::format("must be {} {}{}, {}]", whole ? "a whole number in" : "finite and in",
                  lo_open ? "(" : "[", lo, hi);
  if (*unit != '\0') text += fmt::format(" {}", unit);
  if (*why != '\0') text += fmt::format(" ({})", why);
  return text;
}

double CheckOption(const std::string& option, const std::string& text, const OptionRange& range) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || !range.Holds(v))
    throw std::invalid_argument(option + " = " + text + ": " + range.Describe());
  return v;
}

void RegisterCommands(CLI::App& app) {
  app.require_subcommand(1);
  app.set_version_flag("--version", EPICYCLE_VERSION);
  RegisterGeometryCommands(app);
  RegisterContactCommands(app);
  RegisterStiffnessCommands(app);
  RegisterQuasiStaticCommands(app);
  RegisterDynamicCommands(app);
  RegisterStudyCommands(app);
}

}  // namespace epicycle::app
