#include "epicycle/report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

namespace epicycle::report {

namespace {

const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                          "#ff7f0e", "#8c564b", "#17becf", "#7f7f7f"};

// A "nice" tick step for a range (1, 2 or 5 times a power of ten, about 6 ticks).
double TickStep(double span) {
  if (!(span > 0)) return 1.0;
  const double raw = span / 6.0, p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * p) return m * p;
  return 10.0 * p;
}

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

// A decade tick label, 10^k.
std::string Decade(double k) { return fmt::format("1e{:.0f}", k); }

// A title's font size over a figure `w` px wide: 14, smaller when it would not fit (~0.55 em per
// character).
double TitleSize(double w, const std::string& title) {
  return std::min(
      14.0,
      std::floor((w - 20) / (0.55 * static_cast<double>(std::max<std::size_t>(title.size(), 1)))));
}

// `text` broken between words into lines of at most `chars` characters (a longer word alone).
std::vector<std::string> WrapWords(const std::string& text, double chars) {
  std::vector<std::string> lines;
  std::string line, word;
  auto flush_word = [&] {
    if (word.empty()) return;
    if (!line.empty() && static_cast<double>(line.size() + 1 + word.size()) > chars) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    word.clear();
  };
  for (char c : text) {
    if (c == ' ')
      flush_word();
    else
      word += c;
  }
  flush_word();
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

// A marker label's width: about 5.6 px per character (10 px sans-serif) plus 4 px.
double LabelWidth(const XMarker& m) { return 5.6 * static_cast<double>(m.label.size()) + 4; }

// The figure and its plot area [px], the data range shown and the scales [px per unit].
struct Frame {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1, sx = 1, sy = 1;
  double w = 760, h = 200, left = 90, top = 40, pw = 520, ph = 100;
  double px(double x) const { return left + (x - x0) * sx; }
  double py(double y) const { return top + ph - (y - y0) * sy; }
};

// The plot's values in log10 on its logarithmic axes (a value ≤ 0 dropped).
void ToLogAxes(LinePlot& plot) {
  auto to_log = [](std::vector<double>& v) {
    for (double& x : v) x = x > 0 ? std::log10(x) : std::numeric_limits<double>::quiet_NaN();
  };
  for (PlotSeries& ser : plot.series) {
    if (plot.log_x) to_log(ser.x);
    if (plot.log_y) to_log(ser.y);
  }
  if (plot.log_y) to_log(plot.y_references);
  std::erase_if(plot.y_references, [](double r) { return !std::isfinite(r); });
}

// The range shown (the data's, padded, or the plot's fixed one; whole decades on logarithmic
// axes; equal scales if asked; room on the right for the marker labels if they go there).
Frame PlotFrame(const LinePlot& plot) {
  Frame f;
  f.x0 = std::numeric_limits<double>::infinity(), f.x1 = -f.x0, f.y0 = f.x0, f.y1 = -f.x0;
  for (const PlotSeries& s : plot.series) {
    for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      f.x0 = std::min(f.x0, s.x[k]);
      f.x1 = std::max(f.x1, s.x[k]);
      f.y0 = std::min(f.y0, s.y[k]);
      f.y1 = std::max(f.y1, s.y[k]);
    }
  }
  for (double r : plot.y_references) {
    f.y0 = std::min(f.y0, r);
    f.y1 = std::max(f.y1, r);
  }
  if (!std::isfinite(f.x0)) f.x0 = 0, f.x1 = 1, f.y0 = 0, f.y1 = 1;
  if (f.x1 - f.x0 <= 0) f.x0 -= 0.5, f.x1 += 0.5;
  if (f.y1 - f.y0 <= 1e-12 * std::max(1.0, std::abs(f.y0))) {
    const double d = std::max(std::abs(f.y0) * 1e-3, 1e-12);
    f.y0 -= d;
    f.y1 += d;
  }
  const double pad = plot.log_y ? 0.0 : 0.05 * (f.y1 - f.y0);
  f.y0 -= pad;
  f.y1 += pad;
  if (!plot.log_y && std::isfinite(plot.y_min) && std::isfinite(plot.y_max) &&
      plot.y_min < plot.y_max) {
    f.y0 = plot.y_min;
    f.y1 = plot.y_max;
  }
  if (!plot.log_x && std::isfinite(plot.x_min) && std::isfinite(plot.x_max) &&
      plot.x_min < plot.x_max) {
    f.x0 = plot.x_min;
    f.x1 = plot.x_max;
  }
  if (plot.log_x) f.x0 = std::floor(f.x0), f.x1 = std::max(std::ceil(f.x1), f.x0 + 1);
  if (plot.log_y) f.y0 = std::floor(f.y0), f.y1 = std::max(std::ceil(f.y1), f.y0 + 1);
  f.h = std::max(plot.height, 200.0);
  f.ph = f.h - 100;
  f.sx = f.pw / (f.x1 - f.x0);
  f.sy = f.ph / (f.y1 - f.y0);
  if (plot.equal_axes) {
    const double s = std::min(f.sx, f.sy);
    const double cx = 0.5 * (f.x0 + f.x1), cy = 0.5 * (f.y0 + f.y1);
    f.sx = f.sy = s;
    f.x0 = cx - 0.5 * f.pw / s;
    f.x1 = cx + 0.5 * f.pw / s;
    f.y0 = cy - 0.5 * f.ph / s;
    f.y1 = cy + 0.5 * f.ph / s;
  }
  if (plot.labels_right && !plot.equal_axes) {
    // x1 so that the rightmost labels end inside the plot: (x_m − x0) sx + 2 + width ≤ pw.
    double reach = f.x1;
    for (const XMarker& m : plot.x_markers) {
      const double width = LabelWidth(m) + 2;
      if (std::isfinite(m.x) && m.x >= f.x0 && m.x <= f.x1 && !m.label.empty() && width <= f.pw / 3)
        reach = std::max(reach, f.x0 + (m.x - f.x0) * f.pw / (f.pw - width));
    }
    f.x1 = reach;
    f.sx = f.pw / (f.x1 - f.x0);
  }
  return f;
}

