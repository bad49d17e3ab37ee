// The line plot's vertical markers (report::XMarker): labels placed by rank inside the plot,
// never over each other, and the markers left without room drawn without a label.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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

namespace {

// The marker labels of one plot (a whole SVG from RenderSvg): x, y of the text, its label, and
// whether it is anchored at its end.
struct Label {
  double x = 0, y = 0;
  std::string text;
  bool end = false;
};

std::vector<Label> Labels(const std::string& svg) {
  const std::regex label(
      "<text x=\"([0-9.]+)\" y=\"([0-9.]+)\" fill=\"#555\" font-size=\"10\"( "
      "text-anchor=\"end\")?>([^<]*)</text>");
  std::vector<Label> out;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator();
       ++it)
    out.push_back(
        {std::stod((*it)[1].str()), std::stod((*it)[2].str()), (*it)[4].str(), (*it)[3].matched});
  return out;
}

// The x [px] of every marker line (drawn from the plot's top, 40 px, to its bottom).
std::vector<double> MarkerLines(const std::string& svg) {
  const std::regex line(
      "<line x1=\"([0-9.]+)\" y1=\"40\" x2=\"[0-9.]+\" y2=\"[0-9.]+\" "
      "stroke=\"(#888|#d8d8d8)\"");
  std::vector<double> out;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), line); it != std::sregex_iterator();
       ++it)
    out.push_back(std::stod((*it)[1].str()));
  return out;
}

}  // namespace

TEST_CASE(
    "marker labels right of their lines: each starts at its own line, inside the plot, never "
    "overlapping, the axis long enough for the last",
    "[unit][report]") {
  // Twelve markers 1 unit apart over data from 0 to 12 (a spectrum's mesh harmonics up to the
  // Nyquist frequency) and a long label at 10.985 (11 f_m - f_c): with labels_right every label
  // must start 2 px right of its own line (text anchored at its start), end inside the plot area
  // (x 90 … 610 px of the default figure), and no two in a row overlap; the labels of 11.985 and 12
  // cannot fit right of their lines inside a 12-unit axis, so the axis must reach further.
  report::LinePlot p{"markers", "x", "y", {{"s", {0.0, 12.0}, {1.0, 2.0}}}, false, {}};
  for (int k = 1; k <= 12; ++k)
    p.x_markers.push_back({static_cast<double>(k), std::to_string(k) + " f_m", false, 0});
  p.x_markers.push_back({10.985, "11 f_m - f_c", true, 0});
  p.labels_right = true;
  const std::string svg = report::RenderSvg(p);
  const std::vector<Label> labels = Labels(svg);
  const std::vector<double> lines = MarkerLines(svg);
  REQUIRE(lines.size() == 13);
  CHECK(labels.size() == 13);  // room for all: the axis reaches past 12
  std::map<double, std::vector<std::pair<double, double>>> rows;
  for (const Label& l : labels) {
    INFO("label " << l.text << " at x " << l.x << ", y " << l.y);
    CHECK_FALSE(l.end);
    const double width = 5.6 * static_cast<double>(l.text.size()) + 4;
    const double from = l.x - 2, to = from + width;
    // Its own line 1 px left of the ground it is drawn on, 2 px left of the text.
    bool found = false;
    for (double x : lines) found = found || std::abs(x - from) < 0.11;
    CHECK(found);
    CHECK(from >= 90);
    CHECK(to <= 610 + 1e-9);
    CHECK(l.y > 40);
    CHECK(l.y < 420);
    for (const auto& [a, b] : rows[l.y]) CHECK((to <= a + 1e-9 || b <= from + 1e-9));
    rows[l.y].emplace_back(from, to);
  }
  // The marker at 12 and its label "12 f_m" (6 characters, 37.6 px) end inside 520 px: the axis
  // reaches at least 12/(1 − 39.6/520) = 12.99 units; the data still end at 12.
  CHECK(*std::max_element(lines.begin(), lines.end()) < 610 - 37.6);
}

TEST_CASE("a y label longer than the plot is broken between words, inside the image",
          "[unit][report]") {
  // The dynamic TE plot's label (83 characters) on a 480 px figure: about 0.6 em per character at
  // 12 px, 600 px in one line, more than the image's height. Each turned line centred on the plot
  // (y = 230) must stay within the image, its glyphs right of x = 0 (a line's glyphs lie about
  // one font size left of its x), and the words must all be there in order.
  const std::string label =
      "sun rotation from kinematic [urad] (mean per mesh cycle, band: lowest to highest)";
  report::LinePlot p{"te", "time [ms]", label, {{"s", {0.0, 1.0}, {0.0, 1.0}}}, false, {}};
  const std::string svg = report::RenderSvg(p);
  const std::regex turned(
      "<text x=\"([0-9.]+)\" y=\"([0-9.]+)\" transform=\"rotate\\(-90 "
      "[0-9. ]+\\)\" text-anchor=\"middle\"( font-size=\"([0-9.]+)\")?>([^<]*)"
      "</text>");
  std::string joined;
  int count = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), turned); it != std::sregex_iterator();
       ++it) {
    const double x = std::stod((*it)[1].str()), y = std::stod((*it)[2].str());
    const double size = (*it)[4].matched ? std::stod((*it)[4].str()) : 12.0;
    const std::string text = (*it)[5].str();
    const double length = 0.6 * size * static_cast<double>(text.size());
    INFO("line '" << text << "' at x " << x << ", " << length << " px long");
    CHECK(y - length / 2 >= 0);
    CHECK(y + length / 2 <= 480);
    CHECK(x - size >= 0);
    CHECK(x < 90 - 40);  // clear of the tick labels (end-anchored at 86 px)
    joined += (joined.empty() ? "" : " ") + text;
    ++count;
  }
  CHECK(count == 2);
  CHECK(joined == label);
}

TEST_CASE("a curve denser than the pixels is drawn light under its upper envelope",
          "[unit][report]") {
  // 5201 points over the 520 px plot, alternating 1 and 1e-6 on a log axis (a comb of lines one
  // bin apart, 1 at both ends): the envelope has one point per pixel column (≤ 521), every one at
  // the top of the plot (the decade of 1, y = 40 px); the data are still drawn, thin and light.
  report::PlotSeries comb{"comb", {}, {}};
  comb.envelope = true;
  for (int k = 0; k <= 5200; ++k) {
    comb.x.push_back(k);
    comb.y.push_back(k % 2 == 0 ? 1.0 : 1e-6);
  }
  report::LinePlot p{"comb", "bin", "amplitude", {comb}, false, {}};
  p.log_y = true;
  const std::string svg = report::RenderSvg(p);
  // The polylines, found by hand (std::regex recurses per character: too deep for 5200 points).
  std::vector<std::pair<double, std::string>> found;  // stroke width, points
  for (std::size_t at = svg.find("<polyline"); at != std::string::npos;
       at = svg.find("<polyline", at + 1)) {
    const std::size_t w = svg.find("stroke-width=\"", at) + 14, q = svg.find("points=\"", at) + 8;
    found.emplace_back(std::stod(svg.substr(w, svg.find('"', w) - w)),
                       svg.substr(q, svg.find('"', q) - q));
  }
  REQUIRE(found.size() == 2);
  CHECK(found[0].first < 1);  // the data, thin
  int points = 0;
  bool at_top = true;
  std::istringstream envelope(found[1].second);
  for (std::string xy; envelope >> xy; ++points)
    at_top = at_top && std::abs(std::stod(xy.substr(xy.find(',') + 1)) - 40) < 0.05;
  CHECK(points <= 521);
  CHECK(points >= 500);
  CHECK(at_top);
}
