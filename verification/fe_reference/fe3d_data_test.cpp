// The 3D FE reference's parts that need no ccx (docs/fe_reference.md, "3D reference across the
// face width"):
//  - SliceApproach, the uncoupled-slice estimate of the steps, against the closed forms of ISO
//    6336-1 method C's idealisation (uniform c′, no coupling between slices): the peak line load
//    c′(δ + F_β/2) over the mean F/b is K_Hβ = 1 + c′ F_β b/(2F) while the whole face carries load
//    and √(2 c′ F_β b/F) once part of it lifts off; and ∫ c′(δ − g)₊ dz = F by quadrature (midpoint
//    rule on 10⁵ cells: the integrand is piecewise linear with one kink, error ≤ F_β c′ b/10⁵ per
//    cell edge, 1e-9 relative here).
//  - Bad options: the error names the field, its value and the rule.
//  - The committed reference data (verification/data/fe_reference/iso_pair_20_40_face_load.csv,
//    written by `fe_reference fe3d`): every run's stations add up to the mesh force T/r_b1 (T
//    scaled with b from the scene's 20 mm) within
//    the run's moment balance (≤ 1e-3, as the plane reference's test), the stations tile [0, b],
//    and the aligned face is symmetric about b/2 within ccx's residual criterion (0.5 % of the
//    average force, twice for a difference: 1 % of the mean line load).
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "csv_rows.hpp"
#include "fe3d.hpp"

using namespace epicycle;

TEST_CASE("3D FE reference: uncoupled-slice approach against K_Hbeta's closed forms",
          "[unit][fe3d]") {
  const double c = 13.1e9, b = 0.02, force = 5321.0;  // N/m², m, N (ISO 20/40 at 200 N m)
  for (double fbeta : {0.0, 10e-6, 40e-6, 80e-6, 200e-6}) {
    const double delta = fe_reference::SliceApproach(force, b, c, fbeta);
    // Quadrature of the slices' force at δ.
    constexpr int kCells = 100000;
    double integral = 0;
    for (int i = 0; i < kCells; ++i) {
      const double z = b * (i + 0.5) / kCells;
      integral += c * std::max(0.0, delta - fbeta * (z / b - 0.5)) * b / kCells;
    }
    CHECK(integral == Approx(force).epsilon(1e-9));
    const double peak = c * (delta + 0.5 * fbeta) / (force / b);
    const double x = c * fbeta * b / (2 * force);
    CHECK(peak == Approx(x <= 1 ? 1 + x : std::sqrt(2 * c * fbeta * b / force)).epsilon(1e-12));
  }
}

