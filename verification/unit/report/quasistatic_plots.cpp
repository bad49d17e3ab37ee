// The plots of a quasi-static sweep gathered one position at a time (report::QuasiStaticPlots):
// up to kPlotPoints positions every converged one is a point of its polyline; a longer sweep
// draws at most kPlotPoints points per series whatever its length, and a one-position peak still
// shows (each bin keeps its lowest and highest point).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "epicycle/report/run_files.hpp"

using namespace epicycle;

namespace {

// The points of each polyline of an SVG file, as (x, y) pixel strings.
std::vector<std::vector<std::string>> Polylines(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  std::vector<std::vector<std::string>> out;
  for (std::size_t at = s.find("points=\""); at != std::string::npos;
       at = s.find("points=\"", at + 1)) {
    const std::size_t from = at + 8, to = s.find('"', from);
    std::istringstream points(s.substr(from, to - from));
    out.emplace_back();
    for (std::string p; points >> p;) out.back().push_back(p);
  }
  return out;
}

// Plots of `count` positions: LSR = 1/3 each, TE 1 µrad, the sun at (1, 0) µm, but position
// `peak` where planet 1 carries 0.9 (and planet 2 the rest); position 1 fails.
std::string Plot(long count, long peak, const std::string& name) {
  const std::string base = (std::filesystem::temp_directory_path() / name).string();
  report::QuasiStaticPlots plots(base, 3, count);
  for (long k = 0; k < count; ++k) {
    transmission::PositionResult r;
    r.carrier_angle = 1e-3 * static_cast<double>(k) / static_cast<double>(count);
    r.converged = k != 1;
    r.load_sharing = k == peak ? std::vector<double>{0.9, 0.1 - 1e-9, 1e-9}
                               : std::vector<double>{1.0 / 3, 1.0 / 3, 1.0 / 3};
    r.transmission_error = 1e-6;
    r.sun_displacement = geometry::Vec2(1e-6, 0.0);
    plots.Add(r);
  }
  plots.Write("test", "fixed");
  return base;
}

}  // namespace

TEST_CASE("quasi-static plots: every point of a short sweep, a bounded number of a long one",
          "[unit][report]") {
  const long most = report::QuasiStaticPlots::kPlotPoints;
  // A short sweep: every converged position is a point (one failed of `most`).
  auto lines = Polylines(Plot(most, 7, "epicycle_plots_short") + "_lsr.svg");
  REQUIRE(lines.size() == 3);
  for (const auto& l : lines) CHECK(l.size() == static_cast<std::size_t>(most - 1));
  // A long sweep: at most `most` points per series, and planet 1's peak at one position of
  // 200 001 still drawn: its polyline takes two heights (1/3 and 0.9), not one.
  const std::string base = Plot(200001, 123457, "epicycle_plots_long");
  lines = Polylines(base + "_lsr.svg");
  REQUIRE(lines.size() == 3);
  for (const auto& l : lines) CHECK(l.size() <= static_cast<std::size_t>(most));
  std::set<std::string> heights;
  for (const std::string& p : lines[0]) heights.insert(p.substr(p.find(',') + 1));
  CHECK(heights.size() == 2);
  for (const char* f : {"_te.svg", "_sun_path.svg"}) {
    lines = Polylines(base + f);
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].size() <= static_cast<std::size_t>(most));
    CHECK(lines[0].size() >= static_cast<std::size_t>(most / 4));  // one point a bin at least
  }
}
