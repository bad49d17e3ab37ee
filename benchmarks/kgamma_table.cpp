// The standard's K_γ table put to the test (docs/studies.md, "The standard's K_γ table"): gathers
// the summaries of the studies scenes/studies/kgamma_table/planets<N>_class<A>.toml (run by
// tools/kgamma_table.sh) into a table (CSV and Markdown) of P(K_γ > table value) with its
// Clopper–Pearson interval per planet count and ISO 1328-1 class, and a figure (the report
// library's SVG writer): the probability against the planet count, one series per class, each
// interval a whisker (each study's last k_gamma_limit), and K_γ's P95 with its interval against
// the table's value.
//
//   kgamma_table PREFIX LABEL N:A:DIR/study_summary.json ...
//     writes PREFIX.csv, PREFIX.md, PREFIX.svg, PREFIX_p95.svg; LABEL (the sun's support) goes into the title
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "epicycle/report/files.hpp"
#include "epicycle/report/svg_plot.hpp"

namespace {

using nlohmann::json;

struct Cell {
  int planets = 0, grade = 0;
  json exceedance;  // the summary's "K_gamma_exceedance" array
  json k_gamma;     // its "K_gamma" summary
};

double Number(const json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

std::string Fixed(double v, int digits) {
  return std::isfinite(v) ? fmt::format("{:.{}f}", v, digits) : std::string("-");
}

Cell ReadCell(const std::string& arg) {
  const auto a = arg.find(':'), b = arg.find(':', a + 1);
  if (a == std::string::npos || b == std::string::npos)
    throw std::invalid_argument(arg + ": expected N:A:FILE (planets, ISO 1328-1 class, summary)");
  Cell c;
  c.planets = std::stoi(arg.substr(0, a));
  c.grade = std::stoi(arg.substr(a + 1, b - a - 1));
  std::ifstream in(arg.substr(b + 1));
  if (!in) throw std::invalid_argument(arg.substr(b + 1) + ": cannot be read");
  const json j = json::parse(in);
  if (!j.contains("K_gamma_exceedance"))
    throw std::invalid_argument(arg.substr(b + 1) + ": no K_gamma_exceedance (no k_gamma_limit)");
  c.exceedance = j.at("K_gamma_exceedance");
  c.k_gamma = j.at("K_gamma");
  return c;
}

// One figure's points: per class a series of markers, each point's interval a whisker (an
// unnamed series: no legend entry); the classes side by side at each planet count (5, 6, 7 at
// N - 0.1, N, N + 0.1).
struct Points {
  std::map<int, epicycle::report::PlotSeries> series;  // by class
  std::vector<epicycle::report::PlotSeries> whiskers;
  void Add(int planets, int grade, double y, double lo, double hi) {
    const double at = planets + 0.1 * (grade - 6);
    auto& s = series[grade];
    s.name = fmt::format("ISO 1328-1 class {}", grade);
    s.markers = true;
    s.colour = grade - 5;
    s.x.push_back(at);
    s.y.push_back(y);
    epicycle::report::PlotSeries w;
    w.colour = grade - 5;
    w.x = {at, at};
    w.y = {lo, hi};
    whiskers.push_back(w);
  }
  void Into(epicycle::report::LinePlot* plot) const {
    for (const auto& [grade, s] : series) plot->series.push_back(s);
    for (const auto& w : whiskers) plot->series.push_back(w);
    plot->x_min = 2.6;
    plot->x_max = 6.4;
  }
};

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 4) {
      std::fprintf(stderr, "usage: kgamma_table PREFIX LABEL N:A:SUMMARY.json ...\n");
      return 2;
    }
    const std::string prefix = argv[1], label = argv[2];
    std::vector<Cell> cells;
    for (int i = 3; i < argc; ++i) cells.push_back(ReadCell(argv[i]));

