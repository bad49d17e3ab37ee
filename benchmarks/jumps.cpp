// The jumps of the light-torque paper stage with a pin error (docs/periodic.md §3, "Jumps"): a
// plain program. It continues the periodic orbits over the sun speed from both sides of the
// resonance (their folds), runs carried time-integration sweeps up and down at several speed
// steps (dynamic --speed-sweep --carry-state), prints where each sweep jumps, and writes
// docs/figures/periodic_jumps.csv and .svg (TE amplitude against speed: stable orbits solid,
// unstable dashed, the folds marked, the finest sweeps' points).
//
//   build/benchmarks/jumps [OUT_DIR] [STEP_RPM ...]   (default docs/figures; steps 200 100 50)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/speed_sweep_run.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/scene.hpp"

using namespace epicycle;

namespace {

constexpr double kLow = 11000, kHigh = 12800;  // the sweeps' range [rpm], both folds inside

void Write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

dynamics::DynamicRequest Run() {
  dynamics::DynamicRequest r;
  r.scene = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) +
                                    "/paper_stage_light_pin_error.toml");
  r.tables.cache_directory = transmission::DefaultCacheDirectory();
  return r;
}

// The branch continued from `from` towards `to` [rpm] until its first fold and a little past it.
dynamics::StageBranchRecord Branch(double from, double to) {
  dynamics::BranchRequest b;
  b.run = Run();
  b.start = from;
  b.end = to;
  b.steps = 12;
  b.max_points = 300;
  dynamics::BranchSink sink;
  dynamics::BranchRecord r = dynamics::RunBranch(b, sink);
  if (r.branch.bifurcations.empty())
    throw std::runtime_error("no fold between " + std::to_string(from) + " and " +
                             std::to_string(to) + " rpm: " + r.branch.message);
  return r.branch;
}

dynamics::SpeedSweepRecord Sweep(double step_rpm, dynamics::CarryState carry, double* cpu) {
  dynamics::SpeedSweepRequest s;
  s.run = Run();
  const int n = static_cast<int>(std::lround((kHigh - kLow) / step_rpm)) + 1;
  s.sun_speeds_rpm = dynamics::SpeedGrid(kLow, kHigh, n);
  s.window_cycles = 4;
  s.threads = 1;
  s.carry = carry;
  dynamics::SpeedSweepSink sink;
  const dynamics::SpeedSweepRecord r = dynamics::RunSpeedSweep(s, sink);
  if (r.failed() > 0) throw std::runtime_error("a sweep's speed failed");
  *cpu += r.cpu_seconds;
  return r;
}

}  // namespace

