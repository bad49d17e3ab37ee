// The quasi-static sweep's warm start and threads (docs/quasistatic.md, "Sweep cost") against the
// cold positions of SolvePosition: on the paper's stage with planet 1's 20 µm run-out, fixed and
// floating sun, 360 positions over one planet revolution. The warm start may change a result
// only within what the two stopping rules allow:
//
//  - rigid displacements (rotations at their base circles, translations): the geometric
//    iteration stops when its last increment is ≤ τ = geometric_tolerance and reports the poses
//    after it. The increments fall by three orders or more per iteration (from ~10 µm to below
//    1e-11 m in 2–3 iterations), so the contraction ratio ρ ≤ 1/2 and the reported state lies
//    within ρτ/(1 − ρ) ≤ τ of the fixed point; two runs differ by ≤ 2τ, plus each contact solve's
//    own error, ε ℓ* (ε the contact tolerance on the nondimensional residual, ℓ* the driver's
//    length scale): |Δq| ≤ 2(τ + ε ℓ*).
//  - LSR_i = T_i/(−T): the forces of the last problem belong to the poses after its increment, so
//    they differ between the runs by the first-order response to those poses' difference,
//    dF = C_t⁻¹ Gᵀ dq on the active contacts (C_t = C + diag(u_local'(F)), the tangent
//    compliance), plus each solve's force error ε F* per contact:
//      |ΔT_i| ≤ Σ_k |(L_i C_t⁻¹ Gᵀ)_k| |Δq_k| + 2 ε F* Σ_{j∈i} |lever_j|,
//    L_i the levers of planet i's loaded sun-mesh contacts (the sum over all of them), |Δq_k| ≤ 2(τ
//    + ε ℓ*)/s_k (s_k the base radius of a rotation, 1 for a translation). The bound is evaluated
//    per position from the cold position's own problem.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "sweep_bounds.hpp"

using namespace epicycle;
using test::Sci;
using test::VerifyRow;
using test::Comparison;
using transmission::PositionResult;
using transmission::SunSupport;

namespace {

constexpr const char* kFile = "paper_stage_runout.toml";

struct Rig {
  transmission::Scene scene = transmission::ParseScene(test::SceneText(kFile), kFile);
  geometry::Stage stage{scene.stage};
  transmission::QuasiStaticOptions options;
  std::unique_ptr<transmission::StageModel> model;
  std::vector<double> angles;
  explicit Rig(SunSupport sun, int positions = 360) {
    transmission::StageSetup setup = transmission::SetupFromScene(scene);
    setup.sun = sun;
    model = std::make_unique<transmission::StageModel>(stage, test::Compliance(kFile), setup);
    // One planet revolution relative to the carrier: the period of planet 1's run-out.
    angles = transmission::SweepAngles(
        0.0, transmission::CarrierSpan(stage, transmission::RunRange::kPlanetRevolution),
        positions);
  }
  transmission::StageLoads loads() const { return scene.loads; }
  std::vector<PositionResult> Sweep(bool warm, int threads) const {
    transmission::QuasiStaticOptions o = options;
    o.warm_start = warm;
    o.threads = threads;
    return transmission::Sweep(*model, loads(), angles, o);
  }
};

Comparison Compare(const Rig& rig, const std::vector<PositionResult>& a,
                   const std::vector<PositionResult>& ref) {
  return test::CompareSweeps(*rig.model, rig.options, rig.scene.loads.sun_torque, a, ref);
}

}  // namespace

