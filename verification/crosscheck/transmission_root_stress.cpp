// Root stresses in the quasi-static driver (docs/model.md §9, docs/stresses.md): switching them on
// changes no force, and over a planet revolution a planet's fillets bend both ways (the idler's
// reversed bending). The stresses themselves are checked against the FE solved directly and
// against ISO 6336-3 in the compliance suite ("[stress]").
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "fe_fixtures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using namespace epicycle::transmission;

namespace {

struct Run {
  std::vector<PositionResult> results;
  SweepSummary summary;
};

// The run-out scene over one planet revolution (the period of everything that happens to a
// planet tooth), `positions` positions, fixed sun, root stresses on or off.
Run RunOut(bool root_stress, int positions) {
  Scene scene = ParseScene(test::SceneText("paper_stage_runout.toml"), "paper_stage_runout.toml");
  scene.model.stresses = root_stress;
  const geometry::Stage stage(scene.stage);
  const FeStageCompliance compliance(scene, stage, test::CachedTables());
  const StageModel model(stage, compliance, SetupFromScene(scene));
  QuasiStaticOptions options;
  options.threads = 1;
  const std::vector<double> angles =
      SweepAngles(0.0, CarrierSpan(stage, RunRange::kPlanetRevolution), positions);
  Run run;
  run.results = Sweep(model, scene.loads, angles, options);
  run.summary = SummariseSweep(run.results, stage.planets());
  return run;
}

}  // namespace

TEST_CASE("root stress: on, the forces are those of a run without it, to the bit",
          "[crosscheck][transmission][stress]") {
  // The stress tables come from the same unit-load solves as the compliance, whose values they
  // do not touch: every contact force and rigid displacement must be identical.
  const Run off = RunOut(false, 36), on = RunOut(true, 36);
  REQUIRE(off.results.size() == on.results.size());
  for (std::size_t k = 0; k < off.results.size(); ++k) {
    REQUIRE(off.results[k].converged);
    REQUIRE(on.results[k].converged);
    CHECK(off.results[k].fillet_stress.empty());
    CHECK_FALSE(on.results[k].fillet_stress.empty());
    CHECK(off.results[k].solution.force == on.results[k].solution.force);
    CHECK(off.results[k].displacements == on.results[k].displacements);
  }
  CHECK(off.summary.root_stress.empty());
  CHECK(on.summary.root_stress.size() == 5);
}

TEST_CASE("root stress: a planet bends both ways over its revolution",
          "[crosscheck][transmission][stress]") {
  const Run on = RunOut(true, 360);
  REQUIRE(on.summary.converged == 360);
  const auto& rs = on.summary.root_stress;
  // Every gear's loaded fillets: tension on the loaded side, compression on the other.
  for (const auto& g : rs) {
    INFO(BodyName(g.extremes.body));
    CHECK(g.extremes.tension > 50e6);
    CHECK(g.extremes.compression < -50e6);
  }
  // A planet tooth is driven on one flank by the sun and loads the ring with the other: at the
  // fillet point of its largest range it sees tension in one mesh and compression in the other,
  // each a sizeable part of the planet's extremes (ISO 6336-5's reversed bending of idlers).
  for (int i = 0; i < 3; ++i) {
    const auto& p = rs[static_cast<std::size_t>(PlanetBody(i))];
    INFO("planet " << i + 1 << ": range " << p.range.range / 1e6 << " MPa between "
                   << p.range.max / 1e6 << " and " << p.range.min / 1e6 << " MPa");
    CHECK(p.range.max > 0.25 * p.extremes.tension);
    CHECK(p.range.min < 0.25 * p.extremes.compression);
    CHECK(p.range.range > p.extremes.tension);
  }
  // Planet 1 (run-out 20 µm, K_γ 2.17) carries the most: its root stress exceeds the others'.
  CHECK(rs[PlanetBody(0)].extremes.tension > 1.2 * rs[PlanetBody(1)].extremes.tension);
  CHECK(rs[PlanetBody(0)].extremes.tension > 1.2 * rs[PlanetBody(2)].extremes.tension);
}