// The title, the frame, the ticks and their labels, the axis labels and the y reference lines.
void AppendAxes(const LinePlot& plot, const Frame& f, std::string& s) {
  const double title_size = TitleSize(f.w, plot.title);
  s += fmt::format("<text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"{}\">{}</text>\n",
                   f.w / 2, title_size, Escape(plot.title));
  s += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n",
      f.left, f.top, f.pw, f.ph);
  const double xs = plot.log_x ? std::ceil((f.x1 - f.x0) / 8) : TickStep(f.x1 - f.x0);
  const double ys = plot.log_y ? std::ceil((f.y1 - f.y0) / 8) : TickStep(f.y1 - f.y0);
  for (double t = std::ceil(f.x0 / xs) * xs; t <= f.x1 + 1e-9 * xs; t += xs) {
    s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>",
                     f.px(t), f.top, f.top + f.ph);
    s += fmt::format(
        "<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", f.px(t),
        f.top + f.ph + 16,
        plot.log_x ? Decade(t) : fmt::format("{:g}", std::abs(t) < 1e-12 * xs ? 0.0 : t));
  }
  for (double t = std::ceil(f.y0 / ys) * ys; t <= f.y1 + 1e-9 * ys; t += ys) {
    s += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>",
                     f.left, f.py(t), f.left + f.pw);
    s += fmt::format(
        "<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">{}</text>\n", f.left - 4, f.py(t) + 4,
        plot.log_y ? Decade(t) : fmt::format("{:.6g}", std::abs(t) < 1e-12 * ys ? 0.0 : t));
  }
  s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", f.left + f.pw / 2,
                   f.h - 14, Escape(plot.x_label));
  // The y label, turned, centred on the plot: in lines of at most the image's height (about
  // 0.6 em per character at 12 px), broken between words, smaller if more than two are needed.
  {
    const double centre = f.top + f.ph / 2, room = 2 * std::min(centre, f.h - centre) - 8;
    std::vector<std::string> parts = WrapWords(plot.y_label, room / 7.2);
    const double size = parts.size() <= 2 ? 12.0 : 12.0 * 2 / static_cast<double>(parts.size());
    if (parts.size() > 2) parts = WrapWords(plot.y_label, room / (0.6 * size));
    for (std::size_t k = 0; k < parts.size(); ++k) {
      // Its glyphs lie about one size left of x (turned): the first line at 16 alone, else at 13.
      const double x = (parts.size() == 1 ? 16 : 13) + 1.15 * size * static_cast<double>(k);
      s += fmt::format(
          "<text x=\"{0:.1f}\" y=\"{1}\" transform=\"rotate(-90 {0:.1f} {1})\" "
          "text-anchor=\"middle\"{2}>{3}</text>\n",
          x, centre, size == 12.0 ? "" : fmt::format(" font-size=\"{:.1f}\"", size),
          Escape(parts[k]));
    }
  }
  for (double r : plot.y_references) {
    s += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"black\" "
        "stroke-dasharray=\"4 3\"/>\n",
        f.left, f.py(r), f.left + f.pw);
  }
}

