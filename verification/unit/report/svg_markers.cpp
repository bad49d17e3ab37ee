// The line plot's vertical markers (report::XMarker): labels placed by rank inside the plot,
// never over each other, and the markers left without room drawn without a label.
#include <catch2/catch.hpp>

#include <map>
#include <regex>
#include <string>

#include "epicycle/report/svg_plot.hpp"

using namespace epicycle;

TEST_CASE("marker labels: by rank, inside the plot, never overlapping", "[unit][report]") {
  // 60 markers 1 unit apart over a 520 px wide plot of 61 units (8.5 px apart) with labels about
  // 40 px wide: at most eight rows hold a few of them; the lowest ranks (every tenth marker has
  // rank 0) must all be labelled, and no two labels in a row may overlap.
  report::LinePlot p{"markers", "x", "y", {{"s", {0.0, 61.0}, {0.0, 1.0}}}, false, {}};
  for (int k = 1; k <= 60; ++k)
    p.x_markers.push_back({static_cast<double>(k), "m1 h" + std::to_string(k), false,
                           k % 10 == 0 ? 0 : k});
  const std::string svg = report::RenderSvg(p);
  const std::regex label(
      "<text x=\"([0-9.]+)\" y=\"([0-9.]+)\" fill=\"#555\" font-size=\"10\"( "
      "text-anchor=\"end\")?>m1 h([0-9]+)</text>");
  std::map<double, std::vector<std::pair<double, double>>> rows;  // y -> [from, to] [px]
  std::map<int, bool> labelled;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator();
       ++it) {
    const double x = std::stod((*it)[1].str()), y = std::stod((*it)[2].str());
    const std::string name = "m1 h" + (*it)[4].str();
    const double width = 5.6 * static_cast<double>(name.size()) + 4;
    const bool end = (*it)[3].matched;
    const double from = end ? x + 2 - width : x - 2, to = from + width;
    labelled[std::stoi((*it)[4].str())] = true;
    // Inside the plot area: top 40 px, 380 px high (the default figure).
    CHECK(y > 40);
    CHECK(y < 40 + 380);
    for (const auto& [a, b] : rows[y]) CHECK((to <= a + 1e-9 || b <= from + 1e-9));
    rows[y].emplace_back(from, to);
  }
  CHECK(rows.size() <= 8);
  for (int k = 10; k <= 60; k += 10) CHECK(labelled[k]);
  CHECK(labelled.size() < 60);  // not all fit: the rest are lines without a label
  // Every marker is drawn as a line, labelled or not.
  const std::regex line(
      "<line x1=\"[0-9.]+\" y1=\"40\" x2=\"[0-9.]+\" y2=\"420\" stroke=\"(#888|#d8d8d8)\"");
  CHECK(std::distance(std::sregex_iterator(svg.begin(), svg.end(), line), std::sregex_iterator()) ==
        60);
}
