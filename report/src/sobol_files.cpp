#include "epicycle/report/sobol_files.hpp"

#include <cmath>

#include <fmt/format.h>

#include "epicycle/report/files.hpp"

namespace epicycle::report {

std::string SobolText(const studies::SobolSummary& s) {
  std::string out = fmt::format(
      "  Sobol indices: N = {} rows ({} complete), {} bootstrap resamples, {:g} % intervals\n",
      s.base_samples, s.complete_rows, s.bootstrap, 100.0 * s.level);
  const char* f = "{:.3f}";
  for (const auto& o : s.outputs) {
    const auto& e = o.estimate;
    if (!(e.variance > 0)) {
      out += fmt::format("    {:<22} constant over the cases: no indices\n", o.name);
      continue;
    }
    out += fmt::format("    {:<22} {:<34} {:<24} {}\n", o.name, "variable", "first order S_i [CI]",
                       "total S_Ti [CI]");
    for (std::size_t i = 0; i < e.first.size(); ++i) {
      const auto &a = e.first[i], &t = e.total[i];
      out += fmt::format("    {:<22} {:<34} {:>6} [{}, {}]  {:>6} [{}, {}]\n", "", s.variables[i],
                         Figure(a.value, f, "-"), Figure(a.lower, f, "-"), Figure(a.upper, f, "-"),
                         Figure(t.value, f, "-"), Figure(t.lower, f, "-"), Figure(t.upper, f, "-"));
    }
    out += fmt::format("    {:<22} {:<34} {:>6} [{}, {}]\n", "", "sum of S_i",
                       Figure(e.sum_first.value, f, "-"), Figure(e.sum_first.lower, f, "-"),
                       Figure(e.sum_first.upper, f, "-"));
  }
  return out;
}

LinePlot SobolBarPlot(const std::string& title, const studies::SobolSummary& s,
                      const studies::SobolOutput& output) {
  LinePlot p{title + ": Sobol indices of " + output.name,
             "variable (1 ... d, named above) [-]",
             "index [-]",
             {},
             false,
             {}};
  const auto& e = output.estimate;
  const double half = 0.16;  // bar half-width [x units]; first order at i − 0.18, total at i + 0.18
  for (int kind = 0; kind < 2; ++kind) {
    const auto& x = kind == 0 ? e.first : e.total;
    const double shift = kind == 0 ? -0.18 : 0.18;
    // All bars of one kind as one band: each a closed rectangle down to 0 and back.
    PlotSeries bars{kind == 0 ? "first order S_i" : "total S_Ti", {}, {}};
    bars.band = true;
    bars.colour = kind;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double c = static_cast<double>(i + 1) + shift;
      if (!std::isfinite(x[i].value)) continue;
      for (auto [bx, by] : {std::pair{c - half, 0.0},
                            {c - half, x[i].value},
                            {c + half, x[i].value},
                            {c + half, 0.0}}) {
        bars.x.push_back(bx);
        bars.y.push_back(by);
      }
    }
    p.series.push_back(bars);
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double c = static_cast<double>(i + 1) + shift;
      if (!std::isfinite(x[i].lower) || !std::isfinite(x[i].upper)) continue;
      // One polyline per whisker with its caps (a series is one line); the first one named.
      const bool named = kind == 0 && i == 0;
      PlotSeries w{named ? fmt::format("{:g} % interval", 100.0 * s.level) : "", {}, {}};
      w.colour = 3;
      for (auto [wx, wy] : {std::pair{c - 0.06, x[i].lower},
                            {c + 0.06, x[i].lower},
                            {c, x[i].lower},
                            {c, x[i].upper},
                            {c - 0.06, x[i].upper},
                            {c + 0.06, x[i].upper}}) {
        w.x.push_back(wx);
        w.y.push_back(wy);
      }
      p.series.push_back(w);
    }
  }
  // Each variable's name over its pair of bars, from a separator line at the pair's left.
  for (std::size_t i = 0; i < s.variables.size(); ++i)
    p.x_markers.push_back({static_cast<double>(i) + 0.5, s.variables[i], false, 0});
  p.y_references = {0.0};
  p.x_min = 0.5;
  p.x_max = static_cast<double>(s.variables.size()) + 0.5;
  p.y_min = -0.1;
  p.y_max = 1.1;
  return p;
}

}  // namespace epicycle::report