// The x markers: their lines (`lines`) and their labels (`labels`), in rank order: each label in
// the first row (from the top) where it overlaps no label already placed, in at most eight rows
// inside the plot (a label is about 5.6 px per character); a marker left without room is a light
// line.
void MarkerLines(const LinePlot& plot, const Frame& f, std::string& lines, std::string& labels) {
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < plot.x_markers.size(); ++k) {
    const XMarker& m = plot.x_markers[k];
    if (std::isfinite(m.x) && m.x >= f.x0 && m.x <= f.x1) order.push_back(k);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const XMarker &ma = plot.x_markers[a], &mb = plot.x_markers[b];
    return ma.rank != mb.rank ? ma.rank < mb.rank : ma.x < mb.x;
  });
  const std::size_t rows = static_cast<std::size_t>(std::clamp((f.ph - 20) / 11, 0.0, 8.0));
  std::vector<std::vector<std::pair<double, double>>> taken(rows);  // [from, to] per row [px]
  for (std::size_t k : order) {
    const XMarker& m = plot.x_markers[k];
    // Near the right edge a label goes left of its line, off the legend (not with labels_right).
    const bool right = !plot.labels_right && f.px(m.x) > f.left + f.pw - 50;
    const double width = LabelWidth(m);
    const double from = right ? f.px(m.x) - width : f.px(m.x), to = from + width;
    std::size_t row = 0;
    auto free = [&](std::size_t r) {
      return std::none_of(taken[r].begin(), taken[r].end(),
                          [&](const auto& t) { return from < t.second && t.first < to; });
    };
    while (row < rows && !free(row)) ++row;
    const bool placed = !m.label.empty() && row < rows && to <= f.left + f.pw + 1e-9;
    if (placed) {
      taken[row].emplace_back(from, to);
      // Over the curves and other markers' lines: on a white ground as wide as its estimate.
      if (plot.labels_right)
        labels += fmt::format(
            "<rect x=\"{:.1f}\" y=\"{}\" width=\"{:.1f}\" height=\"11\" fill=\"white\" "
            "fill-opacity=\"0.85\"/>\n",
            f.px(m.x) + 1, f.top + 3 + 11 * static_cast<double>(row), width - 2);
      labels += fmt::format(
          "<text x=\"{:.1f}\" y=\"{}\" fill=\"#555\" font-size=\"10\"{}>{}</text>\n",
          right ? f.px(m.x) - 2 : f.px(m.x) + 2, f.top + 12 + 11 * static_cast<double>(row),
          right ? " text-anchor=\"end\"" : "", Escape(m.label));
    }
    lines += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"{3}\"{4}/>\n",
        f.px(m.x), f.top, f.top + f.ph, placed ? "#888" : "#d8d8d8",
        m.dashed ? " stroke-dasharray=\"2 3\"" : "");
  }
}

// The series (lines, points, bands, envelopes) and the legend of those with a name.
void AppendSeries(const LinePlot& plot, const Frame& f, std::string& s) {
  int legend = 0;
  for (std::size_t b = 0; b < plot.series.size(); ++b) {
    const PlotSeries& ser = plot.series[b];
    const char* col = kColours[(ser.colour >= 0 ? static_cast<std::size_t>(ser.colour) : b) % 8];
    std::string pts;
    // Upper envelope per pixel column [px, smallest y px] of a dense `envelope` series.
    std::vector<std::pair<double, double>> top_px;
    std::size_t drawn = 0;
    for (std::size_t k = 0; k < std::min(ser.x.size(), ser.y.size()); ++k) {
      if (!std::isfinite(ser.x[k]) || !std::isfinite(ser.y[k])) continue;
      if (ser.x[k] < f.x0 || ser.x[k] > f.x1) continue;  // outside a fixed x range
      ++drawn;
      if (ser.envelope) {
        const double column = std::floor(f.px(ser.x[k])) + 0.5;
        if (top_px.empty() || top_px.back().first != column)
          top_px.emplace_back(column, f.py(ser.y[k]));
        else
          top_px.back().second = std::min(top_px.back().second, f.py(ser.y[k]));
      }
      if (ser.points || ser.markers) {
        s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.5\" fill=\"{}\"/>\n",
                         f.px(ser.x[k]), f.py(ser.y[k]), col);
      }
      if (!ser.points) {
        pts += fmt::format("{:.1f},{:.1f} ", f.px(ser.x[k]), f.py(ser.y[k]));
      }
    }
    if (!pts.empty() && ser.band) {
      // Light fill with its edge drawn: overlapping bands stay apart by their outlines.
      s += fmt::format(
          "<polygon fill=\"{0}\" fill-opacity=\"0.12\" stroke=\"{0}\" stroke-width=\"0.7\" "
          "stroke-opacity=\"0.7\" points=\"{1}\"/>\n",
          col, pts);
    } else if (!pts.empty() && ser.envelope && drawn > top_px.size()) {
      // Denser than the pixels: the data thin and light, its upper envelope over it.
      std::string env;
      for (const auto& [x, y] : top_px) env += fmt::format("{:.1f},{:.1f} ", x, y);
      s += fmt::format(
          "<polyline fill=\"none\" stroke=\"{0}\" stroke-width=\"0.5\" stroke-opacity=\"0.35\" "
          "points=\"{1}\"/>\n<polyline fill=\"none\" stroke=\"{0}\" stroke-width=\"1.2\" "
          "points=\"{2}\"/>\n",
          col, pts, env);
    } else if (!pts.empty()) {
      s += fmt::format(
          "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"{}{} points=\"{}\"/>\n", col,
          ser.faint ? 0.6 : 1.5, ser.faint ? " stroke-opacity=\"0.45\"" : "",
          ser.dashed ? " stroke-dasharray=\"6,4\"" : "", pts);
    }
    if (ser.name.empty()) continue;
    s += fmt::format("<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>\n", f.left + f.pw + 12,
                     f.top + 14 + 16 * static_cast<double>(legend++), col, Escape(ser.name));
  }
}

}  // namespace

