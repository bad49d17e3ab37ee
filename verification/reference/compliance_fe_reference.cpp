// The hybrid model's mesh stiffness, loaded transmission error and tooth-pair load shares against
// the full-FE contact reference (CalculiX: both gears meshed by gmsh from the exact profile,
// second-order plane-strain elements refined at the contacts, frictionless surface-to-surface
// contact; verification/fe_reference and tools/fe_reference.sh). The reference's results are
// committed in verification/data/fe_reference/<scene>.csv (ccx is not needed here); this test
// recomputes the hybrid model at the same positions of its 48-position grid and compares.
//
// Tolerance: the reference's own error (its mesh-convergence and penalty studies) plus the hybrid
// model's own join uncertainty (h ± 50 %), derived in the test case; positions whose contact is
// at a tooth's tip corner are reported, not asserted (docs/compliance.md explains why).
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
  // Relative tolerance on k and θ (docs/compliance.md, "FE contact reference"), the sum of
  //  - the reference's discretisation error: kFeMesh, twice the largest change of k from its
  //    mesh to the 2× refined one (−0.061 % at 2.25°, −0.044 % at 13.5°: a Richardson bound for
  //    an observed order ≥ 1);
  //  - its penalty: kFePenalty, the change of k when K goes from 1e8 to 1e9 MPa/mm (+0.031 %),
  //    ×10/9 for the rest of the way to K → ∞;
  //  - the hybrid model's stated accuracy of its join: kJoin, 1.0 % of the approach when the join
  //    depth h moves by ±50 % (docs/compliance.md, the h test of the influence tables).
  // The reference's own part, 0.16 %, is smaller than the offset measured (ISO +0.6 %): the two
  // disagree at that level, per contact, in the join/local term (docs/compliance.md); a
  // ReportRow states it. θ(M) interpolation between steps 14 % apart: below 1e-4.
  constexpr double kFeMesh = 2 * 0.00061;
  constexpr double kFePenalty = 0.00034;
  constexpr double kJoin = 0.010;
  constexpr double kTolK = kFeMesh + kFePenalty + kJoin;
  // A share F_j/ΣF moves by s(1 − s)(ε_j − ε_k) ≤ ε/2 when the pairs' compliances are off by ±ε.
  constexpr double kTolShare = 0.5 * kTolK;
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
    // Tip positions: a loaded pair touches through a tip round here or one grid step away (the
    // contact then sits within a Hertzian width or two of a tooth's tip corner). There the local
    // term's half-plane premise meets the corner; reported, not asserted per position.
    auto tip_at = [&](int i) {
      for (const auto& p : r.samples.at((i + kGrid) % kGrid).pairs)
        if (p.kind != geometry::ContactKind::kInvolute) return true;
      return false;
    };
    const double b_mm = r.face_width * 1e3;
    double worst_k = 0, worst_te = 0, worst_share = 0, worst_tip_k = 0, worst_tip_share = 0;
    double sum[2] = {0, 0}, sum_fe[2] = {0, 0}, peak = 0, peak_fe = 0;
    int count[2] = {0, 0}, tips = 0;
    for (const FeRow& ref : reference) {
      const transmission::MeshSample& s = r.samples.at(ref.index);
      REQUIRE(geometry::Deg(s.angle) == Approx(ref.angle_deg).margin(1e-5));
      REQUIRE(s.converged);
      const bool tip = tip_at(ref.index - 1) || tip_at(ref.index) || tip_at(ref.index + 1);
      tips += tip ? 1 : 0;
      const double k = s.mesh_stiffness / b_mm / 1e6;
      const double dk = std::abs(k / ref.k - 1.0);
      const double dte = std::abs(std::abs(s.rotation * 1e6) / std::abs(ref.te_urad) - 1.0);
      // Zones by the reference's loaded pairs (share above 1 %).
      int loaded = 0;
      for (const auto& [teeth, share] : ref.share) loaded += share > 0.01 ? 1 : 0;
      const int zone = loaded >= 2 ? 1 : 0;
      sum[zone] += k;
      sum_fe[zone] += ref.k;
      ++count[zone];
      peak = std::max(peak, k);
      peak_fe = std::max(peak_fe, ref.k);
      double dshare = 0;
      for (const auto& [teeth, share] : ref.share) {
        double hybrid = 0;
        for (const auto& p : s.pairs)
          if (std::to_string(p.tooth1) + "/" + std::to_string(p.tooth2) == teeth) hybrid = p.share;
        dshare = std::max(dshare, std::abs(hybrid - share));
      }
      if (tip) {
        worst_tip_k = std::max(worst_tip_k, dk);
        worst_tip_share = std::max(worst_tip_share, dshare);
        continue;
      }
      worst_k = std::max(worst_k, dk);
      worst_te = std::max(worst_te, dte);
      worst_share = std::max(worst_share, dshare);
      CHECK(dk <= kTolK);
      CHECK(dte <= kTolK);
      CHECK(dshare <= kTolShare);
    }
    CHECK(count[0] >= 3);
    CHECK(count[1] >= 3);
    const std::string tol = test::Sci(kTolK) + " (FE mesh + penalty + join depth)";
    const std::string n = std::to_string(reference.size() - tips) + " flank positions";
    test::VerifyRow("FE contact reference " + scene + ": mesh stiffness per position",
                    "CalculiX contact, " + n, "hybrid model",
                    test::Sci(worst_k) + " largest relative", tol, worst_k <= kTolK);
    test::VerifyRow("FE contact reference " + scene + ": loaded transmission error per position",
                    "CalculiX gear-1 rotation, " + n, "hybrid model",
                    test::Sci(worst_te) + " largest relative", tol, worst_te <= kTolK);
    test::VerifyRow("FE contact reference " + scene + ": load share of each tooth pair",
                    "CalculiX F_j / sum F, " + n, "hybrid model",
                    test::Sci(worst_share) + " largest", test::Sci(kTolShare),
                    worst_share <= kTolShare);
    for (int z : {0, 1}) {
      const double mean = sum[z] / count[z], mean_fe = sum_fe[z] / count[z];
      const double err = std::abs(mean / mean_fe - 1.0);
      test::VerifyRow("FE contact reference " + scene + ": mean k, " + (z ? "double" : "single") +
                          "-contact positions [N/(mm um)]",
                      "CalculiX " + test::Sci(mean_fe), test::Sci(mean),
                      test::Sci(err) + " relative", tol, err <= kTolK);
      CHECK(err <= kTolK);
    }
    const double dpeak = std::abs(peak / peak_fe - 1);
    test::VerifyRow("FE contact reference " + scene + ": peak k [N/(mm um)]",
                    "CalculiX " + test::Sci(peak_fe), test::Sci(peak),
                    test::Sci(dpeak) + " relative", tol, dpeak <= kTolK);
    CHECK(dpeak <= kTolK);
    test::ReportRow("FE contact reference " + scene +
                        ": offset against the reference's own "
                        "uncertainty",
                    "CalculiX, mesh + penalty " + test::Sci(kFeMesh + kFePenalty), "hybrid model",
                    test::Sci(worst_k) + " largest relative (flank positions)",
                    "beyond the reference's uncertainty: the join/local term, docs/compliance.md");
    test::ReportRow(
        "FE contact reference " + scene + ": tip positions (" + std::to_string(tips) + ")",
        "CalculiX", "hybrid model",
        "k " + test::Sci(worst_tip_k) + ", share " + test::Sci(worst_tip_share) + " largest",
        "contact at a tip corner: local term's half-plane premise, docs/compliance.md");
  }
}