TEST_CASE(
    "quasistatic sweep: warm start and threads agree with cold positions within the "
    "tolerances",
    "[crosscheck][transmission][quasistatic][sweep]") {
  for (SunSupport sun : {SunSupport::kFixed, SunSupport::kFloating}) {
    const Rig rig(sun);
    const std::string name = sun == SunSupport::kFixed ? "fixed sun" : "floating sun";
    std::vector<PositionResult> cold;
    for (double angle : rig.angles)
      cold.push_back(transmission::SolvePosition(*rig.model, angle, rig.loads(), rig.options));
    const auto warm1 = rig.Sweep(true, 1);
    const auto warm2 = rig.Sweep(true, 2);

    // The warm start was used (every position but the first) and saved work.
    int warm_started = 0, iterations_cold = 0, iterations_warm = 0;
    for (std::size_t k = 0; k < cold.size(); ++k) {
      warm_started += warm1[k].warm_started ? 1 : 0;
      iterations_cold += cold[k].contact_iterations;
      iterations_warm += warm1[k].contact_iterations;
    }
    CHECK(warm_started == static_cast<int>(rig.angles.size()) - 1);
    CHECK(iterations_warm < iterations_cold);

    const Comparison wc = Compare(rig, warm1, cold);
    const Comparison threads = Compare(rig, warm2, warm1);
    INFO(name << ": warm vs cold |dq| " << wc.displacement << " m (" << wc.displacement_ratio
              << " of the bound), |dLSR| " << wc.lsr << " (" << wc.lsr_ratio << "), DOFs left out "
              << wc.free_dofs << "; 2 vs 1 threads |dq| " << threads.displacement << ", |dLSR| "
              << threads.lsr);
    CHECK(wc.displacement_ratio <= 1.0);
    CHECK(wc.lsr_ratio <= 1.0);
    CHECK(threads.displacement_ratio <= 1.0);
    CHECK(threads.lsr_ratio <= 1.0);
    VerifyRow(
        "run-out 20 um, " + name + ", 360 positions warm-started from the neighbour",
        "cold positions (SolvePosition)",
        "largest |dq| " + Sci(wc.displacement) + " m, |dLSR| " + Sci(wc.lsr) + " (" +
            std::to_string(wc.free_dofs) + " unloaded planet rotations left out)",
        "largest share of the derived bound " + Sci(std::max(wc.displacement_ratio, wc.lsr_ratio)),
        "2(tau + eps l*); first-order force response + eps F*",
        wc.displacement_ratio <= 1.0 && wc.lsr_ratio <= 1.0);
    VerifyRow("run-out 20 um, " + name + ", warm sweep on 2 threads (2 chunks)",
              "the same on 1 thread",
              "largest |dq| " + Sci(threads.displacement) + " m, |dLSR| " + Sci(threads.lsr),
              "largest share of the derived bound " +
                  Sci(std::max(threads.displacement_ratio, threads.lsr_ratio)),
              "2(tau + eps l*); first-order force response + eps F*",
              threads.displacement_ratio <= 1.0 && threads.lsr_ratio <= 1.0);
  }
}

TEST_CASE("quasistatic sweep: cold positions are bit-identical across thread counts",
          "[crosscheck][transmission][quasistatic][sweep]") {
  const Rig rig(SunSupport::kFloating, 60);
  const auto one = rig.Sweep(false, 1);
  const auto three = rig.Sweep(false, 3);
  REQUIRE(one.size() == three.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    INFO("position " << k);
    CHECK(one[k].converged);
    CHECK(!three[k].warm_started);
    CHECK(one[k].displacements == three[k].displacements);
    CHECK(one[k].load_sharing == three[k].load_sharing);
    CHECK(one[k].solution.force == three[k].solution.force);
  }
}

TEST_CASE("quasistatic sweep: on_result sees every position in order, failed ones included",
          "[crosscheck][transmission][quasistatic][sweep]") {
  Rig rig(SunSupport::kFixed, 25);
  // One geometric iteration cannot settle (the first increment is the whole deflection): every
  // position fails, and each must still be reported, once, in the order of the angles.
  rig.options.max_geometric_iterations = 1;
  for (int threads : {1, 2, 4}) {
    transmission::QuasiStaticOptions o = rig.options;
    o.threads = threads;
    // Recorded in the callback (it runs on the workers), checked here.
    std::vector<int> seen;
    std::vector<PositionResult> reported;
    const auto results = transmission::Sweep(*rig.model, rig.loads(), rig.angles, o,
                                             [&](const PositionResult& r, int k) {
                                               seen.push_back(k);
                                               reported.push_back(r);
                                             });
    INFO(threads << " threads");
    REQUIRE(seen.size() == rig.angles.size());
    CHECK(results.size() == rig.angles.size());
    for (std::size_t k = 0; k < seen.size(); ++k) {
      CHECK(seen[k] == static_cast<int>(k));
      CHECK(reported[k].carrier_angle == rig.angles[k]);
      CHECK(!reported[k].converged);
      CHECK(reported[k].message.find("did not settle") != std::string::npos);
    }
  }
  // An exception from on_result stops the workers and reaches the caller.
  transmission::QuasiStaticOptions o = rig.options;
  o.threads = 2;
  int calls = 0;
  CHECK_THROWS_WITH(transmission::Sweep(*rig.model, rig.loads(), rig.angles, o,
                                        [&](const PositionResult&, int k) {
                                          ++calls;
                                          if (k == 3) throw std::runtime_error("disk full");
                                        }),
                    "disk full");
  CHECK(calls == 4);
  // Bad options name the field.
  o.threads = -1;
  CHECK_THROWS_WITH(transmission::Sweep(*rig.model, rig.loads(), rig.angles, o),
                    Catch::Contains("threads = -1"));
}