std::string RenderSvg(const LinePlot& input) {
  // Logarithmic axes: the plot is drawn in log10 of its values, on whole decades.
  LinePlot plot = input;
  ToLogAxes(plot);
  const Frame f = PlotFrame(plot);
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} "
      "{1}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{0}\" height=\"{1}\" "
      "fill=\"white\"/>\n",
      f.w, f.h);
  AppendAxes(plot, f, s);
  std::string lines, labels;
  MarkerLines(plot, f, lines, labels);
  // With labels_right the labels go over the curves (below, last), else under them.
  s += plot.labels_right ? lines : lines + labels;
  AppendSeries(plot, f, s);
  if (plot.labels_right) s += labels;
  s += "</svg>\n";
  return s;
}

std::string RenderSvgStack(const std::string& title, const std::vector<LinePlot>& panels) {
  const double w = 760, head = 30;
  double h = head;
  std::string body;
  for (const LinePlot& panel : panels) {
    // Each panel is its own document, nested at its offset.
    std::string svg = RenderSvg(panel);
    svg.replace(0, 4, fmt::format("<svg x=\"0\" y=\"{}\"", h));
    body += svg;
    h += std::max(panel.height, 200.0);
  }
  const double title_size = TitleSize(w, title);
  return fmt::format(
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
             "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"12\">\n"
             "<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n"
             "<text x=\"{2}\" y=\"20\" text-anchor=\"middle\" font-size=\"{3}\">{4}</text>\n",
             w, h, w / 2, title_size, Escape(title)) +
         body + "</svg>\n";
}

PlotSeries HistogramOutline(const std::string& name, double lo, double width,
                            const std::vector<long>& counts) {
  PlotSeries hs{name, {}, {}};
  for (std::size_t b = 0; b < counts.size(); ++b) {
    const double x0 = lo + width * static_cast<double>(b), x1 = x0 + width;
    const auto c = static_cast<double>(counts[b]);
    for (auto [x, y] : {std::pair{x0, 0.0}, {x0, c}, {x1, c}, {x1, 0.0}}) {
      hs.x.push_back(x);
      hs.y.push_back(y);
    }
  }
  return hs;
}

PlotSeries EmpiricalCdfSteps(const std::string& name, const std::vector<double>& sorted) {
  PlotSeries cs{name, {}, {}};
  const double n = static_cast<double>(sorted.size());
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    cs.x.push_back(sorted[i]);
    cs.y.push_back(static_cast<double>(i) / n);
    cs.x.push_back(sorted[i]);
    cs.y.push_back(static_cast<double>(i + 1) / n);
  }
  return cs;
}

