// The backlash oscillator's frequency response by continuation (docs/periodic.md §3): a plain
// program writing docs/figures/periodic_backlash_response.csv and .svg (half the peak-to-peak of
// x against Ω, stable orbits solid, unstable dashed, the folds marked, and the amplitudes that
// 100-period time integrations from two initial states settle on at Ω = 0.6).
//
//   build/benchmarks/periodic_response [OUT_DIR]   (default docs/figures)
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/periodic_systems.hpp"
#include "epicycle/report/svg_plot.hpp"

using namespace epicycle;

namespace {

void Write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

double Amplitude(const dynamics::PeriodicSystem& s, const dynamics::ShootingOptions& o,
                 const Eigen::VectorXd& y0, const Eigen::VectorXd& p) {
  const Eigen::MatrixXd orbit = dynamics::SampleOrbit(s, o, y0, p, 512);
  return (orbit.col(0).maxCoeff() - orbit.col(0).minCoeff()) / 2;
}

}  // namespace

int main(int argc, char** argv) try {
  const std::filesystem::path dir =
      argc > 1 ? argv[1] : std::filesystem::path(EPICYCLE_SOURCE_DIR) / "docs/figures";
  const dynamics::BacklashOscillator s;
  dynamics::ContinuationOptions c;
  c.parameter = "Omega";
  c.start = 1.5;
  c.end = 0.4;
  c.max_step = 0.02;
  c.shooting.rtol = 1e-8;
  c.shooting.atol = Eigen::VectorXd::Constant(1, 1e-10);
  const dynamics::ContinuationResult r = dynamics::ContinuePeriodicOrbit(
      s, c, Eigen::Vector2d(1.1, 0), Eigen::Vector2d(c.start, s.alternating_force));
  if (r.status != dynamics::ContinuationStatus::kCompleted)
    throw std::runtime_error("continuation: " + r.message);

  std::string csv = "Omega [-],amplitude [-],stability,spectral_radius [-]\n";
  report::LinePlot plot;
  plot.title = "Gear pair with backlash (Kahraman & Singh): ζ = 0.05, F_m = 0.1, F_a = 0.05";
  plot.x_label = "Ω (forcing over natural frequency) [-]";
  plot.y_label = "half peak-to-peak of x [-]";
  bool named_stable = false, named_unstable = false;
  for (std::size_t k = 0; k < r.points.size();) {
    const bool stable = r.points[k].floquet.stability != dynamics::Stability::kUnstable;
    report::PlotSeries seg;
    seg.colour = 0;
    seg.dashed = !stable;
    if (stable && !named_stable) seg.name = "stable orbits", named_stable = true;
    if (!stable && !named_unstable) seg.name = "unstable orbits", named_unstable = true;
    // The segment and the first point of the next, so that the curve stays connected.
    std::size_t j = k;
    for (; j < r.points.size(); ++j) {
      const dynamics::BranchPoint& b = r.points[j];
      const bool st = b.floquet.stability != dynamics::Stability::kUnstable;
      if (st != stable) break;
      seg.x.push_back(b.parameter);
      seg.y.push_back(b.amplitude);
      char line[160];
      std::snprintf(line, sizeof line, "%.9g,%.9g,%s,%.9g\n", b.parameter, b.amplitude,
                    dynamics::StabilityName(b.floquet.stability).c_str(),
                    b.floquet.spectral_radius);
      csv += line;
    }
    if (j < r.points.size()) {
      seg.x.push_back(r.points[j].parameter);
      seg.y.push_back(r.points[j].amplitude);
    }
    plot.series.push_back(std::move(seg));
    k = j;
  }
  for (const dynamics::Bifurcation& b : r.bifurcations) {
    char label[80];
    std::snprintf(label, sizeof label, "%s Ω = %.4f", dynamics::BifurcationKindName(b.kind).c_str(),
                  b.parameter);
    plot.x_markers.push_back({b.parameter, label, true, 0});
  }
  // Time integrations at Ω = 0.6 from rest at x = 1.1 and from x = 0.
  const Eigen::Vector2d p(0.6, s.alternating_force);
  report::PlotSeries settled;
  settled.name = "settled, Ω = 0.6";
  settled.points = true;
  settled.colour = 2;
  for (const Eigen::Vector2d& start : {Eigen::Vector2d(1.1, 0), Eigen::Vector2d(0, 0)}) {
    const Eigen::VectorXd end = dynamics::IntegratePeriods(s, c.shooting, start, p, 100);
    settled.x.push_back(0.6);
    settled.y.push_back(Amplitude(s, c.shooting, end, p));
  }
  plot.series.push_back(settled);
  std::filesystem::create_directories(dir);
  Write(dir / "periodic_backlash_response.csv", csv);
  Write(dir / "periodic_backlash_response.svg", report::RenderSvg(plot));
  std::printf("wrote %s (%zu points)\n", (dir / "periodic_backlash_response.svg").c_str(),
              r.points.size());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "periodic_response: %s\n", e.what());
  return 1;
}
