// Log-log work-precision panels written by hand as SVG, shared by the work-precision studies
// (work_precision.cpp: contact back ends per solve; dynamic_work_precision.cpp: integrators and
// back ends in motion). One panel per problem or per measured quantity, side by side: decades on
// both axes, one polyline per series in the order its points are given, filled markers for runs
// that succeeded and hollow ones for runs that did not, an optional short label beside each
// marker, optional dashed horizontal lines (e.g. the reference's own error), a legend on the right.
#pragma once

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace epicycle::bench {

struct LogPoint {
  double x = 0, y = 0;  ///< both > 0; y below LogPanel::floor is drawn at the floor
  bool filled = true;   ///< false: the run failed or did not converge
  std::string label;    ///< drawn beside the marker (may be empty)
  std::string tooltip;  ///< SVG <title>
};

struct LogSeries {
  std::string name, colour;
  std::vector<LogPoint> points;
};

struct LogPanel {
  std::string title, x_label, y_label;
  std::vector<LogSeries> series;
  std::vector<std::pair<double, std::string>> y_lines;  ///< dashed horizontal lines with a label
  double floor = 1e-16;                                 ///< plotted in place of an exact zero
};

namespace internal {

struct LogAxis {
  double lo, hi;  // log10 range
  double px0, px1;
  double Map(double v) const { return px0 + (std::log10(v) - lo) / (hi - lo) * (px1 - px0); }
};

inline void DrawLogPanel(std::ostringstream& svg, const LogPanel& panel, double left, double top,
                         double width, double height) {
  double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
  for (const LogSeries& s : panel.series)
    for (const LogPoint& p : s.points) {
      xmin = std::min(xmin, p.x);
      xmax = std::max(xmax, p.x);
      ymin = std::min(ymin, std::max(p.y, panel.floor));
      ymax = std::max(ymax, std::max(p.y, panel.floor));
    }
  for (const auto& line : panel.y_lines) {
    ymin = std::min(ymin, std::max(line.first, panel.floor));
    ymax = std::max(ymax, std::max(line.first, panel.floor));
  }
  if (xmax <= 0) xmin = xmax = 1;  // an empty panel still gets axes
  if (ymax <= 0) ymin = ymax = 1;
  double xlo = std::floor(std::log10(xmin)), xhi = std::ceil(std::log10(xmax));
  double ylo = std::floor(std::log10(ymin)), yhi = std::ceil(std::log10(ymax));
  if (xhi <= xlo) xhi = xlo + 1;
  if (yhi <= ylo) yhi = ylo + 1;
  const LogAxis x{xlo, xhi, left, left + width};
  const LogAxis y{ylo, yhi, top + height, top};
  svg << "<rect x='" << left << "' y='" << top << "' width='" << width << "' height='" << height
      << "' fill='none' stroke='#333'/>\n";
  svg << "<text x='" << left + width / 2 << "' y='" << top - 8
      << "' text-anchor='middle' font-size='13'>" << panel.title << "</text>\n";
  for (double d = x.lo; d <= x.hi + 1e-9; d += 1) {
    const double px = x.Map(std::pow(10.0, d));
    svg << "<line x1='" << px << "' y1='" << top << "' x2='" << px << "' y2='" << top + height
        << "' stroke='#ddd'/>\n";
    svg << "<text x='" << px << "' y='" << top + height + 16
        << "' text-anchor='middle' font-size='11'>1e" << d << "</text>\n";
  }
  const double ystep = y.hi - y.lo > 8 ? 2 : 1;
  for (double d = y.lo; d <= y.hi + 1e-9; d += ystep) {
    const double py = y.Map(std::pow(10.0, d));
    svg << "<line x1='" << left << "' y1='" << py << "' x2='" << left + width << "' y2='" << py
        << "' stroke='#ddd'/>\n";
    svg << "<text x='" << left - 6 << "' y='" << py + 4 << "' text-anchor='end' font-size='11'>1e"
        << d << "</text>\n";
  }
  svg << "<text x='" << left + width / 2 << "' y='" << top + height + 34
      << "' text-anchor='middle' font-size='12'>" << panel.x_label << "</text>\n";
  svg << "<text transform='translate(" << left - 46 << "," << top + height / 2
      << ") rotate(-90)' text-anchor='middle' font-size='12'>" << panel.y_label << "</text>\n";
  for (const auto& [value, label] : panel.y_lines) {
    const double py = y.Map(std::max(value, panel.floor));
    svg << "<line x1='" << left << "' y1='" << py << "' x2='" << left + width << "' y2='" << py
        << "' stroke='#777' stroke-dasharray='5,4'/>\n<text x='" << left + 4 << "' y='" << py - 4
        << "' font-size='10' fill='#555'>" << label << "</text>\n";
  }
  for (std::size_t k = 0; k < panel.series.size(); ++k) {
    const LogSeries& s = panel.series[k];
    const double label_dy = k % 2 == 0 ? -5 : 12;  // neighbouring series label above / below
    svg << "<polyline fill='none' stroke='" << s.colour << "' stroke-width='1.5' points='";
    for (const LogPoint& p : s.points)
      svg << x.Map(p.x) << "," << y.Map(std::max(p.y, panel.floor)) << " ";
    svg << "'/>\n";
    for (const LogPoint& p : s.points) {
      const double cx = x.Map(p.x), cy = y.Map(std::max(p.y, panel.floor));
      svg << "<circle cx='" << cx << "' cy='" << cy << "' r='3.5' stroke='" << s.colour
          << "' fill='" << (p.filled ? s.colour : "white") << "'><title>" << p.tooltip
          << "</title></circle>\n";
      if (!p.label.empty())
        svg << "<text x='" << cx + 5 << "' y='" << cy + label_dy << "' font-size='9' fill='"
            << s.colour << "'>" << p.label << "</text>\n";
    }
  }
}

}  // namespace internal

/// The panels side by side with a legend of every series name (first colour seen) and the notes
/// below it, as a complete SVG document.
inline std::string LogLogSvg(const std::vector<LogPanel>& panels,
                             const std::vector<std::string>& notes) {
  const double panel_w = 380, panel_h = 300, margin_l = 70, gap = 90, top = 40;
  const double n = static_cast<double>(panels.size());
  std::vector<std::pair<std::string, std::string>> legend;
  for (const LogPanel& p : panels)
    for (const LogSeries& s : p.series)
      if (std::none_of(legend.begin(), legend.end(),
                       [&](const auto& l) { return l.first == s.name; }))
        legend.emplace_back(s.name, s.colour);
  std::size_t widest = 0;
  for (const auto& l : legend) widest = std::max(widest, l.first.size());
  for (const auto& note : notes) widest = std::max(widest, note.size());
  const double legend_w = std::max(140.0, 20.0 + 6.5 * static_cast<double>(widest));
  const double width = margin_l + n * (panel_w + gap) + legend_w;
  const double height =
      std::max(top + panel_h + 60, top + 40 + 18.0 * static_cast<double>(legend.size()) +
                                       14.0 * static_cast<double>(notes.size()));
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n";
  for (std::size_t k = 0; k < panels.size(); ++k)
    internal::DrawLogPanel(svg, panels[k], margin_l + static_cast<double>(k) * (panel_w + gap), top,
                           panel_w, panel_h);
  double ly = top + 10;
  const double lx = margin_l + n * (panel_w + gap) - gap + 20;
  for (const auto& [name, colour] : legend) {
    svg << "<circle cx='" << lx << "' cy='" << ly << "' r='4' fill='" << colour << "'/>"
        << "<text x='" << lx + 10 << "' y='" << ly + 4 << "' font-size='12'>" << name
        << "</text>\n";
    ly += 18;
  }
  ly += 10;
  for (const std::string& note : notes) {
    svg << "<text x='" << lx << "' y='" << ly << "' font-size='11'>" << note << "</text>\n";
    ly += 14;
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace epicycle::bench
