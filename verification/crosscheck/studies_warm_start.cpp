// The studies' warm start across cases (docs/studies.md "Throughput"): a case's first carrier
// position starts from the converged first position of its grid point's first case instead of
// its kinematic poses. Like the sweep's warm start from a neighbour (docs/quasistatic.md "Sweep
// cost"), it may change a result only within what the stopping rules allow: per position, the
// rigid displacements within 2(τ + ε ℓ*) and each LSR_i within the first-order force response to
// that plus ε F* per contact (the bounds derived in transmission_quasistatic_sweep.cpp,
// verification/support/sweep_bounds.hpp, evaluated at each cold position); so a row's K_γ =
// max_k n LSR_i(k) within n times the largest LSR bound. The reference is the cold path: the same
// case with its first position solved from the kinematic poses (RunOptions::warm_start_cases =
// false, the program's path before the warm start). On both shipped studies: pin-hole errors with
// the sun fixed (mesh cycles), and run-outs, thickness and pin errors with the sun floating over a
// torque grid (planet revolutions).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/sampling.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "figures.hpp"
#include "program_runs.hpp"
#include "sweep_bounds.hpp"

using namespace epicycle;
using test::Sci;
using transmission::PositionResult;

namespace {

// Case k's rig, as the runner builds it.
struct CaseRig {
  transmission::Scene scene;
  geometry::Stage stage;
  transmission::StageSetup setup;
  std::unique_ptr<transmission::StageModel> model;
  std::vector<double> angles;
  transmission::QuasiStaticOptions options;
  CaseRig(const studies::StudySpec& study, const transmission::StageCompliance& compliance, long k)
      : scene(studies::CaseScene(study, studies::SampleCase(study, k))),
        stage(transmission::MakeStage(scene)),
        setup(transmission::SetupFromScene(scene)) {
    if (study.sun) setup.sun = *study.sun;
    model = std::make_unique<transmission::StageModel>(stage, compliance, setup);
    angles = transmission::SweepAngles(
        study.start_angle,
        transmission::CarrierSpan(stage, study.compute == studies::CaseKind::kMeshCycle
                                             ? transmission::RunRange::kMeshCycle
                                             : transmission::RunRange::kPlanetRevolution),
        study.positions);
    options.backend = study.backend;
    options.threads = 1;
  }
  std::vector<PositionResult> Sweep(const PositionResult* start) const {
    std::vector<PositionResult> out;
    transmission::SweepEach(
        *model, scene.loads, static_cast<int>(angles.size()),
        [&](int i) { return angles[static_cast<std::size_t>(i)]; }, options,
        [&](const PositionResult& r, int) { out.push_back(r); }, start);
    return out;
  }
};

}  // namespace

