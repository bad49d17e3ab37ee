// The dynamic run's sampling rule (dynamics::DefaultOutputsPerCycle) against the mode it must
// resolve, the plots' mesh-cycle envelope (report::BinEnvelope) against the raw states, and the
// load-sharing figure's panels.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/report/run_files.hpp"

using namespace epicycle;

TEST_CASE("outputs per mesh cycle: at least 10 per period of the highest mode below the cap",
          "[unit][report]") {
  // Outputs per period of f_max = N f_m / f_max, computed here from the frequencies, not the rule.
  // The paper stage at 1500 rpm: f_m = 325 Hz, f_max = 6742 Hz (`epicycle dynamic` prints both).
  for (double f_m : {0.2, 3.25, 32.5, 325.0, 3250.0})
    for (double f_max : {0.0, 100.0, 6742.0, 20000.0}) {
      const int n = dynamics::DefaultOutputsPerCycle(f_max, f_m);
      CHECK(n >= 20);
      CHECK(n <= dynamics::kOutputsPerModePeriod * dynamics::kMaxResolvedHarmonic);
      if (f_max > 0 && f_max <= dynamics::kMaxResolvedHarmonic * f_m)
        CHECK(n * f_m / f_max >= dynamics::kOutputsPerModePeriod);
      // Not more than needed: one output fewer per cycle breaks the rule (above the floor of 20).
      if (n > 20 && f_max <= dynamics::kMaxResolvedHarmonic * f_m)
        CHECK((n - 1) * f_m / f_max < dynamics::kOutputsPerModePeriod);
    }
  CHECK_THROWS_AS(dynamics::DefaultOutputsPerCycle(100, 0), std::invalid_argument);
}

TEST_CASE("mesh-cycle envelope: every raw state within its bin, the mean the bin's average",
          "[unit][report]") {
  // A signal sampled 37 times per cycle of width 0.5 (not a whole number per bin): a mean, a
  // vibration at 9.3 cycles per bin and a slow drift, two values.
  const double width = 0.5;
  report::BinEnvelope envelope(2, 0.0, width);
  std::vector<double> xs;
  std::vector<std::vector<double>> raw;
  for (int k = 1; k <= 37 * 20; ++k) {
    const double x = width * k / 37.0;
    const std::vector<double> v{1.0 / 3 + 0.05 * std::sin(2 * M_PI * 9.3 * x / width) + 0.01 * x,
                                -2.0 * std::cos(0.7 * x)};
    envelope.Add(x, v);
    xs.push_back(x);
    raw.push_back(v);
  }
  const auto bins = envelope.Bins();
  CHECK(bins.size() >= 20);
  long total = 0;
  for (const auto& b : bins) {
    total += b.count;
    for (std::size_t j = 0; j < 2; ++j) {
      double sum = 0, lo = INFINITY, hi = -INFINITY;
      long count = 0;
      for (std::size_t k = 0; k < xs.size(); ++k) {
        if (xs[k] < b.x_first || xs[k] > b.x_last) continue;
        ++count;
        sum += raw[k][j];
        lo = std::min(lo, raw[k][j]);
        hi = std::max(hi, raw[k][j]);
        CHECK(raw[k][j] >= b.min[j]);
        CHECK(raw[k][j] <= b.max[j]);
      }
      CHECK(count == b.count);
      CHECK(lo == b.min[j]);  // the extremes are raw values themselves
      CHECK(hi == b.max[j]);
      // Same sums in the same order: equal but for the division, 1 ulp of the mean.
      const double average = sum / static_cast<double>(count);
      CHECK(std::abs(b.mean[j] - average) <= 2.3e-16 * std::abs(average));
    }
    // A bin holds states of one mesh-cycle window only.
    CHECK(std::floor(b.x_first / width) == std::floor(b.x_last / width));
  }
  CHECK(total == static_cast<long>(xs.size()));
}

TEST_CASE("load-sharing figure of a long run: one panel per planet, all on one scale",
          "[unit][report]") {
  // 40 mesh cycles of 50 outputs: planet 1 swings between 0.1 and 0.5 within every cycle, planets
  // 2 and 3 share the rest; each panel must hold its planet's band and mean, every panel the same
  // y ticks (one scale), and the scale must reach both planet 1's 0.1 and its 0.5.
  dynamics::RunSpan span;
  span.cycle_time = 1e-3;
  span.duration = 40e-3;
  span.outputs = 2000;
  span.mesh_frequency = 1e3;
  const std::string base =
      (std::filesystem::temp_directory_path() / "epicycle_lsr_panels").string();
  {
    report::DynamicPlots plots(base, 3, span);
    for (int k = 1; k <= span.outputs; ++k) {
      dynamics::DynamicSample s;
      s.time = span.duration * k / span.outputs;
      const double l1 = 0.3 + 0.2 * std::sin(2 * std::numbers::pi * k / 50.0);
      s.load_sharing = {l1, (1 - l1) / 2, (1 - l1) / 2};
      s.sun_centre = geometry::Vec2(0.0, 0.0);
      plots.Add(s);
    }
    plots.Write("test", "fixed");
  }
  std::ifstream in(base + "_lsr.svg");
  std::stringstream text;
  text << in.rdbuf();
  const std::string svg = text.str();
  // The panels are nested documents, one per planet.
  std::vector<std::string> panels;
  for (std::size_t at = svg.find("<svg x=\"0\""); at != std::string::npos;
       at = svg.find("<svg x=\"0\"", at + 1)) {
    panels.push_back(svg.substr(at, svg.find("</svg>", at) - at));
  }
  REQUIRE(panels.size() == 3);
  std::set<std::string> scales;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const std::string& p = panels[i];
    CHECK(p.find("planet " + std::to_string(i + 1)) != std::string::npos);
    CHECK(p.find("<polygon") != std::string::npos);   // the band
    CHECK(p.find("<polyline") != std::string::npos);  // the mean
    // The y tick labels (right-aligned text left of the plot) name the panel's scale.
    std::string ticks;
    const std::regex tick("text-anchor=\"end\">([-0-9.e]+)</text>");
    for (auto it = std::sregex_iterator(p.begin(), p.end(), tick); it != std::sregex_iterator();
         ++it)
      ticks += (*it)[1].str() + " ";
    scales.insert(ticks);
    if (i == 0) {
      CHECK(ticks.find("0.1 ") != std::string::npos);
      CHECK(ticks.find("0.5 ") != std::string::npos);
    }
  }
  CHECK(scales.size() == 1);
}
