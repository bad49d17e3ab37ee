// A user's program against the installed epicycle: reads a scene, builds the FE compliance of its
// stage and solves one quasi-static position. Checks what equilibrium requires whatever the
// geometry: the planets' load-sharing ratios sum to 1 (the sun's moment balance, solved to the
// contact tolerance 1e-10, hence 1e-9 as in the suite's FE checks) and each lies in [0, 1].
// Usage: consumer SCENE CACHE_DIR
#include <cmath>
#include <cstdio>
#include <exception>

#include "epicycle/config.h"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/scene.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: consumer SCENE CACHE_DIR\n");
    return 2;
  }
  try {
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
