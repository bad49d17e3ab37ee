// A small SVG line-plot writer for the project's figures (stiffness curves, load sharing,
// transmission error, orbits; the command-line program, the benchmarks' studies and the FE
// reference tool): axes with ticks, one polyline (or band) per series, a legend of the named
// series.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace epicycle::report {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
  bool points = false;   ///< markers instead of a line
  bool markers = false;  ///< markers on the line's points as well (with points = false)
  /// A filled band instead of a line: the points go round its outline (e.g. the lower edge
  /// forwards, the upper edge backwards), drawn as a closed polygon, translucent, no stroke.
  bool band = false;
  bool faint = false;  ///< a thin translucent line (raw samples under their means)
  bool dashed = false;  ///< a dashed line (an unstable branch)
  int colour = -1;     ///< index into the palette; -1: the series' own index
  /// Where the points are denser than the pixels (a spectrum's fine comb of lines): the line
  /// drawn faint and over it the upper envelope, the largest value in each pixel column.
  bool envelope = false;
};

/// A vertical marker at x with a label (e.g. a resonance speed); dashed when `dashed`. Labels are
/// placed in the order of `rank` (lower first, then left to right) in up to eight rows inside
/// the plot; a marker whose label finds no room is drawn as a light line without it. A label
/// starts at its line and runs right (near the right edge left, unless LinePlot::labels_right).
struct XMarker {
  double x = 0;
  std::string label;
  bool dashed = false;
  int rank = 0;
};

struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  bool equal_axes = false;  ///< same scale on both axes (orbits)
  /// Horizontal reference lines (e.g. the ideal load-sharing ratio), drawn dashed.
  std::vector<double> y_references;
  /// Vertical markers with labels, drawn in grey (outside the data's x range: left out).
  std::vector<XMarker> x_markers = {};
  /// Every marker label right of its line, on a white ground over the curves (readable across
  /// other markers' lines): the x axis reaches far enough past the data for the rightmost ones
  /// (labels wider than a third of the plot excepted).
  bool labels_right = false;
  /// Logarithmic axes (decade ticks); values ≤ 0 are skipped like non-finite ones.
  bool log_x = false, log_y = false;
  /// The figure's height [px] (760 px wide; the plot area is 100 px less high).
  double height = 480;
  /// A fixed y range (linear axes; both finite and y_min < y_max): panels drawn to one scale.
  double y_min = std::numeric_limits<double>::quiet_NaN();
  double y_max = std::numeric_limits<double>::quiet_NaN();
  /// A fixed x range (both finite, x_min < x_max): a zoom into part of the data.
  double x_min = std::numeric_limits<double>::quiet_NaN();
  double x_max = std::numeric_limits<double>::quiet_NaN();
};

/// The plot as a complete SVG document. Non-finite values are skipped.
std::string RenderSvg(const LinePlot& plot);

/// Panels stacked top to bottom under one title, as one SVG document (e.g. one planet's load
/// sharing per panel, where their bands would cover each other in one plot).
std::string RenderSvgStack(const std::string& title, const std::vector<LinePlot>& panels);

/// A histogram as a step outline: bins [lo + k w, lo + (k + 1) w) of width w = `width` with
/// `counts[k]` values, each bin drawn (x0, 0), (x0, c), (x1, c), (x1, 0).
PlotSeries HistogramOutline(const std::string& name, double lo, double width,
                            const std::vector<long>& counts);

/// The empirical CDF of `sorted` (ascending) as steps: at x_(i) from (i − 1)/n up to i/n.
PlotSeries EmpiricalCdfSteps(const std::string& name, const std::vector<double>& sorted);

/// A heat map as an SVG document: `values` row-major (rows along y, `columns` per row), cells
/// over [x0, x1] × [y0, y1], coloured on one scale from the smallest to the largest finite value
/// (a colour bar labelled `unit`); NaN cells left blank.
struct HeatMap {
  std::string title, x_label, y_label, unit;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  int columns = 0, rows = 0;
  std::vector<double> values;
};
/// Maps stacked top to bottom under one title, on one colour scale.
std::string RenderHeatMaps(const std::string& title, const std::vector<HeatMap>& maps);

}  // namespace epicycle::report
