// [slow] The helical pair's 3D FE reference end to end, one ccx run (registered only where
// CalculiX's ccx is installed; docs/fe_reference.md, "The helical deck"): the ISO 20/40 pair at
// β = 15° on b = 10 mm (verification/data/fe_reference/iso_pair_20_40_helical_b10.toml), gear-1
// angle 13° (one tooth pair across the whole face), whole gears with their bodies held axially at
// mid-face inside the root circles (the reference the slices are compared with), 2 layers at
// in-plane refinement 1 (the cheapest of the committed runs, case `helical_held` of
// verification/data/fe_reference/iso_pair_20_40_helical_face_load.csv, with the same steps: the
// committed 4-layer stiffness's estimate × 0.9 and 1.1).
//  - Equilibrium: the layers' contact forces are normal to the helicoids; their transverse parts
//    F_l cos β_b, on the base circle's tangent, balance the hub's moment: Σ F_l cos β_b r_b1 = |T|
//    within 1e-3, as the spur decks' test (without cos β_b the balance would miss by
//    1 − cos β_b = 3.0 %). Their axial parts F_l sin β_b = F_l cos β_b tan β_b are all the held
//    nodes take axially: gear 1's axial reaction is F_t tan β_b (F_t = Σ F_l cos β_b) in size,
//    gear 2's its opposite, each within ccx's residual criterion (0.5 % of the average force: the
//    contact statistics and the reactions are two read-outs of one solution; measured 8e-4).
//  - The run reproduces its committed row: every station within ccx's residual criterion (0.5 %
//    of the average force, twice for a difference of two runs: 1 % of the mean line load).
// The slices against the committed reference: crosscheck/transmission_helical_fe3d.cpp.
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

TEST_CASE("3D FE reference: the helical deck's run, its equilibrium and its committed row",
          "[reference][slow][fe_reference]") {
  constexpr double kResidual = 0.005;
  const std::string data = std::string(EPICYCLE_TEST_DATA_DIR) + "/fe_reference/";
  const std::string csv = data + "iso_pair_20_40_helical_face_load.csv";
  const transmission::Scene scene = transmission::ReadScene(data + "iso_pair_20_40_helical_b10.toml");
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  const std::string dir =
      (std::filesystem::temp_directory_path() / "epicycle_fe3d_helical_test").string();
  std::filesystem::remove_all(dir);
  fe_reference::Fe3dOptions o;
  o.layers = 2;
  o.sector_teeth = 20;  // both gears whole
  o.axial_support = fe_reference::AxialSupport::kBodyMidPlane;
  const double k4 = test::CommittedRun(csv, "helical_held", 4, "1").mean_stiffness;
  const test::HelicalRun committed = test::CommittedRun(csv, "helical_held", 2, "1");
  const auto run = fe_reference::RunFe3d(scene, pair, setup.torque,
                                         13.0 * geometry::kPi / 180.0, k4 * 1e9, o, dir,
                                         EPICYCLE_CCX, 1, {0.9, 1.1});
  CHECK(run.runs == 1);
  const fe_reference::Fe3dLineLoad& r = run.result;
  CHECK(run.deck.transverse_factor ==
        Approx(transmission::LocalWidthFactor(pair.gear1(), pair.gear2())).epsilon(1e-15));
  CHECK(r.moment_balance <= 1e-3);
  // ISO 21771 from the data file's β = 15°, α_n = 20°: tan α_t = tan α_n / cos β,
  // tan β_b = tan β cos α_t.
  const double beta = 15.0 * geometry::kPi / 180.0, alpha_n = 20.0 * geometry::kPi / 180.0;
  const double tan_bb = std::tan(beta) * std::cos(std::atan(std::tan(alpha_n) / std::cos(beta)));
  const double axial = r.total_force * tan_bb;
  INFO("axial reactions " << r.axial_reaction[0] << ", " << r.axial_reaction[1]
                          << " N; F_t tan beta_b " << axial << " N");
  CHECK(std::abs(std::abs(r.axial_reaction[0]) - axial) <= kResidual * axial);
  CHECK(std::abs(r.axial_reaction[0] + r.axial_reaction[1]) <= kResidual * axial);
  const double mean = r.total_force / r.face_width / 1e3;  // N/mm
  REQUIRE(r.line_load.size() == committed.line_load.size());
  for (std::size_t l = 0; l < r.line_load.size(); ++l)
    CHECK(std::abs(r.line_load[l] / 1e3 - committed.line_load[l]) <= 2 * kResidual * mean);
  std::filesystem::remove_all(dir);
}
