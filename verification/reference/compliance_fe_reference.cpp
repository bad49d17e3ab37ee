// The hybrid model's mesh stiffness, loaded transmission error and tooth-pair load shares against
// the full-FE contact reference (CalculiX: both gears meshed by gmsh from the exact profile,
// second-order plane-strain elements refined at the contacts, frictionless surface-to-surface
// contact; verification/fe_reference and tools/fe_reference.sh). The reference's results are
// committed in verification/data/fe_reference/<scene>.csv (ccx is not needed here); this test
// recomputes the hybrid model at the same positions of its 48-position grid and compares.
//
// Tolerance: the reference's own error (its mesh-convergence and penalty studies) plus the hybrid
// model's own join uncertainty (h ± 50 %), derived in the test case; positions whose contact is
// at a tooth's tip corner are reported, not asserted (docs/fe_reference.md explains why).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "csv_rows.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "fe_reference_grid.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;

namespace {

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

// The hybrid model at the reference's positions, compared. Zones by the reference's loaded pairs
// (share above 1 %); "tip positions": a loaded pair touches through a tip round here or one grid
// step away (the contact then sits within a Hertzian width or two of a tooth's tip corner).
struct Comparison {
  int flank = 0, tips = 0, count[2] = {0, 0};
  double mean[2] = {0, 0}, mean_fe[2] = {0, 0}, peak = 0, peak_fe = 0;
  double worst_k = 0, worst_te = 0, worst_share = 0;  // flank positions: |relative|, |absolute|
  double worst_tip_k = 0, worst_tip_share = 0;
  double signed_min = 1e9, signed_max = -1e9;  // k/k_FE − 1 over the flank positions
  double Offset(int zone) const { return mean[zone] / mean_fe[zone] - 1.0; }
  double PeakOffset() const { return peak / peak_fe - 1.0; }
};

Comparison Compare(const std::string& scene, const std::vector<FeRow>& reference,
                   const transmission::FeComplianceOptions& tables, int refinement = 1,
                   double join_depth_factor = 0.0) {
  transmission::Scene sc =
      transmission::ParseScene(test::SceneText(scene + ".toml"), scene + ".toml");
  sc.model.mesh_refinement = refinement;
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(sc, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  if (join_depth_factor > 0) {  // one h for both bodies: the factor times the smaller default
    const transmission::FePairCompliance defaults(sc, pair, tables);
    sc.model.join_depth =
        join_depth_factor * std::min(defaults.JoiningDepth(0), defaults.JoiningDepth(1));
  }
  const transmission::FePairCompliance fe(sc, pair, tables);
  const transmission::MeshStiffnessResult r = test::FeReferenceSweep(setup, pair, fe);
  REQUIRE(r.failed == 0);
  const double b_mm = r.face_width * 1e3;
  Comparison c;
  for (const FeRow& ref : reference) {
    const transmission::MeshSample& s = r.samples.at(ref.index);
    REQUIRE(geometry::Deg(s.angle) == Approx(ref.angle_deg).margin(1e-5));
    REQUIRE(s.converged);
    const bool tip = test::TipPosition(r, ref.index);
    const double k = s.mesh_stiffness / b_mm / 1e6;
    const double dk = k / ref.k - 1.0;
    const double dte = std::abs(s.rotation * 1e6) / std::abs(ref.te_urad) - 1.0;
    int loaded = 0;
    for (const auto& [teeth, share] : ref.share) loaded += share > 0.01 ? 1 : 0;
    const int zone = loaded >= 2 ? 1 : 0;
    c.mean[zone] += k;
    c.mean_fe[zone] += ref.k;
    ++c.count[zone];
    c.peak = std::max(c.peak, k);
    c.peak_fe = std::max(c.peak_fe, ref.k);
    double dshare = 0;
    for (const auto& [teeth, share] : ref.share) {
      double hybrid = 0;
      for (const auto& p : s.pairs)
        if (std::to_string(p.tooth1) + "/" + std::to_string(p.tooth2) == teeth) hybrid = p.share;
      dshare = std::max(dshare, std::abs(hybrid - share));
    }
    if (tip) {
      ++c.tips;
      c.worst_tip_k = std::max(c.worst_tip_k, std::abs(dk));
      c.worst_tip_share = std::max(c.worst_tip_share, dshare);
      continue;
    }
    ++c.flank;
    c.worst_k = std::max(c.worst_k, std::abs(dk));
    c.worst_te = std::max(c.worst_te, std::abs(dte));
    c.worst_share = std::max(c.worst_share, dshare);
    c.signed_min = std::min(c.signed_min, dk);
    c.signed_max = std::max(c.signed_max, dk);
  }
  for (int z : {0, 1}) {
    c.mean[z] /= std::max(c.count[z], 1);
    c.mean_fe[z] /= std::max(c.count[z], 1);
  }
  return c;
}

std::string Pct(double x) {
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << std::showpos << 100 * x << "%";
  return s.str();
}

const char* const kScenes[] = {"iso_pair_20_40", "paper_sun_planet", "paper_planet_ring"};

}  // namespace

TEST_CASE("Mesh stiffness, transmission error and load shares against the FE contact reference",
          "[reference][slow][stiffness][fe_reference]") {
  // Relative tolerance on k and θ (docs/fe_reference.md), the sum of
  //  - the reference's discretisation error: kFeMesh, twice the largest change of k from its
  //    mesh to the 2× refined one (−0.061 % at 2.25°, −0.044 % at 13.5°: a Richardson bound for
  //    an observed order ≥ 1);
  //  - its penalty: kFePenalty, the change of k when K goes from 1e8 to 1e9 MPa/mm (+0.031 %),
  //    ×10/9 for the rest of the way to K → ∞;
  //  - the hybrid model's own discretisation: kTables, twice (a Richardson bound, as for the
  //    reference) the largest change of a zone's mean or peak k when every table is refined ×2
  //    (the [.fe_reference_study] case below, layer term on): ISO 0.18 % (peak), sun–planet
  //    0.20 % (single), planet–ring 0.45 % (single: the ring's and planet's read-outs at depth).
  // θ(M) interpolation between the reference's load steps 14 % apart: below 1e-4.
  constexpr double kFeMesh = 2 * 0.00061;
  constexpr double kFePenalty = 0.00034;
  const std::map<std::string, double> tables_change = {
      {"iso_pair_20_40", 0.0018}, {"paper_sun_planet", 0.0020}, {"paper_planet_ring", 0.0045}};
  transmission::FeComplianceOptions tables;
  tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  transmission::FeComplianceOptions paper_join = tables;  // the join without the layer term
  paper_join.table.layer_term = false;
  for (const std::string scene : kScenes) {
    INFO(scene);
    const double kTables = 2 * tables_change.at(scene);
    const double kTolK = kFeMesh + kFePenalty + kTables;
    // A share F_j/ΣF moves by s(1 − s)(ε_j − ε_k) ≤ ε/2 when the pairs' compliances are off by ±ε.
    const double kTolShare = 0.5 * kTolK;
    const std::vector<FeRow> reference = ReadReference(scene);
    REQUIRE(reference.size() >= 12);
    const Comparison c = Compare(scene, reference, tables);
    for (int z : {0, 1}) CHECK(c.count[z] >= 3);
    const std::string tol = test::Sci(kTolK) + " (FE mesh + penalty + tables)";
    const std::string n = std::to_string(c.flank) + " flank positions";
    CHECK(c.worst_k <= kTolK);
    CHECK(c.worst_te <= kTolK);
    CHECK(c.worst_share <= kTolShare);
    test::VerifyRow("FE contact reference " + scene + ": mesh stiffness per position",
                    "CalculiX contact, " + n, "hybrid model",
                    test::Sci(c.worst_k) + " largest relative", tol, c.worst_k <= kTolK);
    test::VerifyRow("FE contact reference " + scene + ": loaded transmission error per position",
                    "CalculiX gear-1 rotation, " + n, "hybrid model",
                    test::Sci(c.worst_te) + " largest relative", tol, c.worst_te <= kTolK);
    test::VerifyRow("FE contact reference " + scene + ": load share of each tooth pair",
                    "CalculiX F_j / sum F, " + n, "hybrid model",
                    test::Sci(c.worst_share) + " largest", test::Sci(kTolShare),
                    c.worst_share <= kTolShare);
    for (int z : {0, 1}) {
      const double err = std::abs(c.Offset(z));
      CHECK(err <= kTolK);
      test::VerifyRow("FE contact reference " + scene + ": mean k, " + (z ? "double" : "single") +
                          "-contact positions [N/(mm um)]",
                      "CalculiX " + test::Sci(c.mean_fe[z]), test::Sci(c.mean[z]),
                      test::Sci(err) + " relative", tol, err <= kTolK);
    }
    const double dpeak = std::abs(c.PeakOffset());
    CHECK(dpeak <= kTolK);
    test::VerifyRow("FE contact reference " + scene + ": peak k [N/(mm um)]",
                    "CalculiX " + test::Sci(c.peak_fe), test::Sci(c.peak),
                    test::Sci(dpeak) + " relative", tol, dpeak <= kTolK);
    // The same model without the layer term (the join as the paper has it): the offset this
    // issue was about, kept in the table as the evidence for the fix.
    const Comparison before = Compare(scene, reference, paper_join);
    auto offsets = [](const Comparison& x) {
      return "single " + Pct(x.Offset(0)) + ", double " + Pct(x.Offset(1)) + ", peak " +
             Pct(x.PeakOffset()) + "; flank positions " + Pct(x.signed_min) + " to " +
             Pct(x.signed_max);
    };
    test::ReportRow("FE contact reference " + scene + ": k offset, join without the layer term",
                    "CalculiX", "hybrid model (paper's join)", offsets(before),
                    "stiffer at every contact: the layer's structural strain is missing");
    test::ReportRow("FE contact reference " + scene + ": k offset, join with the layer term",
                    "CalculiX", "hybrid model", offsets(c),
                    "within the reference's own uncertainty " + test::Sci(kFeMesh + kFePenalty) +
                        " plus the tables' " + test::Sci(kTables));
    test::ReportRow(
        "FE contact reference " + scene + ": tip positions (" + std::to_string(c.tips) + ")",
        "CalculiX", "hybrid model",
        "k " + test::Sci(c.worst_tip_k) + ", share " + test::Sci(c.worst_tip_share) +
            " largest (without the layer term: k " + test::Sci(before.worst_tip_k) + ", share " +
            test::Sci(before.worst_tip_share) + ")",
        "contact at a tip corner: local term's half-plane premise, docs/fe_reference.md");
  }
}

TEST_CASE("FE contact reference: the hybrid model's own sensitivities (study)",
          "[.fe_reference_study]") {
  // Prints the zone offsets against the reference for the join with and without the layer term,
  // the tables refined ×2, and the join depth h ×0.5 and ×1.5 (one h for both bodies).
  transmission::FeComplianceOptions on;
  on.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  transmission::FeComplianceOptions off = on;
  off.table.layer_term = false;
  for (const std::string scene : kScenes) {
    const std::vector<FeRow> reference = ReadReference(scene);
    for (const bool layer : {true, false}) {
      for (const auto& [refinement, factor] :
           {std::pair{1, 0.0}, std::pair{2, 0.0}, std::pair{1, 0.5}, std::pair{1, 1.0},
            std::pair{1, 1.5}}) {
        const Comparison c = Compare(scene, reference, layer ? on : off, refinement, factor);
        std::printf(
            "%s layer %d refinement %d h-factor %.1f: single %s double %s peak %s flank "
            "%s..%s tip |k| %.4f share %.4f\n",
            scene.c_str(), layer ? 1 : 0, refinement, factor, Pct(c.Offset(0)).c_str(),
            Pct(c.Offset(1)).c_str(), Pct(c.PeakOffset()).c_str(), Pct(c.signed_min).c_str(),
            Pct(c.signed_max).c_str(), c.worst_tip_k, c.worst_tip_share);
        std::fflush(stdout);
      }
    }
  }
}
