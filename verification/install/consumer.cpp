// A user's program against the installed epicycle: reads a scene, builds the FE compliance of its
// stage and solves one quasi-static position. Checks what equilibrium requires whatever the
// geometry: the planets' load-sharing ratios sum to 1 (the sun's moment balance, solved to the
// contact tolerance 1e-10, hence 1e-9 as in the suite's FE checks) and each lies in [0, 1].
// Then the studies (epicycle::studies): a study file on that scene is read (a variable on
// "planets" becomes one per planet of the scene, σ in metres, cases = samples), and the
// statistics of 1, 2, ..., 100 are checked against their closed forms (mean 50.5, standard
// deviation √(100·101/12), median x_(50) = 50, Spearman's ρ of x and x³ = 1).
// Usage: consumer SCENE CACHE_DIR
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "epicycle/config.h"
#include "epicycle/studies/statistics.hpp"
#include "epicycle/studies/study.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/scene.hpp"

namespace {

// The studies' checks; false (with a message) on the first that fails.
bool CheckStudies(const std::string& scene_path) {
  namespace st = epicycle::studies;
  const std::filesystem::path scene(scene_path);
  const std::string text = "[study]\nname = \"consumer\"\nscene = \"" + scene.filename().string() +
                           "\"\nseed = 7\nsamples = 10\ncompute = \"mesh-cycle\"\n"
                           "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planets\"\n"
                           "distribution = \"normal\"\nsigma_um = 5.0\n";
  const st::StudySpec study = st::ParseStudy(text, "consumer.toml", scene.parent_path().string());
  const auto planets = static_cast<std::size_t>(study.scene.stage.planets);
  bool ok = study.Cases() == 10 && study.variables.size() == planets && planets > 0;
  // σ read in µm, held in m: 5 µm to the rounding of the unit's factor.
  for (const st::Variable& v : study.variables) ok = ok && std::abs(v.sigma / 5e-6 - 1) <= 1e-15;
  std::printf("study: %ld cases, %zu variables (one per planet), sigma %.17g m\n", study.Cases(),
              study.variables.size(), study.variables.empty() ? 0.0 : study.variables[0].sigma);
  if (!ok) {
    std::fprintf(stderr, "consumer: the study file was not read as written\n");
    return false;
  }
  std::vector<double> x, cube;
  for (int i = 1; i <= 100; ++i) {
    x.push_back(i);
    cube.push_back(static_cast<double>(i) * i * i);
  }
  const st::SampleSummary s = st::Summarise(x, {0.5});
  const double rho = st::SpearmanCorrelation(x, cube);
  std::printf("statistics of 1..100: mean %.12g, sd %.12g, median %.12g, Spearman %.12g\n", s.mean,
              s.standard_deviation, s.percentiles.at(0).value, rho);
  if (s.count != 100 || std::abs(s.mean - 50.5) > 1e-12 ||
      std::abs(s.standard_deviation / std::sqrt(100.0 * 101.0 / 12.0) - 1.0) > 1e-12 ||
      s.percentiles.at(0).value != 50.0 || std::abs(rho - 1.0) > 1e-12) {
    std::fprintf(stderr, "consumer: the statistics differ from their closed forms\n");
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: consumer SCENE CACHE_DIR\n");
    return 2;
  }
  try {
    if (!CheckStudies(argv[1])) return 1;
    namespace tr = epicycle::transmission;
    const tr::Scene scene = tr::ReadScene(argv[1]);
    const epicycle::geometry::Stage stage(scene.stage);
    tr::FeComplianceOptions fe;
    fe.cache_directory = argv[2];
    const tr::FeStageCompliance compliance(scene, stage, fe);
    const tr::StageModel model(stage, compliance, tr::SetupFromScene(scene));
    const tr::PositionResult r = tr::SolvePosition(model, 0.0, scene.loads, {});
    if (!r.converged) {
      std::fprintf(stderr, "consumer: the position did not converge: %s\n", r.message.c_str());
      return 1;
    }
    double sum = 0;
    bool in_range = true;
    for (double lsr : r.load_sharing) {
      std::printf("LSR %.9f\n", lsr);
      sum += lsr;
      in_range = in_range && lsr >= 0 && lsr <= 1;
    }
    std::printf("epicycle %s: %zu planets, sum of LSR - 1 = %.3e\n", EPICYCLE_VERSION,
                r.load_sharing.size(), sum - 1.0);
    return std::abs(sum - 1.0) <= 1e-9 && in_range ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
