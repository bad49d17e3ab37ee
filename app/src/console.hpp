// What the command-line program prints besides its results: the progress bar, the warnings, and
// the failure that exits 1; and the report library's writers under the app's namespace.
#pragma once

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/report/files.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/report/svg_plot.hpp"
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

/// The progress bar "[#####     ] done/total what, failed failed, s s" on one rewritten stderr
/// line, shown when stderr is a terminal and the user did not ask for --quiet.
class ProgressBar {
 public:
  explicit ProgressBar(bool quiet) : tty_(!quiet && isatty(fileno(stderr))) {}
  bool tty() const { return tty_; }
  void Restart() { t0_ = std::chrono::steady_clock::now(); }
  void Show(int done, int total, int failed, const char* what) const {
    if (!tty_) return;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    const int width = 30, filled = total > 0 ? width * done / total : width;
    std::fprintf(stderr, "\r  [%s%s] %d/%d %s, %d failed, %.1f s", std::string(filled, '#').c_str(),
                 std::string(width - filled, ' ').c_str(), done, total, what, failed, seconds);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  bool tty_;
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

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

/// Scene warnings (Scene::warnings plus those computed from results), printed to stdout under a
/// "WARNING" heading; nothing if the list is empty.
inline void PrintWarnings(const std::vector<std::string>& warnings) {
  if (warnings.empty()) return;
  std::printf(
      "\nWARNING: %zu value(s) outside the model's validity (results computed, read with "
      "care):\n",
      warnings.size());
  for (const std::string& w : warnings) std::printf("  warning: %s\n", w.c_str());
}

}  // namespace epicycle::app
