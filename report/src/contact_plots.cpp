#include "epicycle/report/contact_plots.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "epicycle/report/files.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::report {

namespace {

std::string Svg(double w, double h) {
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} "
      "{1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{0}\" height=\"{1}\" "
      "fill=\"white\"/>\n",
      w, h);
}

// The document with the plot area's frame at (x0, y0), pw × ph.
std::string Frame(double w, double h, double x0, double y0, double pw, double ph) {
  return Svg(w, h) + fmt::format(
                         "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" "
                         "stroke=\"black\"/>\n",
                         x0, y0, pw, ph);
}

// The axis titles under and left of the frame.
std::string AxisTitles(const char* x_title, const char* y_title, double h, double x0, double y0,
                       double pw, double ph) {
  return fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", x0 + pw / 2,
                     h - 8, x_title) +
         fmt::format(
             "<text x=\"14\" y=\"{}\" transform=\"rotate(-90 14 {})\" text-anchor=\"middle\">{}"
             "</text>\n",
             y0 + ph / 2, y0 + ph / 2, y_title);
}

const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                          "#ff7f0e", "#8c564b", "#17becf"};

}  // namespace

std::string PerformanceProfileSvg(const std::vector<solvers::PerformanceProfile>& profiles,
                                  std::size_t problems) {
  const double w = 640, h = 420, x0 = 60, y0 = 20, pw = 540, ph = 340, tau_max = 1e4;
  std::string s = Frame(w, h, x0, y0, pw, ph);
  for (int k = 0; k <= 4; ++k) {
    const double x = x0 + pw * k / 4.0;
    s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">1e{}</text>\n", x,
                     y0 + ph + 16, k);
    const double y = y0 + ph - ph * k / 4.0;
    s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{:.2f}</text>\n", x0 - 4, y + 4,
                     k / 4.0);
  }
  s += AxisTitles("time / best time (tau)", "fraction of problems solved", h, x0, y0, pw, ph);
  for (std::size_t b = 0; b < profiles.size(); ++b) {
    const std::vector<double>& ratios = profiles[b].ratios;
    std::string pts = fmt::format("{},{} ", x0, y0 + ph);
    double frac = 0;
    for (std::size_t i = 0; i < ratios.size(); ++i) {
      const double x = x0 + pw * std::min(std::log10(ratios[i]), std::log10(tau_max)) / 4.0;
      pts += fmt::format("{:.1f},{:.1f} ", x, y0 + ph - ph * frac);
      frac = static_cast<double>(i + 1) / static_cast<double>(problems);
      pts += fmt::format("{:.1f},{:.1f} ", x, y0 + ph - ph * frac);
    }
    pts += fmt::format("{},{:.1f}", x0 + pw, y0 + ph - ph * frac);
    const char* col = kColours[b % 7];
    s += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"2\" points=\"{}\"/>\n",
                     col, pts);
    s += fmt::format("<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>\n", x0 + pw - 120,
                     y0 + ph - 20 - 16 * static_cast<double>(b), col, profiles[b].backend);
  }
  s += "</svg>\n";
  return s;
}

std::string ErrorVersusTimeSvg(const std::vector<std::string>& backends,
                               const std::vector<ErrorTimePoint>& points) {
  const double w = 640, h = 420, x0 = 70, y0 = 20, pw = 530, ph = 340;
  const double tmin = -6, tmax = 0, emin = -16, emax = 0;
  std::string s = Frame(w, h, x0, y0, pw, ph);
  for (int k = static_cast<int>(tmin); k <= static_cast<int>(tmax); ++k)
    s += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">1e{}</text>\n",
                     x0 + pw * (k - tmin) / (tmax - tmin), y0 + ph + 16, k);
  for (int k = static_cast<int>(emin); k <= static_cast<int>(emax); k += 2)
    s += fmt::format("<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\">1e{}</text>\n", x0 - 4,
                     y0 + ph - ph * (k - emin) / (emax - emin) + 4, k);
  s += AxisTitles("run time per solve [s]", "error against the reference [-]", h, x0, y0, pw, ph);
  for (std::size_t b = 0; b < backends.size(); ++b) {
    const char* col = kColours[b % 7];
    for (const ErrorTimePoint& r : points) {
      if (r.backend != backends[b]) continue;
      // A run without a finite error (failed, or thrown) is drawn at the top edge.
      const double err = std::isfinite(r.error) ? r.error : std::pow(10.0, emax);
      const double lx = std::clamp(std::log10(std::max(r.seconds, 1e-12)), tmin, tmax);
      const double ly = std::clamp(std::log10(std::max(err, 1e-16)), emin, emax);
      const double x = x0 + pw * (lx - tmin) / (tmax - tmin),
                   y = y0 + ph - ph * (ly - emin) / (emax - emin);
      if (r.solved)
        s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"{}\"/>\n", x, y, col);
      else
        s += fmt::format(
            "<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"{}\" text-anchor=\"middle\">x</text>\n", x,
            y + 4, col);
    }
    s += fmt::format("<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>\n", x0 + 10,
                     y0 + 16 + 16 * static_cast<double>(b), col, backends[b]);
  }
  s += "</svg>\n";
  return s;
}

void WriteComparisonPlots(const std::string& prefix, const solvers::ComparisonRecord& record) {
  std::vector<solvers::ProfileRun> runs;
  std::vector<ErrorTimePoint> points;
  for (const solvers::ComparisonRun& r : record.runs) {
    runs.push_back({r.problem, r.backend, r.median_seconds, r.solved});
    points.push_back({r.backend, r.median_seconds, r.error(), r.solved});
  }
  WriteTextFile(prefix + "_profile.svg",
                PerformanceProfileSvg(solvers::DolanMoreProfile(runs, record.backends),
                                      record.problem_names.size()));
  WriteTextFile(prefix + "_error_vs_time.svg", ErrorVersusTimeSvg(record.backends, points));
}

nlohmann::json ComparisonProvenance(const solvers::ComparisonRequest& request) {
  const std::vector<std::string> files = solvers::ListProblemFiles(request.inputs);
  std::string hashes, backends_used;
  for (const std::string& f : files) hashes += FileHash(f) + "\n";
  for (solvers::Backend b : request.backends) {
    if (!backends_used.empty()) backends_used += ' ';
    backends_used += solvers::BackendName(b);
  }
  return FileProvenance(backends_used, fmt::format("{} problem files", files.size()),
                        transmission::ContentHash(hashes));
}

}  // namespace epicycle::report
