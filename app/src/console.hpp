// What the command-line program prints besides its results: the progress bar, the warnings, and
// the failure that exits 1; and the report library's writers under the app's namespace.
#pragma once

#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/report/files.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::app {

using report::CsvFile;
using report::CsvText;
using report::FileHash;
using report::FileProvenance;
using report::LinePlot;
using report::PlotSeries;
using report::Provenance;
using report::ProvenanceCsvLine;
using report::RenderSvg;
using report::WriteTextFile;
using report::XMarker;

/// Thrown when what the user asked for could not be computed (a failed contact solve, failed
/// sweep positions) after its results were written. main() prints it and exits with status 1.
class ComputationFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The influence-table options of `--cache DIR` (empty: the default folder) and `--no-cache`.
inline transmission::FeComplianceOptions TableOptions(const std::string& cache, bool no_cache) {
  transmission::FeComplianceOptions o;
  if (!no_cache) o.cache_directory = cache.empty() ? transmission::DefaultCacheDirectory() : cache;
  return o;
}

/// The scene of a command that needs a stage, its sun support overridden by `--sun` if given.
/// @throws std::invalid_argument for a gear-pair scene (and the reader's bad-input errors).
inline transmission::Scene StageScene(const std::string& file, const std::string& sun,
                                      const char* command) {
  transmission::Scene scene = transmission::ReadScene(file);
  if (scene.kind != transmission::SceneKind::kStage)
    throw std::invalid_argument(file + ": a gear-pair scene; " + command + " needs a stage");
  if (const auto support = io::ValueOf(transmission::kSunSupportNames, sun))
    scene.supports.sun = *support;
  return scene;
}

/// The sun supports `--sun` may set (an elastic one needs the scene's stiffness).
inline std::vector<std::string> SunOverrideNames() {
  return {transmission::SunSupportName(transmission::SunSupport::kFixed),
          transmission::SunSupportName(transmission::SunSupport::kFloating)};
}

/// "[#####     ] done/total what, failed failed, s s" on one rewritten stderr line.
inline void Progress(int done, int total, int failed, double seconds, const char* what) {
  const int width = 30, filled = total > 0 ? width * done / total : width;
  std::fprintf(stderr, "\r  [%s%s] %d/%d %s, %d failed, %.1f s", std::string(filled, '#').c_str(),
               std::string(width - filled, ' ').c_str(), done, total, what, failed, seconds);
  if (done == total) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

/// Scene warnings (Scene::warnings plus those computed from results), printed to stdout under a
/// "WARNING" heading; nothing if the list is empty.
/// The errno of the first write to the standard output that failed (0: none): main names it when
/// the final flush finds the stream's error flag (a report larger than the stream's buffer is
/// written, and fails, inside the call that prints it).
inline int& StdoutErrno() {
  static int first = 0;
  return first;
}

/// `text` onto the standard output; a write that fails keeps its errno (StdoutErrno).
inline void Print(const std::string& text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() && StdoutErrno() == 0)
    StdoutErrno() = errno != 0 ? errno : EIO;
}

inline void PrintWarnings(const std::vector<std::string>& warnings) {
  if (warnings.empty()) return;
  std::printf(
      "\nWARNING: %zu value(s) outside the model's validity (results computed, read with "
      "care):\n",
      warnings.size());
  for (const std::string& w : warnings) std::printf("  warning: %s\n", w.c_str());
}

}  // namespace epicycle::app