TEST_CASE("study warm start across cases: within the stopping rules' bounds of the cold path",
          "[crosscheck][studies]") {
  struct Shipped {
    const char* file;
    long cases;  // the first cases checked
  };
  for (const Shipped& shipped :
       {Shipped{"pin_tolerance.toml", 12}, Shipped{"grades_and_torque.toml", 6}}) {
    const studies::StudySpec study =
        studies::ReadStudy(std::string(EPICYCLE_SCENES_DIR) + "/studies/" + shipped.file);
    transmission::FeComplianceOptions fe;
    fe.cache_directory = EPICYCLE_TEST_CACHE_DIR;
    const transmission::FeStageCompliance compliance(study.scene,
                                                     transmission::MakeStage(study.scene), fe);
    // The starts, computed here: each grid point's first case, its first position solved cold.
    std::vector<PositionResult> starts;
    for (long g = 0; g < study.GridPoints(); ++g) {
      const CaseRig rig(study, compliance, g);
      starts.push_back(transmission::SolvePosition(*rig.model, rig.angles.front(), rig.scene.loads,
                                                   rig.options));
      REQUIRE(starts.back().converged);
    }
    // The runner's rows, warm and cold, for the first cases.
    test::TempDir dir("study-warm");
    studies::RunOptions o;
    o.cache_directory = EPICYCLE_TEST_CACHE_DIR;
    o.threads = 2;
    o.max_new_cases = shipped.cases;
    o.rows_file = dir.File("warm.csv");
    const studies::RunReport warm = studies::RunStudy(study, o);
    o.rows_file = dir.File("cold.csv");
    o.warm_start_cases = false;
    const studies::RunReport cold = studies::RunStudy(study, o);
    REQUIRE(warm.rows.size() == static_cast<std::size_t>(shipped.cases));
    REQUIRE(cold.rows.size() == warm.rows.size());
    double worst_ratio = 0, worst_k_gamma = 0, worst_k_gamma_ratio = 0;
    int first_cold = 0, first_warm = 0;
    for (long k = 0; k < shipped.cases; ++k) {
      INFO(shipped.file << " case " << k);
      const CaseRig rig(study, compliance, k);
      const PositionResult& start = starts[static_cast<std::size_t>(k % study.GridPoints())];
      const auto w = rig.Sweep(&start);
      const auto c = rig.Sweep(nullptr);
      REQUIRE(w.size() == c.size());
      CHECK(w.front().warm_started);
      CHECK(!c.front().warm_started);
      first_warm += w.front().contact_iterations;
      first_cold += c.front().contact_iterations;
      const test::Comparison cmp =
          test::CompareSweeps(*rig.model, rig.options, rig.scene.loads.sun_torque, w, c);
      CHECK(cmp.displacement_ratio <= 1.0);
      CHECK(cmp.lsr_ratio <= 1.0);
      worst_ratio = std::max({worst_ratio, cmp.displacement_ratio, cmp.lsr_ratio});
      // The rows: the runner's warm row is this start's (the same bytes: the runner's start is
      // case g's cold first position, computed the same way), its cold row the cold path's, and
      // their K_γ within n times the largest LSR bound over the case's positions.
      const studies::CaseRow& rw = warm.rows[static_cast<std::size_t>(k)];
      const studies::CaseRow& rc = cold.rows[static_cast<std::size_t>(k)];
      REQUIRE(rw.ok());
      REQUIRE(rc.ok());
      CHECK(rw.Format() == studies::ComputeCase(study, compliance, k, "", &start).Format());
      CHECK(rc.Format() == studies::ComputeCase(study, compliance, k, "").Format());
      double lsr_bound = 0;
      for (const PositionResult& r : c) {
        const test::Bounds b =
            test::DerivedBounds(*rig.model, rig.options, rig.scene.loads.sun_torque, r);
        lsr_bound = std::max(lsr_bound, *std::max_element(b.lsr.begin(), b.lsr.end()));
      }
      const double n = static_cast<double>(rig.model->planets());
      const double dk = std::abs(rw.k_gamma - rc.k_gamma);
      CHECK(dk <= n * lsr_bound);
      worst_k_gamma = std::max(worst_k_gamma, dk);
      worst_k_gamma_ratio = std::max(worst_k_gamma_ratio, dk / (n * lsr_bound));
    }
    // The point of it: the first positions need fewer contact iterations from the start.
    CHECK(first_warm < first_cold);
    test::VerifyRow(
        std::string("study warm start across cases, ") + shipped.file + ", first " +
            std::to_string(shipped.cases) + " cases",
        "the cold path (first position from the kinematic poses)",
        "largest |dK_gamma| " + Sci(worst_k_gamma) +
            "; first positions' contact "
            "iterations " +
            std::to_string(first_warm) + " against " + std::to_string(first_cold),
        "largest share of the derived bounds " + Sci(std::max(worst_ratio, worst_k_gamma_ratio)),
        "2(tau + eps l*); first-order force response + eps F*; K_gamma: n x LSR's",
        worst_ratio <= 1.0 && worst_k_gamma_ratio <= 1.0);
  }
}
