// The mesh stiffness of a stage's sliced meshes from its own quasi-static solutions
// (stage_mesh_stiffness.hpp; docs/model.md §10, "Mesh stiffness of a sliced mesh"): what the
// dynamic model's damping and the modes take for a helical stage.
//  - The helical mesh's mean stiffness is the spur mesh's: without local terms and with uncoupled
//    slices each slice is a linear spring system, and a helical slice is the spur slice at a
//    shifted phase of the mesh cycle (its sections turned by their lead), so the mean over a
//    cycle of the sum over the slices is the sum of the slices' means, the spur sliced mesh's.
//    The reference is the gear-pair driver (ComputeMeshStiffness), another code path.
//  - The tangent gᵀ(C_AA + diag u')⁻¹g against finite differences of the contact problem's
//    solutions under the mesh's approach ±h.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/stage_mesh_stiffness.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"

using namespace epicycle;

namespace {

constexpr int kPositions = 48;  // per mesh cycle, both drivers

// Σ over the cyclic samples of |x_{k+1} − x_k|: the samples' total variation over a period.
double CyclicVariation(const std::vector<double>& x) {
  double v = 0;
  for (std::size_t k = 0; k < x.size(); ++k) v += std::abs(x[(k + 1) % x.size()] - x[k]);
  return v;
}

// The helical paper stage with 5 uncoupled slices; `local` its local terms.
struct HelicalStage {
  transmission::Scene scene;
  geometry::Stage stage;
  transmission::FeStageCompliance compliance;
  transmission::StageModel model;
  explicit HelicalStage(bool local)
      : scene(transmission::ParseScene(test::Replace(test::SceneText("paper_stage_helical.toml"),
                                                     "slices = 20", "slices = 5"),
                                       "paper_stage_helical.toml")),
        stage(scene.stage),
        compliance(scene, stage, Sliced()),
        model(stage, compliance, Setup(scene, local)) {}
  static transmission::FeComplianceOptions Sliced() {
    transmission::FeComplianceOptions o = test::CachedTables();
    o.helical_slices = true;
    return o;
  }
  static transmission::StageSetup Setup(const transmission::Scene& s, bool local) {
    transmission::StageSetup setup = transmission::SetupFromScene(s);
    setup.local_terms = local;
    return setup;
  }
};

}  // namespace

TEST_CASE(
    "a helical mesh's mean stiffness from the stage's quasi-static solutions is the spur sliced "
    "mesh's of the gear-pair driver",
    "[crosscheck][transmission][helical]") {
  const HelicalStage h(false);
  REQUIRE(h.model.helical());
  // Per position, planet 1's meshes (MeshStiffnessOf), over one mesh cycle.
  std::vector<double> k_sun, k_ring;
  transmission::QuasiStaticOptions qo;
  qo.threads = 1;
  transmission::SweepEach(
      h.model, h.scene.loads, kPositions,
      [&](int k) { return transmission::SweepAngle(0.0, h.stage.mesh_cycle(), k, kPositions); },
      qo, [&](const transmission::PositionResult& r, int) {
        REQUIRE(r.converged);
        const auto s = transmission::MeshStiffnessOf(h.stage, r, 0, false);
        const auto g = transmission::MeshStiffnessOf(h.stage, r, 0, true);
        // Without local terms the tangent is gᵀC⁻¹g, independent of the load.
        CHECK(s.tangent > 0);
        CHECK(g.tangent > 0);
        k_sun.push_back(s.secant);
        k_ring.push_back(g.secant);
      });
  REQUIRE(k_sun.size() == static_cast<std::size_t>(kPositions));
  double mean[2] = {0, 0};
  for (int k = 0; k < kPositions; ++k) {
    mean[0] += k_sun[static_cast<std::size_t>(k)] / kPositions;
    mean[1] += k_ring[static_cast<std::size_t>(k)] / kPositions;
  }
  const transmission::StageMeshStiffness all =
      transmission::ComputeStageMeshStiffness(h.model, h.scene.loads, kPositions);
  CHECK(all.secant[0] == Approx(mean[0]).epsilon(1e-12));
  CHECK(all.secant[1] == Approx(mean[1]).epsilon(1e-12));

  // The reference: the spur paper stage's meshes with the same 5 slices in the pair driver.
  const transmission::Scene spur = transmission::ParseScene(
      test::SceneText("paper_stage.toml") + "\n[face_width]\nslices = 5\n", "paper_stage.toml");
  const geometry::Stage spur_stage(spur.stage);
  const char* names[2] = {"sun-planet1", "planet1-ring"};
  const std::vector<double>* helical_samples[2] = {&k_sun, &k_ring};
  for (int m = 0; m < 2; ++m) {
    const transmission::MeshPairSetup setup = transmission::MakeMeshPair(spur, &spur_stage, names[m]);
    const geometry::GearPair pair = transmission::MakePair(spur, setup.spec);
    const transmission::FePairCompliance compliance(spur, pair, test::CachedTables(), setup.gears);
    transmission::MeshStiffnessOptions o;
    o.positions = kPositions;
    o.local_terms = false;
    const transmission::MeshStiffnessResult r =
        transmission::ComputeMeshStiffness(setup, pair, compliance, o);
    REQUIRE(r.failed == 0);
    std::vector<double> k_pair;
    for (const transmission::MeshSample& s : r.samples) k_pair.push_back(s.mesh_stiffness);
    // Each mean is a P-point rule over one period of a function of bounded variation V, whose
    // error is at most V/P (Koksma's inequality, the star discrepancy of P equispaced points
    // being 1/P); V is taken from the samples (the jumps where a tooth pair enters or leaves).
    const double bound =
        (CyclicVariation(k_pair) + CyclicVariation(*helical_samples[m])) / kPositions;
    const double diff = std::abs(mean[m] - r.mean_stiffness);
    test::Figure(std::string(names[m]) + ": helical (beta 15 deg, 5 slices) mean stiffness " +
                 test::Sci(mean[m], 5) + " N/m, spur sliced pair " +
                 test::Sci(r.mean_stiffness, 5) + " N/m, difference " + test::Sci(diff, 2) +
                 " N/m, bound " + test::Sci(bound, 2));
    test::VerifyRow(std::string("helical mesh stiffness = spur sliced mean, ") + names[m],
                    "gear-pair driver, spur slices, no local term",
                    test::Sci(mean[m], 5) + " vs " + test::Sci(r.mean_stiffness, 5) + " N/m",
                    "difference " + test::Sci(diff / r.mean_stiffness, 2) + " relative",
                    "V/P of both samplings: " + test::Sci(bound / r.mean_stiffness, 2),
                    diff <= bound);
    CHECK(diff <= bound);
  }
}