TEST_CASE("quasistatic sweep: a streamed sweep beyond the positions in flight",
          "[crosscheck][transmission][quasistatic][sweep]") {
  // kSweepInFlight + 904 positions on 2 workers: chunks of at most kSweepInFlight/2 positions, so
  // at least ⌈5000/2048⌉ = 3 cold positions (each chunk's first), every other one warm; the
  // streamed sweep (SweepEach, results let go once handed on) and the one that keeps them (Sweep)
  // run the same chunks, so they agree bit for bit, and so do their summaries.
  const int count = transmission::kSweepInFlight + 904;
  Rig rig(SunSupport::kFixed, count);
  rig.options.threads = 2;
  const std::vector<PositionResult> kept = rig.Sweep(true, 2);
  REQUIRE(kept.size() == static_cast<std::size_t>(count));
  transmission::SweepAccumulator streamed(3);
  int same = 0, cold = 0, longest = 0, run = 0;
  transmission::SweepEach(
      *rig.model, rig.loads(), count,
      [&](int k) { return rig.angles[static_cast<std::size_t>(k)]; }, rig.options,
      [&](const PositionResult& r, int k) {
        const PositionResult& e = kept[static_cast<std::size_t>(k)];
        same += r.converged && e.converged && r.load_sharing == e.load_sharing &&
                r.transmission_error == e.transmission_error &&
                r.warm_started == e.warm_started;
        cold += !r.warm_started;
        run = r.warm_started ? run + 1 : 1;
        longest = std::max(longest, run);
        streamed.Add(r);
      });
  CHECK(same == count);
  CHECK(cold >= 3);
  CHECK(longest <= transmission::kSweepInFlight / 2);
  const transmission::SweepSummary a = streamed.Result(),
                                   b = transmission::SummariseSweep(kept, 3);
  CHECK(a.converged == count);
  CHECK(a.lsr_mean == b.lsr_mean);
  CHECK(a.k_gamma == b.k_gamma);
  CHECK(a.transmission_error_max == b.transmission_error_max);
}

TEST_CASE("mesh stiffness: the same samples, in order, on 1 and 3 threads",
          "[crosscheck][transmission][stiffness][sweep]") {
  const transmission::Scene scene = test::PaperScene();
  const geometry::Stage stage(scene.stage);
  const auto setup = transmission::MakeMeshPair(scene, &stage, "sun-planet1");
  const geometry::GearPair pair(setup.spec);
  const transmission::FePairCompliance fe(scene, pair, test::CachedTables());
  transmission::MeshStiffnessOptions o;
  o.positions = 24;
  o.threads = 1;
  const auto one = transmission::ComputeMeshStiffness(setup, pair, fe, o);
  o.threads = 3;
  std::vector<double> seen;  // angles in the order on_sample saw them
  const auto three = transmission::ComputeMeshStiffness(setup, pair, fe, o,
      [&](const transmission::MeshSample& s) { seen.push_back(s.angle); });
  REQUIRE(one.failed == 0);
  REQUIRE(three.samples.size() == one.samples.size());
  REQUIRE(seen.size() == one.samples.size());
  // Every position starts from the kinematic pose: the thread count changes nothing.
  for (std::size_t k = 0; k < one.samples.size(); ++k) {
    CHECK(seen[k] == one.samples[k].angle);
    CHECK(three.samples[k].mesh_stiffness == one.samples[k].mesh_stiffness);
    CHECK(three.samples[k].rotation == one.samples[k].rotation);
  }
  CHECK(three.mean_stiffness == one.mean_stiffness);
  CHECK(three.peak_pair_stiffness == one.peak_pair_stiffness);
}
