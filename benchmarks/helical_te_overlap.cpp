// The transmission error's ripple of a helical stage against its overlap ratio ε_β (docs/
// face_width.md, "Helical meshes"): the paper stage's transverse section (paper_stage.toml, its
// FE bodies) with one planet (the sun–planet and planet–ring meshes of one planet in series,
// without the planets' phasing, which cancels most of a stage's ripple) given a helix of
// β = 0 … 30° (the same transverse module, so ε_β = b tan β/(π m_t)), swept quasi-statically over
// one mesh cycle with S slices of the face width, S = 20 and 40 (the slice discretisation's
// convergence). Writes <out>/helical_te_overlap.csv and .svg.
//
//   helical_te_overlap <out folder> [cache folder]
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "epicycle/report/svg_plot.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/helical_study.hpp"
#include "epicycle/transmission/scene.hpp"

namespace tr = epicycle::transmission;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: helical_te_overlap <out folder> [cache folder]\n";
    return 2;
  }
  const std::string out = argv[1];
  try {
    const tr::Scene scene = tr::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
    epicycle::geometry::StageSpec spur = scene.stage;
    spur.planets = 1;
    const epicycle::geometry::Stage body_stage(spur);
    tr::FeComplianceOptions fe;
    fe.cache_directory = argc > 2 ? argv[2] : tr::DefaultCacheDirectory();
    const tr::FeStageCompliance compliance(scene, body_stage, fe);
    constexpr int kPositions = 24;
    const std::vector<int> slice_counts = {20, 40};
    std::ofstream csv(out + "/helical_te_overlap.csv");
    csv << "beta_deg,eps_beta,te_pp_urad_S20,te_pp_urad_S40\n";
    std::vector<epicycle::report::PlotSeries> series(slice_counts.size());
    for (std::size_t k = 0; k < slice_counts.size(); ++k)
      series[k].name = "S = " + std::to_string(slice_counts[k]) + " slices";
    for (int deg = 0; deg <= 30; deg += 1) {
      const epicycle::geometry::Stage stage(
          tr::WithHelix(spur, deg * std::numbers::pi / 180, epicycle::geometry::Hand::kRight));
      const double eps = tr::StageOverlapRatio(stage);
      csv << deg << ',' << eps;
      for (std::size_t k = 0; k < slice_counts.size(); ++k) {
        tr::StageSetup setup = tr::SetupFromScene(scene);
        setup.face_width.slices = slice_counts[k];
        const tr::StageModel model(stage, compliance, setup);
        const double pp = tr::TransmissionErrorRipple(model, scene.loads, kPositions) * 1e6;
        csv << ',' << pp;
        series[k].x.push_back(eps);
        series[k].y.push_back(pp);
      }
      csv << '\n';
      std::fprintf(stderr, "beta %2d deg  eps_beta %.3f\n", deg, eps);
    }
    series[1].markers = true;
    epicycle::report::LinePlot plot;
    plot.title = "Helical paper stage, one planet: transmission error ripple vs overlap ratio";
    plot.x_label = "overlap ratio eps_beta [-] (beta 0..30 deg, m_t 4.23 mm, b 25 mm)";
    plot.y_label = "static TE peak to peak over a mesh cycle [urad]";
    plot.series = series;
    plot.x_markers = {{1.0, "eps_beta = 1", true, 0}};
    std::ofstream svg(out + "/helical_te_overlap.svg");
    svg << epicycle::report::RenderSvg(plot);
    if (!csv || !svg) {
      std::cerr << "helical_te_overlap: writing to " << out << " failed\n";
      return 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "helical_te_overlap: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
