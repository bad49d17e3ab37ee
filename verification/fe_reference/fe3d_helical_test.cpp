// [slow] The helical pair's 3D FE reference end to end, one ccx run (registered only where
// CalculiX's ccx is installed; docs/fe_reference.md, "The helical deck"): the ISO 20/40 pair at
// β = 15° on b = 10 mm (verification/data/fe_reference/iso_pair_20_40_helical_b10.toml), gear-1
// angle 13° (one tooth pair across the whole face), whole gears, 4 layers at in-plane refinement
// 1: the reference the crosscheck compares with (its committed rows and convergence runs in
// verification/data/fe_reference/iso_pair_20_40_helical_face_load.csv).
//  - Equilibrium: the layers' contact forces are normal to the helicoids; their transverse parts
//    F_l cos β_b, on the base circle's tangent, balance the hub's moment: Σ F_l cos β_b r_b1 = |T|
//    within 1e-3, as the spur decks' test (without cos β_b the balance would miss by
//    1 − cos β_b = 3.0 %).
//  - The run reproduces its committed row: every station within ccx's residual criterion (0.5 %
//    of the average force, twice for a difference of two runs: 1 % of the mean line load).
//  - The slices against it within the reference's derived tolerance (fe3d_helical.hpp,
//    ReferenceTolerance: twice the axial and in-plane changes of the committed runs, plus the
//    slices' change from 20 to 40 slices), as the crosscheck does with the committed rows
//    (crosscheck/transmission_helical_fe3d.cpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "fe3d.hpp"
#include "fe3d_helical.hpp"

using namespace epicycle;

TEST_CASE("3D FE reference: the helical deck's run, its equilibrium and the slices against it",
          "[reference][slow][fe_reference]") {
  constexpr double kResidual = 0.005;
  const std::string data = std::string(EPICYCLE_TEST_DATA_DIR) + "/fe_reference/";
  const std::string csv = data + "iso_pair_20_40_helical_face_load.csv";
  transmission::Scene scene = transmission::ReadScene(data + "iso_pair_20_40_helical_b10.toml");
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  const std::string dir =
      (std::filesystem::temp_directory_path() / "epicycle_fe3d_helical_test").string();
  std::filesystem::remove_all(dir);
  fe_reference::Fe3dOptions o;
  o.layers = 4;
  o.sector_teeth = 20;  // both gears whole
  // The steps bracket the torque around the committed run's stiffness: one ccx run.
  const test::HelicalRun committed = test::CommittedRun(csv, "helical", 4, "1");
  const auto run =
      fe_reference::RunFe3d(scene, pair, setup.torque, 13.0 * geometry::kPi / 180.0,
                            committed.mean_stiffness * 1e9, o, dir, EPICYCLE_CCX, 1,
                            {0.97, 1.03});
  CHECK(run.runs == 1);
  const fe_reference::Fe3dLineLoad& r = run.result;
  CHECK(run.deck.transverse_factor ==
        Approx(transmission::LocalWidthFactor(pair.gear1(), pair.gear2())).epsilon(1e-15));
  CHECK(r.moment_balance <= 1e-3);

  const double mean = r.total_force / r.face_width / 1e3;  // N/mm
  REQUIRE(r.line_load.size() == committed.line_load.size());
  for (std::size_t l = 0; l < r.line_load.size(); ++l)
    CHECK(std::abs(r.line_load[l] / 1e3 - committed.line_load[l]) <= 2 * kResidual * mean);

  transmission::FeComplianceOptions tables;
  tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  const test::HelicalSliceSample slices = test::HelicalSlicesAt(scene, tables, 13.0, 18);
  scene.face_width.slices *= 2;
  const test::HelicalSliceSample finer = test::HelicalSlicesAt(scene, tables, 13.0, 18);
  std::vector<double> model = slices.Stations(o.layers), model2 = finer.Stations(o.layers);
  for (double& q : model) q /= 1e3;
  for (double& q : model2) q /= 1e3;
  const test::HelicalTolerance t =
      test::ReferenceTolerance(csv, test::LargestChange(model, model2));
  for (std::size_t l = 0; l < model.size(); ++l) {
    INFO("station " << l << ": 3D " << r.line_load[l] / 1e3 << " N/mm, slices " << model[l]
                    << " N/mm, tolerance " << t.total() << " N/mm");
    CHECK(std::abs(model[l] - r.line_load[l] / 1e3) <= t.total());
  }
  std::filesystem::remove_all(dir);
}
