// A small SVG line-plot writer for the command-line program's figures (stiffness curves, load
// sharing, transmission error, orbits): axes with ticks, one polyline per series, a legend.
#pragma once

#include <string>
#include <vector>

namespace epicycle::app {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
  bool points = false;   ///< markers instead of a line
  bool markers = false;  ///< markers on the line's points as well (with points = false)
};

/// A vertical marker at x with a label (e.g. a resonance speed); dashed when `dashed`.
struct XMarker {
  double x = 0;
  std::string label;
  bool dashed = false;
};

struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  bool equal_axes = false;  ///< same scale on both axes (orbits)
  /// Horizontal reference lines (e.g. the ideal load-sharing ratio), drawn dashed.
  std::vector<double> y_references;
  /// Vertical markers with labels, drawn in grey (outside the data's x range: left out).
  std::vector<XMarker> x_markers = {};
  /// Logarithmic axes (decade ticks); values ≤ 0 are skipped like non-finite ones.
  bool log_x = false, log_y = false;
};

/// The plot as a complete SVG document. Non-finite values are skipped.
std::string RenderSvg(const LinePlot& plot);

/// Writes `text` to `path`. @throws std::runtime_error naming the file if it cannot be written.
void WriteTextFile(const std::string& path, const std::string& text);

}  // namespace epicycle::app
