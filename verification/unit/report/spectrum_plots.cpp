// The spectrum figures (report::SpectrumSvg, docs/spectra.md): which lines are marked
// for which damage, and where their labels go.
#include <catch2/catch.hpp>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "epicycle/dynamics/spectrum.hpp"
#include "epicycle/report/spectrum_files.hpp"
#include "spectrum_fixtures.hpp"

using namespace epicycle;

namespace {

struct Label {
  int panel = 0;
  double x = 0, y = 0;
  std::string text;
  bool end = false;
};

// Every marker label of a figure, with its panel (0: the first), and every marker line's x per
// panel. Panels are nested <svg x="0" y="..."> documents, each in its own coordinates.
void Parse(const std::string& svg, std::vector<Label>* labels,
           std::vector<std::vector<double>>* lines) {
  std::vector<std::string> panels;
  const std::string open = "<svg x=\"0\" y=\"";
  std::size_t at = svg.find(open);
  if (at == std::string::npos) {
    panels.push_back(svg);
  } else {
    while (at != std::string::npos) {
      const std::size_t next = svg.find(open, at + 1);
      panels.push_back(svg.substr(at, next == std::string::npos ? std::string::npos : next - at));
      at = next;
    }
  }
  const std::regex label(
      "<text x=\"([0-9.]+)\" y=\"([0-9.]+)\" fill=\"#555\" font-size=\"10\"( "
      "text-anchor=\"end\")?>([^<]*)</text>");
  const std::regex line(
      "<line x1=\"([0-9.]+)\" y1=\"40\" x2=\"[0-9.]+\" y2=\"[0-9.]+\" "
      "stroke=\"(#888|#d8d8d8)\"");
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const std::string& s = panels[p];
    for (auto it = std::sregex_iterator(s.begin(), s.end(), label); it != std::sregex_iterator();
         ++it)
      labels->push_back({static_cast<int>(p), std::stod((*it)[1].str()), std::stod((*it)[2].str()),
                         (*it)[4].str(), (*it)[3].matched});
    lines->emplace_back();
    for (auto it = std::sregex_iterator(s.begin(), s.end(), line); it != std::sregex_iterator();
         ++it)
      lines->back().push_back(std::stod((*it)[1].str()));
  }
}

// A spectrum at Δf = f_c up to 12 f_m: a floor of 1e-3 with 1 at every bin.
std::vector<double> Flat(const dynamics::StageFrequencies& f) {
  return std::vector<double>(static_cast<std::size_t>(std::lround(12 * f.mesh / f.carrier)) + 1,
                             1e-3);
}

bool Has(const std::vector<Label>& labels, const std::string& text) {
  for (const Label& l : labels)
    if (l.text == text) return true;
  return false;
}

}  // namespace

TEST_CASE(
    "spectrum figures: the healthy lines always, the scene's own fault lines only, each label "
    "right of its own line inside its panel",
    "[unit][report]") {
  // The paper stage's ring mounting force (a housing signal). By hand (docs/damage.md "Which
  // lines a tooth fault puts into which signal"): healthy h f_m + f_c for h = 1, 4, 7, 10 and
  // h f_m − f_c for h = 2, 5, 8, 11 (16 h ≡ ±1 mod 3); a sun tooth's f_s and
  // k n (f_s − f_c) ± f_s; a planet tooth's f_c and k f_m/z_p ± f_c. A healthy scene: one panel,
  // no fault label; a sun tooth: a second panel with the sun tooth's lines and no planet's or
  // ring's; a planet tooth the other way round. Every label: anchored at its start, 2 px right
  // of a marker line of its panel, inside the plot area (x 90 … 610 px, y 40 … 340 px for
  // panels 400 px high), no two overlapping in a row (about 5.6 px per character plus 4).
  // The paper stage at 1500 rpm: 16/24/65 teeth, 3 planets, f_s = 25 Hz.
  const dynamics::StageFrequencies f = test::KinematicFrequencies(16, 24, 65, 3, 25.0);
  report::SpectrumFigure figure;
  figure.title = "paper stage: ring_force_x";
  figure.y_label = "ring_force_x amplitude [N]";
  figure.legend = "1 segment";
  figure.kind = dynamics::SignalKind::kHousing;
  figure.frequencies = f;
  const std::vector<double> amplitude = Flat(f);
  for (const auto& faults : std::vector<std::vector<dynamics::LineKind>>{
           {}, {dynamics::LineKind::kSunTooth}, {dynamics::LineKind::kPlanetTooth}}) {
    figure.faults = faults;
    const std::string svg = report::SpectrumSvg(figure, amplitude, f.carrier);
    std::vector<Label> labels;
    std::vector<std::vector<double>> lines;
    Parse(svg, &labels, &lines);
    const bool sun = !faults.empty() && faults[0] == dynamics::LineKind::kSunTooth;
    const bool planet = !faults.empty() && faults[0] == dynamics::LineKind::kPlanetTooth;
    INFO("faults: " << (sun ? "sun tooth" : planet ? "planet tooth" : "none"));
    CHECK(lines.size() == (faults.empty() ? 1u : 2u));
    for (const char* healthy : {"f_m + f_c", "2 f_m - f_c", "4 f_m + f_c", "11 f_m - f_c"})
      CHECK(Has(labels, healthy));
    CHECK(Has(labels, "f_s") == sun);
    CHECK(Has(labels, "n (f_s - f_c) + f_s") == sun);
    CHECK(Has(labels, "3 x n (f_s - f_c) - f_s") == sun);
    CHECK(Has(labels, "f_m/z_p + f_c") == planet);
    CHECK(Has(labels, "f_c") == planet);
    for (const Label& l : labels) {
      INFO("label '" << l.text << "' in panel " << l.panel << " at x " << l.x << ", y " << l.y);
      // Nothing of another family, nor the former rule's k n (f_s - f_c) at the housing.
      CHECK(l.text.find("n f_c") == std::string::npos);
      CHECK(l.text != "n (f_s - f_c)");
      CHECK_FALSE(l.end);
      bool own = false;
      for (double x : lines[static_cast<std::size_t>(l.panel)])
        own = own || std::abs(l.x - 2 - x) < 0.11;
      CHECK(own);
      const double to = l.x - 2 + 5.6 * static_cast<double>(l.text.size()) + 4;
      CHECK(l.x - 2 >= 90);
      CHECK(to <= 610 + 1e-9);
      CHECK(l.y > 40);
      CHECK(l.y < 340);
      for (const Label& m : labels) {
        if (&m == &l || m.panel != l.panel || m.y != l.y) continue;
        const double m_to = m.x - 2 + 5.6 * static_cast<double>(m.text.size()) + 4;
        CHECK((to <= m.x - 2 + 1e-9 || m_to <= l.x - 2 + 1e-9));
      }
    }
  }
}
