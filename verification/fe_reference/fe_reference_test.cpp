// [slow] The FE contact reference end to end (registered only where CalculiX's ccx is installed):
// the deck of the ISO 20/40 pair at one single-contact position on the coarse mesh of the
// convergence study, run by ccx, read back.
//  - Equilibrium: on an involute contact every point's normal is tangent to gear 1's base circle,
//    so the moment of the pair forces about gear 1's centre is (Σ F_j) r_b1 exactly; the hub
//    moment read from the reactions must equal it (the FE contact normals follow the quadratic
//    faces: deviation O((h/ρ)²) ≈ 1e-4 with h/ρ ≈ 0.01; bound 1e-3).
//  - The mesh stiffness against the committed reference rows of the same position
//    (verification/data/fe_reference/iso_pair_20_40.csv): the coarse mesh lies within the
//    convergence band the study measured (|k(0.7) − k(1)|, committed), plus the θ(M)
//    interpolation (0.05 %).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "csv_rows.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "fe_deck.hpp"

using namespace epicycle;

namespace {

struct Row {
  double angle_deg = 0, hybrid_te_urad = 0, k = 0;
};

// The reference row (first pair) of `index` at `refinement`.
Row Committed(int index, double refinement) {
  for (const auto& c : test::ReadCsvRows(std::string(EPICYCLE_TEST_DATA_DIR) +
                                         "/fe_reference/iso_pair_20_40.csv")) {
    if (c.size() != 18 || std::stoi(c[0]) != index || std::stod(c[2]) != refinement ||
        std::stod(c[3]) != 1e8)
      continue;
    return {std::stod(c[1]), std::stod(c[11]), std::stod(c[12])};
  }
  FAIL("no committed row for index " << index << " at refinement " << refinement);
  return {};
}

}  // namespace

TEST_CASE("FE contact reference: CalculiX run of one position, equilibrium and convergence band",
          "[reference][slow][fe_reference]") {
  constexpr int kIndex = 36;  // 13.5 deg of the 48-position grid: single contact
  const Row coarse = Committed(kIndex, 0.7), base = Committed(kIndex, 1.0);
  const std::string dir =
      (std::filesystem::temp_directory_path() / "epicycle_fe_reference_test").string();
  std::filesystem::remove_all(dir);
  std::ifstream in(std::string(EPICYCLE_SCENES_DIR) + "/iso_pair_20_40.toml");
  std::ostringstream text;
  text << in.rdbuf();
  const transmission::Scene scene = transmission::ParseScene(text.str(), "iso_pair_20_40.toml");
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  fe_reference::FeMeshOptions mesh;
  mesh.refinement = 0.7;
  // The committed rows predate the fillets' refinement: their mesh has the tooth size there.
  mesh.fillet_size_per_module = mesh.tooth_size_per_module;
  const double te = coarse.hybrid_te_urad * 1e-6;
  const fe_reference::FeDeckInfo info =
      fe_reference::WriteDeck(scene, pair, setup.torque, coarse.angle_deg * geometry::kPi / 180.0,
                              {0.9 * te, 1.04 * te}, mesh, {}, dir);
  const std::string command = "cd '" + dir + "' && OMP_NUM_THREADS=1 nice -n 10 '" +
                              std::string(EPICYCLE_CCX) + "' -i deck > ccx.log 2>&1";
  REQUIRE(std::system(command.c_str()) == 0);
  const auto steps = fe_reference::ReadSteps(dir, info);
  REQUIRE(steps.size() == 2);
  const fe_reference::FeSample s = fe_reference::Interpolate(info, steps);
  CHECK(s.moment_balance <= 1e-3);
  const double k = s.mesh_stiffness / (info.face_width * 1e3) / 1e6;
  const double band = std::abs(coarse.k - base.k) + 5e-4 * base.k;
  CHECK(std::abs(k - base.k) <= band);
  CHECK(k == Approx(coarse.k).epsilon(5e-4));
  std::filesystem::remove_all(dir);
}
