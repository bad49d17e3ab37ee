#include "epicycle/report/sobol_files.hpp"

#include <cmath>

#include <fmt/format.h>

#include "epicycle/report/files.hpp"

namespace epicycle::report {

namespace {

nlohmann::json Stat(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json Indices(const std::vector<std::string>& variables,
                       const std::vector<studies::SobolIndex>& x) {
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < x.size(); ++i)
    list.push_back({{"variable", variables[i]},
                    {"value", Stat(x[i].value)},
                    {"ci", {Stat(x[i].lower), Stat(x[i].upper)}},
                    {"standard_error", Stat(x[i].standard_error)}});
  return list;
}

}  // namespace

nlohmann::json SobolJson(const studies::SobolSummary& s) {
  nlohmann::json j = {
      {"design", "Saltelli: A, B and A_B^(i) of N rows each, N (d + 2) cases"},
      {"estimators",
       "first order: Saltelli et al. 2010 (1/N) sum y_B (y_ABi - y_A) / V; total: Jansen "
       "(1/2N) sum (y_A - y_ABi)^2 / V; outputs centred on their mean, V from A and B"},
      {"intervals", "percentile bootstrap over the rows j"},
      {"base_samples_N", s.base_samples},
      {"complete_rows", s.complete_rows},
      {"bootstrap_resamples", s.bootstrap},
      {"confidence_level", s.level},
      {"variables", s.variables}};
  nlohmann::json outputs = nlohmann::json::object();
  for (const auto& o : s.outputs) {
    const auto& e = o.estimate;
    outputs[o.name] = {{"rows", e.rows},
                       {"mean", Stat(e.mean)},
                       {"variance", Stat(e.variance)},
                       {"first_order", Indices(s.variables, e.first)},
                       {"total", Indices(s.variables, e.total)},
                       {"sum_first_order",
                        {{"value", Stat(e.sum_first.value)},
                         {"ci", {Stat(e.sum_first.lower), Stat(e.sum_first.upper)}},
                         {"standard_error", Stat(e.sum_first.standard_error)}}}};
  }
  j["outputs"] = outputs;
  return j;
}

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
                         Num(a.value, f, "-"), Num(a.lower, f, "-"), Num(a.upper, f, "-"),
                         Num(t.value, f, "-"), Num(t.lower, f, "-"), Num(t.upper, f, "-"));
    }
    out += fmt::format("    {:<22} {:<34} {:>6} [{}, {}]\n", "", "sum of S_i",
                       Num(e.sum_first.value, f, "-"), Num(e.sum_first.lower, f, "-"),
                       Num(e.sum_first.upper, f, "-"));
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