int main(int argc, char** argv) try {
  const std::filesystem::path dir =
      argc > 1 ? argv[1] : std::filesystem::path(EPICYCLE_SOURCE_DIR) / "docs/figures";
  std::vector<double> steps;
  for (int k = 2; k < argc; ++k) steps.push_back(std::atof(argv[k]));
  if (steps.empty()) steps = {200, 100, 50};

  // From below the resonance up along the orbit without contact loss to the upper fold, and from
  // above it down along the separating orbit to the lower fold.
  const dynamics::StageBranchRecord up = Branch(10800, 13200);
  const dynamics::StageBranchRecord down = Branch(13200, 10800);
  const double fold_hi = up.bifurcations.front().parameter;
  const double fold_lo = down.bifurcations.front().parameter;
  const double threshold = dynamics::SeparatingTeAmplitude(up, down);
  std::printf("folds: %.2f and %.2f rpm (%.1f s and %.1f s CPU, %zu and %zu points); TE "
              "amplitude between the orbits %.2f urad\n",
              fold_lo, fold_hi, up.cpu_seconds, down.cpu_seconds, up.points.size(),
              down.points.size(), threshold * 1e6);

  std::string csv = "series,sun_speed_rpm,te_amplitude_urad,stability\n";
  report::LinePlot plot;
  plot.title = "Paper stage, -50 N·m, planet 1's pin 2 µm tangential: jumps";
  plot.x_label = "sun speed [rpm]";
  plot.y_label = "TE amplitude [µrad]";
  bool named_stable = false, named_unstable = false;
  for (const dynamics::StageBranchRecord* b : {&up, &down}) {
    const std::string name = b == &up ? "branch from below" : "branch from above";
    for (std::size_t k = 0; k < b->points.size();) {
      const bool stable = b->points[k].stability != dynamics::Stability::kUnstable;
      report::PlotSeries seg;
      seg.colour = 0;
      seg.dashed = !stable;
      if (stable && !named_stable) seg.name = "stable orbits", named_stable = true;
      if (!stable && !named_unstable) seg.name = "unstable orbits", named_unstable = true;
      std::size_t j = k;
      for (; j < b->points.size(); ++j) {
        const dynamics::StageBranchPoint& p = b->points[j];
        if ((p.stability != dynamics::Stability::kUnstable) != stable) break;
        seg.x.push_back(p.parameter);
        seg.y.push_back(p.te_amplitude * 1e6);
        char line[160];
        std::snprintf(line, sizeof line, "%s,%.6f,%.6f,%s\n", name.c_str(), p.parameter,
                      p.te_amplitude * 1e6, stable ? "stable" : "unstable");
        csv += line;
      }
      if (j < b->points.size()) {  // keep the curve connected
        seg.x.push_back(b->points[j].parameter);
        seg.y.push_back(b->points[j].te_amplitude * 1e6);
      }
      plot.series.push_back(std::move(seg));
      k = j;
    }
  }
  char label[80];
  std::snprintf(label, sizeof label, "fold %.0f rpm", fold_lo);
  plot.x_markers.push_back({fold_lo, label, true, 0});
  std::snprintf(label, sizeof label, "fold %.0f rpm", fold_hi);
  plot.x_markers.push_back({fold_hi, label, true, 0});

  std::printf("%10s %12s %12s %12s %12s %10s\n", "step rpm", "up jump rpm", "down jump rpm",
              "gap rpm", "rate rpm/s", "CPU s");
  for (std::size_t s = 0; s < steps.size(); ++s) {
    double cpu = 0;
    const dynamics::SpeedSweepRecord up_sweep = Sweep(steps[s], dynamics::CarryState::kUp, &cpu);
    const dynamics::SpeedSweepRecord down_sweep =
        Sweep(steps[s], dynamics::CarryState::kDown, &cpu);
    const std::vector<dynamics::SpeedResult>& ups = up_sweep.speeds;
    const std::vector<dynamics::SpeedResult>& downs = down_sweep.speeds;
    const int ju = dynamics::JumpIndex(ups, dynamics::CarryState::kUp, threshold);
    const int jd = dynamics::JumpIndex(downs, dynamics::CarryState::kDown, threshold);
    if (ju < 0 || jd < 0) throw std::runtime_error("a sweep did not jump");
    const double up_rpm = ups[static_cast<std::size_t>(ju)].sun_speed_rpm;
    const double down_rpm = downs[static_cast<std::size_t>(jd)].sun_speed_rpm;
    // The sweep rate: one step per skip and window (the window's 4 mesh cycles at the upper
    // jump's speed).
    const double dwell =
        up_sweep.plan.skip_time + 4 / ups[static_cast<std::size_t>(ju)].mesh_frequency;
    std::printf("%10.1f %12.1f %12.1f %12.1f %12.0f %10.1f\n", steps[s], up_rpm, down_rpm,
                up_rpm - down_rpm, steps[s] / dwell, cpu);
    if (s + 1 == steps.size()) {
      for (const auto* sw : {&ups, &downs}) {
        report::PlotSeries pts;
        pts.points = true;
        pts.colour = sw == &ups ? 1 : 2;
        std::snprintf(label, sizeof label, "%s, %.0f rpm steps", sw == &ups ? "up" : "down",
                      steps[s]);
        pts.name = label;
        for (const dynamics::SpeedResult& r : *sw) {
          pts.x.push_back(r.sun_speed_rpm);
          pts.y.push_back(r.te_amplitude * 1e6);
          char line[160];
          std::snprintf(line, sizeof line, "%s,%.6f,%.6f,\n", sw == &ups ? "up" : "down",
                        r.sun_speed_rpm, r.te_amplitude * 1e6);
          csv += line;
        }
        plot.series.push_back(std::move(pts));
      }
    }
  }
  std::filesystem::create_directories(dir);
  Write(dir / "periodic_jumps.csv", csv);
  Write(dir / "periodic_jumps.svg", report::RenderSvg(plot));
  std::printf("wrote %s\n", (dir / "periodic_jumps.svg").c_str());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "jumps: %s\n", e.what());
  return 1;
}