TEST_CASE("a sliced mesh's tangent stiffness is the derivative of its contact forces",
          "[crosscheck][transmission][helical]") {
  // With the local terms (nonlinear), at one position of the helical stage: the mesh's loaded
  // contacts A with their compliance block and local terms at the pair's state of the stage's
  // mesh force (δ0_A + g s, MeshStiffnessOf's Δ: h = 0 must give F_m back), moved by ±h g,
  // solved by the contact solver (complementarity: another code path than the Newton of the
  // pair's state). F_m(Δ) = gᵀF is smooth while the active set holds; the central difference's
  // truncation is (h/Δ)² ~ 1e-8 of k (Δ ~ 10 µm, h = 1 nm), the solver's tolerance 1e-13 on the
  // residual gives 1e-13 F_m/(2h) ~ 1e-7 of k: 1e-6.
  const HelicalStage h(true);
  const auto r = transmission::SolvePosition(h.model, 0.01, h.scene.loads,
                                             transmission::QuasiStaticOptions{});
  REQUIRE(r.converged);
  const double rbp = h.stage.planet(0).base_radius();
  for (const bool ring : {false, true}) {
    const transmission::MeshStiffnessAt at = transmission::MeshStiffnessOf(h.stage, r, 0, ring);
    const geometry::MeshKind kind =
        ring ? geometry::MeshKind::kPlanetRing : geometry::MeshKind::kSunPlanet;
    std::vector<int> a;
    for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
      const auto& c = r.problem.contacts[j];
      if (c.planet == 0 && c.mesh == kind && c.loaded && r.solution.force(static_cast<long>(j)) > 0)
        a.push_back(static_cast<int>(j));
    }
    const auto n = static_cast<Eigen::Index>(a.size());
    REQUIRE(n >= 5);  // a contact line across the slices
    solvers::ContactProblemData d;
    d.compliance.resize(n, n);
    d.overlap.resize(n);
    Eigen::VectorXd g(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto& c = r.problem.contacts[static_cast<std::size_t>(a[i])];
      g(i) = std::abs(ring ? c.contact.lever_a : c.contact.lever_b) / rbp;
      d.local.push_back(r.problem.data.local[static_cast<std::size_t>(a[i])]);
      for (Eigen::Index k = 0; k < n; ++k) d.compliance(i, k) = r.problem.data.compliance(a[i], a[k]);
    }
    d.equality_matrix.resize(0, n);
    d.equality_rhs.resize(0);
    auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
    solvers::ContactOptions co;
    co.tolerance = 1e-13;
    // The pair's state: the stage's rigid overlaps moved by s = Δ − max_j δ0_j/g_j (header).
    Eigen::VectorXd overlap(n);
    double touch = -1e300;
    for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
      const auto& c = r.problem.contacts[j];
      if (c.planet != 0 || c.mesh != kind || !c.loaded) continue;
      const double lever = std::abs(ring ? c.contact.lever_a : c.contact.lever_b) / rbp;
      if (lever > 0) touch = std::max(touch, r.problem.data.overlap(static_cast<long>(j)) / lever);
    }
    for (Eigen::Index i = 0; i < n; ++i) overlap(i) = r.problem.data.overlap(a[i]);
    const double shift = at.approach - touch;
    int loaded = -1;  // the active set's size, the same at every h
    auto mesh_force = [&](double step) {
      solvers::ContactProblemData p = d;
      p.overlap = overlap + g * (shift + step);
      solvers::ContactSolution s;
      const solvers::ContactReport rep = solver->Solve(solvers::ContactProblem(std::move(p)), co, &s);
      REQUIRE(rep.status == solvers::ContactStatus::kConverged);
      const int count = static_cast<int>((s.force.array() > 0).count());
      if (loaded < 0) loaded = count;
      REQUIRE(count == loaded);  // the active set holds
      return g.dot(s.force);
    };
    const double step = 1e-9;  // [m]
    CHECK(mesh_force(0.0) == Approx(at.force).epsilon(1e-8));
    const double k_fd = (mesh_force(step) - mesh_force(-step)) / (2 * step);
    test::Figure(std::string(ring ? "planet1-ring" : "sun-planet1") + " at 0.01 rad: tangent " +
                 test::Sci(at.tangent, 6) + " N/m, finite difference " + test::Sci(k_fd, 6) +
                 " N/m; secant " + test::Sci(at.secant, 6) + " N/m");
    CHECK(at.tangent == Approx(k_fd).epsilon(1e-6));
    // The local term's approach grows less than linearly with the load: tangent > secant.
    CHECK(at.tangent > at.secant);
  }
}
