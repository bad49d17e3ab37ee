// The contact problem of the paper stage with face-width slices (scenes/paper_stage_pin_tilt.toml:
// planet 1's pin tilted radially by 20 µm over the face) solved through its Kronecker structure
// (docs/solvers.md §12) against the dense Newton on the same matrix, at S = 10 and 20 slices,
// uncoupled and Pasternak-coupled: the structured answer within the KKT bound of the dense one
// (kkt_bound.hpp), definiteness proved by the factors, and both answers judged by the one residual.
#include <catch2/catch.hpp>

#include <string>

#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "fe_fixtures.hpp"
#include "kkt_bound.hpp"

using namespace epicycle;

TEST_CASE("sliced paper stage: the structured Newton's forces are the dense Newton's within the "
          "KKT bound, S = 10 and 20, uncoupled and Pasternak",
          "[crosscheck][transmission][face_width]") {
  const int slices = GENERATE(10, 20);
  const bool pasternak = GENERATE(false, true);
  CAPTURE(slices, pasternak);
  std::string table = "\n[face_width]\nslices = " + std::to_string(slices) + "\n";
  // λ = 5 mm: a fifth of the 25 mm face, a coupling that reaches a few slices either side.
  if (pasternak) table += "coupling = \"pasternak\"\ncoupling_length_mm = 5.0\n";
  table += "[[face_width.pin_tilt]]\nplanet = 1\nradial_um = 20.0\n";
  const transmission::Scene scene = transmission::ParseScene(
      test::SceneText("paper_stage.toml") + table, "paper_stage.toml + [face_width]");
  const geometry::Stage stage(scene.stage);
  const transmission::StageModel model(stage, test::Compliance("paper_stage.toml"),
                                       transmission::SetupFromScene(scene));
  const transmission::PositionResult r =
      transmission::SolvePosition(model, 0.3 * stage.mesh_cycle(), scene.loads, {});
  REQUIRE(r.converged);
  REQUIRE(r.problem.data.compliance_terms.size() == 1);  // the paper stage's meshes share W

  const solvers::ContactProblem structured(r.problem.data);
  CHECK(structured.definite_by_structure());
  solvers::ContactProblemData dense_data = r.problem.data;
  dense_data.compliance_terms.clear();
  const solvers::ContactProblem dense(std::move(dense_data));
  CHECK_FALSE(dense.definite_by_structure());

  constexpr double kTolerance = 1e-10;  // the contact driver's default
  solvers::ContactOptions o;
  o.tolerance = kTolerance;
  solvers::ContactSolution a, b;
  auto newton = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  const solvers::ContactReport ra = newton->Solve(dense, o, &a);
  const solvers::ContactReport rb = newton->Solve(structured, o, &b);
  REQUIRE(ra.status == solvers::ContactStatus::kConverged);
  REQUIRE(rb.status == solvers::ContactStatus::kConverged);
  // The one residual, recomputed from the dense problem for the structured answer.
  CHECK(solvers::EvaluateResiduals(dense, b).total <= kTolerance);

  const test::KktBound kb = test::ScaledKktBound(dense, a, kTolerance);
  // The tilt lifts planet 1's meshes off at one end: loaded and unloaded slices both present.
  CHECK(kb.active.size() > 0);
  CHECK(static_cast<int>(kb.active.size()) < dense.num_contacts());
  const double diff = (b.force / kb.force_scale - kb.scaled_force).cwiseAbs().maxCoeff();
  INFO("max |x - x_dense| " << diff << ", bound " << kb.bound << " (F* = " << kb.force_scale
                            << " N)");
  CHECK(diff <= kb.bound);
}