TEST_CASE("3D FE reference: bad options name the field, its value and the rule", "[unit][fe3d]") {
  auto message = [](const fe_reference::Fe3dOptions& o) {
    try {
      o.Validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  fe_reference::Fe3dOptions o;
  o.layers = 0;
  CHECK(message(o) == "fe3d: layers = 0: must be in [1, 200]");
  o = {};
  o.misalignment = 2e-3;
  CHECK(message(o).find("misalignment = 0.002 m: must be finite and within ±1 mm") !=
        std::string::npos);
  o = {};
  o.plane_strain = true;
  o.misalignment = 10e-6;
  CHECK(message(o).find("plane_strain with misalignment = 1e-05 m") != std::string::npos);
  o = {};
  o.influence = true;
  o.read_depth[1] = 1e-3;
  CHECK(message(o) == "fe3d: read_depth of gear 1 = 0 m: must be > 0 with influence");
  o.read_depth[0] = 1e-3;
  o.misalignment = 10e-6;
  CHECK(message(o).find("influence with misalignment = 1e-05 m") != std::string::npos);
  o = {};
  o.axial_support = fe_reference::AxialSupport::kBodyMidPlane;
  o.misalignment = 10e-6;
  CHECK(message(o).find("axial_support of the bodies with misalignment = 1e-05 m") !=
        std::string::npos);
  CHECK_THROWS_AS(fe_reference::SliceApproach(0.0, 0.02, 1e10, 0.0), std::invalid_argument);
}

TEST_CASE("3D FE reference: the committed line loads balance the torque and tile the face",
          "[unit][fe3d]") {
  const auto rows = test::ReadCsvRows(std::string(EPICYCLE_TEST_DATA_DIR) +
                                      "/fe_reference/iso_pair_20_40_face_load.csv");
  REQUIRE(!rows.empty());
  constexpr double kMeshForce = 200.0 / (0.04 * std::cos(20.0 * 3.14159265358979323846 / 180.0));
  struct Run {
    double force = 0, balance = 0, b = 0, covered = 0, mean = 0;
    std::map<int, double> q;
    bool aligned = false;
  };
  std::map<std::string, Run> runs;
  for (const auto& r : rows) {
    REQUIRE(r.size() == 27);
    Run& run = runs[r[0] + "/" + r[4] + "/" + r[5] + "/" + r[6] + "/" + r[7]];
    const double lo = std::stod(r[23]), hi = std::stod(r[24]);  // mm
    run.force += std::stod(r[26]) * (hi - lo);
    run.covered += hi - lo;
    run.balance = std::stod(r[14]);
    run.b = std::stod(r[2]);
    run.mean = std::stod(r[17]) / run.b;
    run.q[std::stoi(r[22])] = std::stod(r[26]);
    run.aligned = std::stod(r[3]) == 0;
  }
  for (const auto& [key, run] : runs) {
    INFO(key);
    CHECK(run.covered == Approx(run.b).epsilon(1e-9));
    CHECK(run.balance <= 1e-3);
    // The tool keeps the scene's load per unit width: the torque scales with b (20 mm: the pair's).
    CHECK(std::abs(run.force / (kMeshForce * run.b / 20.0) - 1) <= 1e-3);
    if (!run.aligned) continue;
    const int n = static_cast<int>(run.q.size());
    for (const auto& [l, q] : run.q) CHECK(std::abs(q - run.q.at(n - 1 - l)) <= 0.01 * run.mean);
  }
}

namespace {

// The rows of verification/data/fe_reference/<file>_face_influence.csv by run (case/layers/
// refinement): G_ij [m/N] and the run's layer count.
struct InfluenceRuns {
  std::map<std::string, std::map<std::pair<int, int>, double>> runs;
  std::map<std::string, int> layers;
};

InfluenceRuns ReadInfluenceRuns(const std::string& file) {
  InfluenceRuns in;
  for (const auto& r : test::ReadCsvRows(std::string(EPICYCLE_TEST_DATA_DIR) + "/fe_reference/" +
                                         file + "_face_influence.csv")) {
    REQUIRE(r.size() == 15);
    const std::string key = r[0] + "/" + r[3] + "/" + r[4];
    in.runs[key][{std::stoi(r[10]), std::stoi(r[11])}] = std::stod(r[14]);
    in.layers[key] = std::stoi(r[3]);
  }
  return in;
}

}  // namespace

TEST_CASE(
    "3D FE reference: the committed structural compliance along the face is complete, positive "
    "and symmetric about the mid-face",
    "[unit][fe3d]") {
  // verification/data/fe_reference/iso_pair_20_40_face_influence.csv, written by `fe_reference
  // fe3d --influence` (docs/fe_reference.md, "The structural compliance along the face"). The
  // deck is extruded in equal layers with free ends and its hubs held, so station i under a load
  // on j mirrors station N−1−i under a load on N−1−j exactly; ccx prints 7 significant digits,
  // so two printed values of one number differ by at most 1e-6 of it (twice the rounding).
  // The same for the paper stage's two mesh kinds (10 layers: the stage's slices), the
  // planet-ring pair's deck an internal gear held at its rim.
  const std::string file =
      GENERATE(as<std::string>{}, "iso_pair_20_40", "paper_sun_planet", "paper_planet_ring");
  INFO(file);
  const InfluenceRuns in = ReadInfluenceRuns(file);
  const auto& runs = in.runs;
  REQUIRE(runs.count("plane_strain/1/1"));
  REQUIRE(runs.count(file == "iso_pair_20_40" ? "free/8/1" : "free/10/1"));
  for (const auto& [key, g] : runs) {
    INFO(key);
    const int n = in.layers.at(key);
    REQUIRE(static_cast<int>(g.size()) == n * n);
    for (const auto& [ij, v] : g) {
      CHECK(std::isfinite(v));
      if (ij.first == ij.second) CHECK(v > 0);
      const double mirror = g.at({n - 1 - ij.first, n - 1 - ij.second});
      CHECK(std::abs(v - mirror) <= 1e-6 * std::abs(v) + 1e-20);
    }
  }
}

// The paper stage's kernels (docs/fe_reference.md, "The paper stage's two mesh kinds"): the
// S-layer deck with u_z = 0 at every node (case plane_strain_layers) carries a load uniform
// along the face as the one-layer plane-strain deck does, whose answer is the z-independent plane
// field, so every row of its G sums to S G_ps: a check of the loads' spread over the layers, the
// read-out's averaging along z and, on the planet-ring pair, of the internal gear's deck (the
// ring held at its rim, the read-out at depth h inside the ring's tooth along the contact
// normal). Both are exact in the FE; what remains is ccx's printing of 7 digits: 5e-7 of each
// displacement, times at most 2 for the read-out's weights (Σ|N_k| of the quadratic triangle at
// an interior point), for two gears whose displacements add: within 4e-6, taken as 1e-5 (the
// [slow] test's bound on the ISO pair's 4 layers, fe3d_test.cpp).
TEST_CASE("3D FE reference: the paper stage's plane-strain layers' influence rows sum to S G_ps",
          "[unit][fe3d]") {
  const std::string file = GENERATE(as<std::string>{}, "paper_sun_planet", "paper_planet_ring");
  INFO(file);
  const InfluenceRuns in = ReadInfluenceRuns(file);
  // Every layered plane-strain run of the file: 10 layers (the kernels' stations) on both pairs,
  // and 5 on the planet-ring pair.
  REQUIRE(in.runs.count("plane_strain/1/1"));
  REQUIRE(in.runs.count("plane_strain_layers/10/1"));
  const double g_ps = in.runs.at("plane_strain/1/1").at({0, 0});
  REQUIRE(g_ps > 0);
  for (const auto& [key, g] : in.runs) {
    if (key.rfind("plane_strain_layers/", 0) != 0) continue;
    const int n = in.layers.at(key);
    INFO(key);
    for (int i = 0; i < n; ++i) {
      double row = 0;
      for (int j = 0; j < n; ++j) row += g.at({i, j});
      INFO("station " << i << ": sum of G_ij " << row << ", S G_ps " << n * g_ps << " m/N");
      CHECK(std::abs(row / (n * g_ps) - 1) <= 1e-5);
    }
  }
}
