// [slow] The 3D FE reference across the face width end to end (registered only where CalculiX's
// ccx is installed; docs/fe_reference.md, "3D reference across the face width"): the ISO 20/40
// pair at 13.5° (single contact), the default plane mesh of the 3D deck with 4 layers (the coarse
// axial level of the convergence study).
//  - Plane strain: the one-layer deck of the same plane mesh (u_z = 0) against the plane
//    reference's committed row at refinement 1 (verification/data/fe_reference/iso_pair_20_40.csv,
//    a finer mesh of whole gears, 40 µm at the contact): within the 3D mesh's own in-plane
//    discretisation error, twice its change from refinement 1 to 2 on the plane-strain deck
//    (kInPlane, a Richardson bound; docs table), plus the plane reference's 0.16 %.
//  - The layers' contact pairs: the 4-layer deck with u_z = 0 at every node has the plane field,
//    so every station carries the plane deck's line load and k is the plane deck's, up to ccx's
//    equilibrium tolerance: its residual criterion is 0.5 % of the average nodal force (*CONTROLS,
//    R_n^α = 0.005), kResidual on k and twice that on a station against another or the plane.
//  - Equilibrium: Σ F_l r_b1 = |T| (the contact normals are tangent to the base circle) within
//    1e-3, as the plane reference's test.
//  - The aligned face (F_β = 0): symmetric about z = b/2 (mesh and loads are), |q_l − q_{N−1−l}|
//    ≤ 2 kResidual × mean q; its stiffness per width in the middle lies between the plane-stress
//    (a 1 mm slab with free faces, the scene's line load) and the plane-strain decks' of the same
//    mesh: the middle of a finite face is neither free nor held axially.
//  - A misalignment F_β > 0 closes the z = 0 end (fe3d.hpp): the line load falls from z = 0 to
//    z = b, station by station.
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
  for (const auto& c :
       test::ReadCsvRows(std::string(EPICYCLE_TEST_DATA_DIR) + "/fe_reference/iso_pair_20_40.csv"))
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

TEST_CASE("3D FE reference: plane strain, layers, equilibrium, symmetry and the misaligned face",
          "[reference][slow][fe_reference]") {
  constexpr double kResidual = 0.005;
  const Pair p = IsoPair();
  const geometry::GearPair pair(p.setup.spec);
  const double angle = 13.5 * geometry::kPi / 180.0;
  const double k_plane = CommittedPlaneK();  // N/(mm·µm)
  const std::string root = (std::filesystem::temp_directory_path() / "epicycle_fe3d_test").string();
  std::filesystem::remove_all(root);
  auto run = [&](const fe_reference::Fe3dOptions& o, double torque, const std::string& name) {
    const auto r = fe_reference::RunFe3d(p.scene, pair, torque, angle, k_plane * 1e9, o,
                                         root + "/" + name, EPICYCLE_CCX);
    CHECK(r.result.moment_balance <= 1e-3);
    return r.result;
  };

  fe_reference::Fe3dOptions plane;
  plane.plane_strain = true;
  plane.layers = 1;
  const auto ps = run(plane, p.setup.torque, "plane");
  const double k_ps = ps.stiffness_per_width / 1e9;
  CHECK(std::abs(k_ps / k_plane - 1) <= kInPlane + kPlaneReference);

  fe_reference::Fe3dOptions layered = plane;
  layered.layers = 4;
  const auto pl = run(layered, p.setup.torque, "layered");
  CHECK(std::abs(pl.stiffness_per_width / ps.stiffness_per_width - 1) <= kResidual);
  for (double q : pl.line_load) CHECK(std::abs(q / ps.line_load.front() - 1) <= 2 * kResidual);

  fe_reference::Fe3dOptions stress;  // a 1 mm slab, free faces, the scene's line load
  stress.layers = 1;
  stress.face_width = 1e-3;
  const double b = geometry::ContactFaceWidth(pair.gear1(), pair.gear2());
  const auto pst = run(stress, p.setup.torque * stress.face_width / b, "stress");

  fe_reference::Fe3dOptions aligned;
  aligned.layers = 4;
  const auto c = run(aligned, p.setup.torque, "aligned");
  const auto& q = c.line_load;
  const double mean = c.total_force / c.face_width;
  for (std::size_t l = 0; l < q.size(); ++l)
    CHECK(std::abs(q[l] - q[q.size() - 1 - l]) <= 2 * kResidual * mean);
  CHECK(c.middle_stiffness_per_width < ps.stiffness_per_width);
  CHECK(c.middle_stiffness_per_width > pst.stiffness_per_width);

  fe_reference::Fe3dOptions tilted = aligned;
  tilted.misalignment = 20e-6;
  const auto a = run(tilted, p.setup.torque, "tilted");
  for (std::size_t l = 0; l + 1 < a.line_load.size(); ++l)
    CHECK(a.line_load[l] > a.line_load[l + 1]);
  std::filesystem::remove_all(root);
}

// The structural compliance along the face (docs/fe_reference.md, "The structural compliance
// along the face") on the 4-layer deck with u_z = 0 at every node: the four stations' loads add
// up to the one-layer plane-strain deck's uniform line load, whose answer is the z-independent
// plane field, so every row of G sums to 4 G_ps (the one layer's approach per unit force over the
// face). Both are exact in the FE; what remains is ccx's printing of 7 digits: 5e-7 of each
// displacement, times at most 2 for the read-out's weights (Σ|N_k| of the quadratic triangle at
// an interior point), for two gears whose displacements add: within 4e-6, taken as 1e-5.
TEST_CASE("3D FE reference: the influence rows of the plane-strain layers sum to the plane deck's",
          "[reference][slow][fe_reference]") {
  const Pair p = IsoPair();
  const geometry::GearPair pair(p.setup.spec);
  const double angle = 13.5 * geometry::kPi / 180.0;
  const std::string root =
      (std::filesystem::temp_directory_path() / "epicycle_fe3d_influence_test").string();
  std::filesystem::remove_all(root);
  fe_reference::Fe3dOptions o;
  o.influence = true;
  o.plane_strain = true;
  o.layers = 1;
  o.read_depth[0] = 0.972e-3;  // the plane model's joining depths of the ISO pair [m]
  o.read_depth[1] = 1.024e-3;
  const double g_ps =
      fe_reference::RunFe3dInfluence(p.scene, pair, angle, o, root + "/plane", EPICYCLE_CCX)
          .compliance.at(0)
          .at(0);
  o.layers = 4;
  const auto g =
      fe_reference::RunFe3dInfluence(p.scene, pair, angle, o, root + "/layers", EPICYCLE_CCX)
          .compliance;
  REQUIRE(g.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    double row = 0;
    for (double v : g[i]) row += v;
    INFO("station " << i << ": sum of G_ij " << row << ", 4 G_ps " << 4 * g_ps << " m/N");
    CHECK(std::abs(row / (4 * g_ps) - 1) <= 1e-5);
  }
  std::filesystem::remove_all(root);
}