namespace {

// A colour of the map's scale at t ∈ [0, 1]: dark blue, teal, green, yellow (a perceptually
// ordered ramp, light for large values).
std::string RampColour(double t) {
  static const double stops[5][3] = {
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int k = std::min(3, static_cast<int>(t));
  const double f = t - k;
  int c[3];
  for (int i = 0; i < 3; ++i)
    c[i] = static_cast<int>(std::lround(stops[k][i] + f * (stops[k + 1][i] - stops[k][i])));
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

}  // namespace

std::string RenderHeatMaps(const std::string& title, const std::vector<HeatMap>& maps) {
  const double w = 760, panel = 170, top = 40, left = 70, right = 110, gap = 40;
  const double h = top + static_cast<double>(maps.size()) * (panel + gap) + 10;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const HeatMap& m : maps)
    for (double v : m.values)
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  if (!(hi > lo)) {
    lo = std::isfinite(lo) ? lo - 0.5 : 0;
    hi = lo + 1;
  }
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} "
      "{1}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{0}\" height=\"{1}\" "
      "fill=\"white\"/>\n<text x=\"{2}\" y=\"20\" text-anchor=\"middle\" font-size=\"{3}\">{4}"
      "</text>\n",
      w, h, w / 2, TitleSize(w, title), Escape(title));
  const double pw = w - left - right;
  for (std::size_t p = 0; p < maps.size(); ++p) {
    const HeatMap& m = maps[p];
    const double y_top = top + static_cast<double>(p) * (panel + gap);
    const double cw = pw / std::max(1, m.columns), ch = panel / std::max(1, m.rows);
    for (int r = 0; r < m.rows; ++r) {
      for (int c = 0; c < m.columns; ++c) {
        const double v = m.values[static_cast<std::size_t>(r * m.columns + c)];
        if (!std::isfinite(v)) continue;
        // Row 0 at the bottom (y0), cells overlapping by half a pixel (no seams).
        s += fmt::format(
            "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\"/>\n",
            left + c * cw, y_top + panel - (r + 1) * ch, cw + 0.5, ch + 0.5,
            RampColour((v - lo) / (hi - lo)));
      }
    }
    s += fmt::format(
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n",
        left, y_top, pw, panel);
    s += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"12\">{}</text>\n", left, y_top - 5,
                     Escape(m.title));
    // Ticks on both axes.
    const double xs = TickStep(m.x1 - m.x0), ys = TickStep(m.y1 - m.y0);
    for (double x = std::ceil(m.x0 / xs) * xs; x <= m.x1 + 1e-9 * xs; x += xs) {
      const double px = left + (x - m.x0) / (m.x1 - m.x0) * pw;
      s += fmt::format(
          "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"black\"/>\n"
          "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\" font-size=\"10\">{4}</text>\n",
          px, y_top + panel, y_top + panel + 4, y_top + panel + 15,
          fmt::format("{:g}", std::abs(x) < 1e-9 * xs ? 0.0 : x));
    }
    for (double y = std::ceil(m.y0 / ys) * ys; y <= m.y1 + 1e-9 * ys; y += ys) {
      const double py = y_top + panel - (y - m.y0) / (m.y1 - m.y0) * panel;
      s += fmt::format(
          "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"black\"/>\n"
          "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\" font-size=\"10\">{5}</text>\n",
          left - 4, py, left, left - 6, py + 3,
          fmt::format("{:g}", std::abs(y) < 1e-9 * ys ? 0.0 : y));
    }
    s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"11\">{}</text>\n",
                     left + pw / 2, y_top + panel + 28, Escape(m.x_label));
    s += fmt::format(
        "<text x=\"16\" y=\"{0}\" text-anchor=\"middle\" font-size=\"11\" transform=\"rotate(-90 "
        "16 {0})\">{1}</text>\n",
        y_top + panel / 2, Escape(m.y_label));
  }
  // The colour bar, beside the first panel.
  const double bx = w - right + 20, by = top, bh = panel;
  for (int k = 0; k < 50; ++k)
    s += fmt::format("<rect x=\"{}\" y=\"{:.2f}\" width=\"16\" height=\"{:.2f}\" fill=\"{}\"/>\n",
                     bx, by + bh - (k + 1) * bh / 50, bh / 50 + 0.5, RampColour((k + 0.5) / 50));
  s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"16\" height=\"{}\" fill=\"none\" "
                   "stroke=\"black\"/>\n",
                   bx, by, bh);
  s += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\">{}</text>\n", bx + 20, by + bh,
                   fmt::format("{:.4g}", lo));
  s += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\">{}</text>\n", bx + 20, by + 8,
                   fmt::format("{:.4g}", hi));
  if (!maps.empty())
    s += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\">{}</text>\n", bx - 4, by + bh + 16,
                     Escape(maps.front().unit));
  return s + "</svg>\n";
}

}  // namespace epicycle::report
