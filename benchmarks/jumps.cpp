// The jumps of the light-torque paper stage with a pin error (docs/periodic.md §3, "Jumps"): a
// plain program. It continues the periodic orbits over the sun speed from both sides of the
// resonance (their folds), runs carried time-integration sweeps up and down at several speed
// steps (dynamic --speed-sweep --carry-state), prints where each sweep jumps, and writes
// docs/figures/periodic_jumps.csv and .svg (TE amplitude against speed: stable orbits solid,
// unstable dashed, the folds marked, the finest sweeps' points).
//
//   build/benchmarks/jumps [OUT_DIR] [STEP_RPM ...]   (default docs/figures; steps 200 100 50)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/dynamics/jumps.hpp"
#include "epicycle/report/branch_files.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/scene.hpp"

using namespace epicycle;

int main(int argc, char** argv) try {
  const std::filesystem::path dir =
      argc > 1 ? argv[1] : std::filesystem::path(EPICYCLE_SOURCE_DIR) / "docs/figures";
  std::vector<double> steps;
  for (int k = 2; k < argc; ++k) {
    char* end = nullptr;
    const double step = std::strtod(argv[k], &end);
    if (end == argv[k] || *end != '\0' || !(step > 0) || !std::isfinite(step)) {
      std::fprintf(stderr, "jumps: STEP_RPM = '%s': must be a number > 0 [rpm]\n", argv[k]);
      return 2;
    }
    steps.push_back(step);
  }
  if (steps.empty()) steps = {200, 100, 50};

  dynamics::JumpRequest request;
  request.run.scene = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) +
                                              "/paper_stage_light_pin_error.toml");
  request.run.tables.cache_directory = transmission::DefaultCacheDirectory();
  request.below_rpm = 10800;  // the branches: from below the resonance, from above it
  request.above_rpm = 13200;
  request.sweep_from_rpm = 11000;  // the sweeps: both folds inside
  request.sweep_to_rpm = 12800;
  request.steps_rpm = steps;
  const dynamics::JumpStudy study = dynamics::RunJumps(request);
  std::printf("folds: %.2f and %.2f rpm (%.1f s and %.1f s CPU, %zu and %zu points); TE "
              "amplitude between the orbits %.2f urad\n",
              study.lower_fold_rpm, study.upper_fold_rpm, study.from_below.cpu_seconds,
              study.from_above.cpu_seconds, study.from_below.points.size(),
              study.from_above.points.size(), study.te_threshold * 1e6);

  std::string csv = "series,sun_speed_rpm,te_amplitude_urad,stability\n";
  report::LinePlot plot;
  plot.title = "Paper stage, -50 N·m, planet 1's pin 2 µm tangential: jumps";
  plot.x_label = "sun speed [rpm]";
  plot.y_label = "TE amplitude [µrad]";
  for (const dynamics::StageBranchRecord* b : {&study.from_below, &study.from_above}) {
    const bool first = b == &study.from_below;
    std::vector<double> x, y;
    std::vector<bool> stable;
    for (const dynamics::StageBranchPoint& p : b->points) {
      x.push_back(p.parameter);
      y.push_back(p.te_amplitude * 1e6);
      stable.push_back(p.stability != dynamics::Stability::kUnstable);
      char line[160];
      std::snprintf(line, sizeof line, "%s,%.6f,%.6f,%s\n", first ? "from below" : "from above",
                    x.back(), y.back(), stable.back() ? "stable" : "unstable");
      csv += line;
    }
    for (report::PlotSeries& seg : report::StabilitySegments("orbits", x, y, stable)) {
      if (!first) seg.name.clear();  // one legend entry per style
      plot.series.push_back(std::move(seg));
    }
  }
  char label[80];
  for (double fold : {study.lower_fold_rpm, study.upper_fold_rpm}) {
    std::snprintf(label, sizeof label, "fold %.0f rpm", fold);
    plot.x_markers.push_back({fold, label, true, 0});
  }

  std::printf("%10s %12s %12s %12s %12s %10s\n", "step rpm", "up jump rpm", "down jump rpm",
              "gap rpm", "rate rpm/s", "CPU s");
  for (const dynamics::JumpSweeps& j : study.sweeps) {
    std::printf("%10.1f %12.1f %12.1f %12.1f %12.0f %10.1f\n", j.step_rpm, j.up_jump_rpm,
                j.down_jump_rpm, j.up_jump_rpm - j.down_jump_rpm, j.rate_rpm_per_s(),
                j.up.cpu_seconds + j.down.cpu_seconds);
  }
  const dynamics::JumpSweeps& finest = study.sweeps.back();
  for (const dynamics::SpeedSweepRecord* sw : {&finest.up, &finest.down}) {
    const bool up = sw == &finest.up;
    report::PlotSeries pts;
    pts.points = true;
    pts.colour = up ? 1 : 2;
    std::snprintf(label, sizeof label, "%s, %.0f rpm steps", up ? "up" : "down", finest.step_rpm);
    pts.name = label;
    for (const dynamics::SpeedResult& r : sw->speeds) {
      pts.x.push_back(r.sun_speed_rpm);
      pts.y.push_back(r.te_amplitude * 1e6);
      char line[160];
      std::snprintf(line, sizeof line, "%s,%.6f,%.6f,\n", up ? "up" : "down", r.sun_speed_rpm,
                    r.te_amplitude * 1e6);
      csv += line;
    }
    plot.series.push_back(std::move(pts));
  }
  std::filesystem::create_directories(dir);
  report::WriteTextFile((dir / "periodic_jumps.csv").string(), csv);
  report::WriteTextFile((dir / "periodic_jumps.svg").string(), report::RenderSvg(plot));
  std::printf("wrote %s\n", (dir / "periodic_jumps.svg").c_str());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "jumps: %s\n", e.what());
  return 1;
}