    std::string csv =
        "planets,iso1328_class,k_gamma_limit,cases,above,probability,ci_low,ci_high,"
        "K_gamma_mean,K_gamma_P95,K_gamma_max\n";
    std::string md =
        "| planets | class | table K_γ | P(K_γ > table) [95 % CI] | cases above / cases | "
        "K_γ mean | K_γ P95 [95 % CI] | K_γ max |\n|---|---|---|---|---|---|---|---|\n";
    Points probability, p95s;
    epicycle::report::PlotSeries table{"table K_gamma (ABS)", {}, {}};
    table.colour = 3;
    for (const Cell& c : cells) {
      const json& pct = c.k_gamma.at("percentiles");
      double p95 = std::nan(""), p95_lo = p95, p95_hi = p95;
      for (const json& q : pct)
        if (Number(q.at("p")) == 0.95) {
          p95 = Number(q.at("value"));
          p95_lo = Number(q.at("ci")[0]);
          p95_hi = Number(q.at("ci")[1]);
        }
      p95s.Add(c.planets, c.grade, p95, p95_lo, p95_hi);
      const double table_value = Number(c.exceedance.at(0).at("k_gamma_limit"));
      if (table.x.empty() || table.x.back() != c.planets) {
        table.x.push_back(c.planets);
        table.y.push_back(table_value);
      }
      for (std::size_t k = 0; k < c.exceedance.size(); ++k) {
        const json& e = c.exceedance[k];
        const double x = Number(e.at("k_gamma_limit")), p = Number(e.at("probability"));
        const double lo = Number(e.at("ci")[0]), hi = Number(e.at("ci")[1]);
        const long n = e.at("cases").get<long>(), above = e.at("above").get<long>();
        csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", c.planets, c.grade, x, n, above,
                           p, lo, hi, Number(c.k_gamma.at("mean")), p95,
                           Number(c.k_gamma.at("max")));
        md += fmt::format("| {} | {} | {} | {} [{}, {}] | {} / {} | {} | {} [{}, {}] | {} |\n",
                          c.planets, c.grade, x, Fixed(p, 3), Fixed(lo, 3), Fixed(hi, 3), above,
                          n, Fixed(Number(c.k_gamma.at("mean")), 3), Fixed(p95, 3),
                          Fixed(p95_lo, 3), Fixed(p95_hi, 3),
                          Fixed(Number(c.k_gamma.at("max")), 3));
        // The figure: each study's last limit (3 planets: 1.1; the table's 1.0 is exceeded by
        // every K_γ, which is at least 1).
        if (k + 1 != c.exceedance.size()) continue;
        probability.Add(c.planets, c.grade, p, lo, hi);
      }
    }
    epicycle::report::WriteTextFile(prefix + ".csv", csv);
    epicycle::report::WriteTextFile(prefix + ".md", md);
    epicycle::report::LinePlot plot{
        "P(K_gamma > table value), " + label + ": pin holes and run-outs of one ISO 1328-1 class",
        "planets (K_gamma limit: 3: 1.1, 4: 1.2, 5: 1.3, 6: 1.4)",
        "P(K_gamma > table value) [-], 95 % Clopper-Pearson",
        {},
        false,
        {}};
    probability.Into(&plot);
    plot.y_min = 0;
    plot.y_max = 1;
    epicycle::report::WriteTextFile(prefix + ".svg", epicycle::report::RenderSvg(plot));
    epicycle::report::LinePlot tail{"K_gamma's P95 (95 % CI) and the table value, " + label,
                                    "planets", "K_gamma [-]", {}, false, {}};
    p95s.Into(&tail);
    tail.series.push_back(table);
    epicycle::report::WriteTextFile(prefix + "_p95.svg", epicycle::report::RenderSvg(tail));
    std::printf("%s", md.c_str());
    std::printf("wrote %s.csv, .md, .svg, _p95.svg\n", prefix.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kgamma_table: error: %s\n", e.what());
    return 1;
  }
}
