// The hybrid model's mesh stiffness, loaded transmission error and tooth-pair load shares against
// the full-FE contact reference (CalculiX: both gears meshed by gmsh from the exact profile,
// second-order plane-strain elements refined at the contacts, frictionless surface-to-surface
// contact; verification/fe_reference and tools/fe_reference.sh). The reference's results are
// committed in verification/data/fe_reference/<scene>.csv (ccx is not needed here); this test
// recomputes the hybrid model at the same positions of its 48-position grid and compares.
//
// Tolerance: the reference's own discretisation error, measured by its mesh-convergence study
// (docs/compliance.md, "FE contact reference": mesh sizes 0.5×, 1× and 2× the reference's, the
// largest change of k between the reference mesh and the finest), plus the contact penalty's
// share (penalty ×10: the change of k), plus the interpolation of θ(M) between the two steps.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "csv_rows.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;

namespace {

constexpr int kGrid = 48;  // tools/fe_reference.sh's default grid

struct FeRow {
  int index = 0;
  double angle_deg = 0, te_urad = 0, k = 0;  // k per face width [N/(mm um)]
  std::map<std::string, double> share;       // teeth "t1/t2" → F_j/ΣF
};

// The rows of refinement 1 and the default penalty, one per position.
std::vector<FeRow> ReadReference(const std::string& scene) {
  const std::string path = std::string(EPICYCLE_TEST_DATA_DIR) + "/fe_reference/" + scene + ".csv";
  std::map<int, FeRow> rows;
  for (const auto& c : test::ReadCsvRows(path)) {
    REQUIRE(c.size() == 18);
    if (std::stod(c[2]) != 1.0 || std::stod(c[3]) != 1e8) continue;
    FeRow& r = rows[std::stoi(c[0])];
    r.index = std::stoi(c[0]);
    r.angle_deg = std::stod(c[1]);
    r.te_urad = std::stod(c[10]);
    r.k = std::stod(c[12]);
    r.share[c[14]] = std::stod(c[16]);
  }
  std::vector<FeRow> out;
  for (auto& [i, r] : rows) out.push_back(r);
  return out;
}

}  // namespace

TEST_CASE("Mesh stiffness, transmission error and load shares against the FE contact reference",
          "[reference][stiffness][fe_reference]") {
  // Relative tolerance on k and θ: FE discretisation (convergence study) 1.0 % + penalty 0.1 % +
  // θ(M) interpolation 0.05 %, rounded up: 1.5 %. Load share: the same relative error on each
  // pair's force, F_j/ΣF moving by at most 2 × 1.5 % × 0.5 ≈ 0.015 in absolute terms.
  constexpr double kTolK = 0.015;
  constexpr double kTolShare = 0.015;
  for (const std::string scene : {"iso_pair_20_40", "paper_sun_planet", "paper_planet_ring"}) {
    INFO(scene);
    const std::vector<FeRow> reference = ReadReference(scene);
    REQUIRE(reference.size() >= 12);
    const transmission::Scene sc =
        transmission::ParseScene(test::SceneText(scene + ".toml"), scene + ".toml");
    const transmission::MeshPairSetup setup = transmission::MakeMeshPair(sc, nullptr, "");
    const geometry::GearPair pair(setup.spec);
    transmission::FeComplianceOptions tables;
    tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
    const transmission::FePairCompliance fe(sc, pair, tables);
    transmission::MeshStiffnessOptions o;
    o.positions = kGrid;
    const transmission::MeshStiffnessResult r =
        transmission::ComputeMeshStiffness(sc, setup, pair, fe, o);
    REQUIRE(r.failed == 0);
    const double b_mm = r.face_width * 1e3;
    double worst_k = 0, worst_te = 0, worst_share = 0;
    double sum[2] = {0, 0}, sum_fe[2] = {0, 0}, peak = 0, peak_fe = 0;
    int count[2] = {0, 0};
    for (const FeRow& ref : reference) {
      const transmission::MeshSample& s = r.samples.at(ref.index);
      REQUIRE(geometry::Deg(s.angle) == Approx(ref.angle_deg).margin(1e-5));
      REQUIRE(s.converged);
      const double k = s.mesh_stiffness / b_mm / 1e6;
      worst_k = std::max(worst_k, std::abs(k / ref.k - 1.0));
      worst_te =
          std::max(worst_te, std::abs(std::abs(s.rotation * 1e6) / std::abs(ref.te_urad) - 1));
      CHECK(k == Approx(ref.k).epsilon(kTolK));
      // Zones by the FE reference's loaded pairs (share above 1 %).
      int loaded = 0;
      for (const auto& [teeth, share] : ref.share) loaded += share > 0.01 ? 1 : 0;
      const int zone = loaded >= 2 ? 1 : 0;
      sum[zone] += k;
      sum_fe[zone] += ref.k;
      ++count[zone];
      peak = std::max(peak, k);
      peak_fe = std::max(peak_fe, ref.k);
      if (zone == 1) {
        for (const auto& [teeth, share] : ref.share) {
          double hybrid = 0;
          for (const auto& p : s.pairs)
            if (std::to_string(p.tooth1) + "/" + std::to_string(p.tooth2) == teeth)
              hybrid = p.share;
          worst_share = std::max(worst_share, std::abs(hybrid - share));
          CHECK(hybrid == Approx(share).margin(kTolShare));
        }
      }
    }
    CHECK(count[0] >= 3);
    CHECK(count[1] >= 3);
    const std::string n = std::to_string(reference.size()) + " positions";
    test::VerifyRow("FE contact reference " + scene + ": mesh stiffness per position",
                    "CalculiX contact, " + n, "hybrid model",
                    test::Sci(worst_k) + " largest relative", "1.5 %", worst_k <= kTolK);
    for (int z : {0, 1}) {
      const double mean = sum[z] / count[z], mean_fe = sum_fe[z] / count[z];
      const double err = std::abs(mean / mean_fe - 1.0);
      test::VerifyRow("FE contact reference " + scene + ": mean k, " + (z ? "double" : "single") +
                          "-contact zone [N/(mm um)]",
                      "CalculiX " + test::Sci(mean_fe), test::Sci(mean),
                      test::Sci(err) + " relative", "1.5 %", err <= kTolK);
      CHECK(err <= kTolK);
    }
    test::VerifyRow("FE contact reference " + scene + ": peak k [N/(mm um)]",
                    "CalculiX " + test::Sci(peak_fe), test::Sci(peak),
                    test::Sci(std::abs(peak / peak_fe - 1)) + " relative", "1.5 %",
                    std::abs(peak / peak_fe - 1) <= kTolK);
    CHECK(peak == Approx(peak_fe).epsilon(kTolK));
    test::VerifyRow("FE contact reference " + scene + ": loaded transmission error per position",
                    "CalculiX gear-1 rotation, " + n, "hybrid model",
                    test::Sci(worst_te) + " largest relative", "1.5 %", worst_te <= kTolK);
    CHECK(worst_te <= kTolK);
    test::VerifyRow("FE contact reference " + scene + ": load share of each pair, double contact",
                    "CalculiX F_j / sum F", "hybrid model", test::Sci(worst_share) + " largest",
                    "0.015", worst_share <= kTolShare);
  }
}
