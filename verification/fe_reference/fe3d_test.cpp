// [slow] The 3D FE reference across the face width end to end (registered only where CalculiX's
// ccx is installed; docs/fe_reference.md, "3D reference across the face width"): the ISO 20/40
// pair at 13.5° (single contact), the committed discretisation's plane mesh with 4 layers (the
// coarse axial level of the convergence study).
//  - Plane strain: the one-layer deck of the same plane mesh (u_z = 0) against the plane
//    reference's committed row at refinement 1 (verification/data/fe_reference/iso_pair_20_40.csv,
//    a finer mesh of whole gears, 40 µm at the contact): within the 3D mesh's own in-plane
//    discretisation error, twice its change from refinement 1 to 2 on the plane-strain deck
//    (kInPlane, a Richardson bound; docs table), plus the plane reference's 0.16 %.
//  - Equilibrium: Σ F_l r_b1 = |T| (the contact normals are tangent to the base circle) within
//    1e-3, as the plane reference's test.
//  - Symmetry of the aligned face: mesh and loads are symmetric about z = b/2, so q(z) = q(b − z)
//    up to ccx's equilibrium tolerance, whose default residual criterion is 0.5 % of the average
//    nodal force (*CONTROLS, R_n^α = 0.005): |q_l − q_{N−1−l}| ≤ 0.005 × 2 × mean q.
//  - A misalignment F_β > 0 closes the z = 0 end (fe3d.hpp): the load is largest there and
//    smallest at z = b, and K_Hβ lies below uncoupled slices' 1 + c′ F_β b/(2F) (with c′ the
//    middle stiffness): the plate coupling leaves a linear load unchanged in the interior, and
//    the free ends, softer than the middle (plane stress), carry less than slices would.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "csv_rows.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "fe3d.hpp"

using namespace epicycle;

namespace {

// Twice the plane-strain deck's change of k from in-plane refinement 1 to 2 (docs table).
constexpr double kInPlane = 2 * 0.0021;
constexpr double kPlaneReference = 0.0016;  // the plane reference's own uncertainty (docs)

double CommittedPlaneK() {
  for (const auto& c : test::ReadCsvRows(std::string(EPICYCLE_TEST_DATA_DIR) +
                                         "/fe_reference/iso_pair_20_40.csv"))
    if (c.size() == 18 && std::stoi(c[0]) == 36 && std::stod(c[2]) == 1.0 &&
        std::stod(c[3]) == 1e8 && std::stod(c[15]) > 0)
      return std::stod(c[12]);
  FAIL("no committed plane reference row at index 36, refinement 1");
  return 0;
}

struct Pair {
  transmission::Scene scene;
  transmission::MeshPairSetup setup;
};

Pair IsoPair() {
  std::ifstream in(std::string(EPICYCLE_SCENES_DIR) + "/iso_pair_20_40.toml");
  std::ostringstream text;
  text << in.rdbuf();
  Pair p{transmission::ParseScene(text.str(), "iso_pair_20_40.toml"), {}};
  p.setup = transmission::MakeMeshPair(p.scene, nullptr, "");
  return p;
}

}  // namespace

TEST_CASE("3D FE reference: plane strain, equilibrium, symmetry and the misaligned face",
          "[reference][slow][fe_reference]") {
  const Pair p = IsoPair();
  const geometry::GearPair pair(p.setup.spec);
  const double angle = 13.5 * geometry::kPi / 180.0;
  const double k_plane = CommittedPlaneK();  // N/(mm·µm)
  const std::string root =
      (std::filesystem::temp_directory_path() / "epicycle_fe3d_test").string();
  std::filesystem::remove_all(root);

  fe_reference::Fe3dOptions plane;
  plane.plane_strain = true;
  plane.layers = 1;
  const auto ps = fe_reference::RunFe3d(p.scene, pair, p.setup.torque, angle, k_plane * 1e9,
                                        plane, root + "/plane", EPICYCLE_CCX);
  const double k_ps = ps.result.stiffness_per_width / 1e9;
  CHECK(std::abs(k_ps / k_plane - 1) <= kInPlane + kPlaneReference);
  CHECK(ps.result.moment_balance <= 1e-3);

  fe_reference::Fe3dOptions aligned;
  aligned.layers = 4;
  const auto c = fe_reference::RunFe3d(p.scene, pair, p.setup.torque, angle, k_ps * 1e9, aligned,
                                       root + "/aligned", EPICYCLE_CCX);
  const auto& q = c.result.line_load;
  const double mean = c.result.total_force / c.result.face_width;
  CHECK(c.result.moment_balance <= 1e-3);
  for (std::size_t l = 0; l < q.size(); ++l) CHECK(std::abs(q[l] - q[q.size() - 1 - l]) <= 0.01 * mean);

  fe_reference::Fe3dOptions tilted = aligned;
  tilted.misalignment = 20e-6;
  const auto a = fe_reference::RunFe3d(p.scene, pair, p.setup.torque, angle, k_ps * 1e9, tilted,
                                       root + "/tilted", EPICYCLE_CCX);
  const auto& qa = a.result.line_load;
  CHECK(a.result.moment_balance <= 1e-3);
  CHECK(qa.front() == *std::max_element(qa.begin(), qa.end()));
  CHECK(qa.back() == *std::min_element(qa.begin(), qa.end()));
  const double slices = 1 + c.result.middle_stiffness_per_width * tilted.misalignment *
                                c.result.face_width / (2 * a.result.total_force);
  CHECK(a.result.k_hbeta < slices);
  std::filesystem::remove_all(root);
}
