// Mesh stiffness of the hybrid model (FE influence tables + local contact term, solved as a
// contact problem over one mesh cycle) against ISO 6336-1 method B (c′ and c_γα) for the ISO
// basic-rack pairs (20°, x = 0; 20/40 and 30/30 teeth) and the paper's sun–planet pair; the
// ring–planet (internal) mesh is reported beside them; and against the potential-energy method of
// verification/support/pem_reference.hpp (its own code path: Yang & Lin, Tian, Sainsot). docs/model.md
// §8: a sound FE + local model lands within roughly ±20 % of ISO and closer to a careful PEM.
#include <catch2/catch.hpp>

#include <map>
#include <string>

#include "../unit/compliance/test_meshes.hpp"
#include "epicycle/compliance/iso6336.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "figures.hpp"
#include "pem_reference.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using compliance::testing::Figure;

namespace {

struct PairRun {
  transmission::Scene scene;
  transmission::MeshStiffnessResult result;
  transmission::MeshStiffnessResult uncoupled;  ///< teeth as independent springs (PEM's premise)
  compliance::iso6336::PairData iso;
  double contact_ratio = 0;
};

// One run per scene file, shared by the test cases (the tables are the expensive part).
const PairRun& Run(const std::string& file) {
  static std::map<std::string, PairRun> runs;
  auto it = runs.find(file);
  if (it != runs.end()) return it->second;
  PairRun r;
  r.scene = transmission::ParseScene(test::SceneText(file), file);
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(r.scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  transmission::FeComplianceOptions tables;
  tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;  // shared by the suite's processes
  const transmission::FePairCompliance fe(r.scene, pair, tables);
  transmission::MeshStiffnessOptions o;
  o.positions = 40;
  r.result = transmission::ComputeMeshStiffness(setup, pair, fe, o);
  o.tooth_coupling = false;
  r.uncoupled = transmission::ComputeMeshStiffness(setup, pair, fe, o);
  r.iso = transmission::IsoPairData(pair);
  r.contact_ratio = pair.summary().contact_ratio_iso;
  return runs.emplace(file, std::move(r)).first->second;
}

}  // namespace

TEST_CASE("Mesh stiffness within 20 % of ISO 6336-1 (c_gamma_alpha and c')",
          "[reference][stiffness]") {
  for (const std::string file :
       {"iso_pair_20_40.toml", "iso_pair_30_30.toml", "paper_sun_planet.toml"}) {
    const PairRun& r = Run(file);
    INFO(file);
    REQUIRE(r.result.failed == 0);
    const double c_gamma = compliance::iso6336::MeshStiffness(r.iso);
    const double c_prime = compliance::iso6336::SinglePairStiffness(r.iso);
    const double mean = r.result.mean_per_width(), peak = r.result.peak_pair_per_width();
    Figure("stiffness " + file + ": mean " + compliance::testing::Sci(mean) +
           " N/(mm um) vs c_ga " + compliance::testing::Sci(c_gamma) + " (ratio " +
           compliance::testing::Sci(mean / c_gamma) + "), peak pair " +
           compliance::testing::Sci(peak) + " vs c' " + compliance::testing::Sci(c_prime) +
           " (ratio " + compliance::testing::Sci(peak / c_prime) + "), eps_alpha " +
           compliance::testing::Sci(r.contact_ratio));
    CHECK(mean / c_gamma >= 0.8);
    CHECK(mean / c_gamma <= 1.2);
    CHECK(peak / c_prime >= 0.8);
    CHECK(peak / c_prime <= 1.2);
    test::VerifyRow("mesh stiffness " + file + ": mean over a mesh cycle [N/(mm um)]",
                    "ISO 6336-1 c_gamma_alpha = " + test::Sci(c_gamma), test::Sci(mean),
                    test::Sci(mean / c_gamma - 1.0) + " relative", "20 %",
                    std::abs(mean / c_gamma - 1.0) <= 0.2);
    test::VerifyRow("mesh stiffness " + file + ": peak single pair [N/(mm um)]",
                    "ISO 6336-1 c' = " + test::Sci(c_prime), test::Sci(peak),
                    test::Sci(peak / c_prime - 1.0) + " relative", "20 %",
                    std::abs(peak / c_prime - 1.0) <= 0.2);
  }
}

TEST_CASE("Mesh stiffness curve: loaded pairs against the rigid geometry and the contact ratio",
          "[reference][stiffness]") {
  // Along one mesh cycle the loaded tooth pairs alternate between one and two. Two geometric
  // references bound the share of the cycle with two pairs: from below, ε_α − 1 (the rigid
  // contact ratio from the tip circles: loaded contact is never shorter than rigid contact); from
  // above, the share of positions where gear 1, turned rigidly by the loaded rotation, overlaps
  // two teeth of gear 2 (a pair can carry load only where that rigid overlap is ≥ 0, since its
  // elastic approach is ≥ 0). Load extends contact beyond the involutes' ends through the tip
  // rounds (the gap there grows only quadratically with roll), so the loaded share exceeds ε_α − 1.
  for (const std::string file : {"iso_pair_20_40.toml", "iso_pair_30_30.toml",
                                 "paper_sun_planet.toml", "paper_planet_ring.toml"}) {
    const PairRun& r = Run(file);
    INFO(file);
    REQUIRE(r.result.failed == 0);
    const geometry::GearPair pair(transmission::MakeMeshPair(r.scene, nullptr, "").spec);
    geometry::ContactSearchOptions search;
    search.gap_window = r.scene.gap_window;
    int two = 0, rigid_two = 0;
    for (const auto& s : r.result.samples) {
      CHECK(s.pairs.size() >= 1);
      if (s.pairs.size() >= 2) ++two;
      // Equal approach along the line of action: the pairs' stiffnesses add up to the mesh's
      // (exact for involute contacts; tip-round contacts act off the line of action).
      double sum = 0, share = 0;
      bool involute = true;
      for (const auto& p : s.pairs) {
        sum += p.stiffness;
        share += p.share;
        involute = involute && p.kind == geometry::ContactKind::kInvolute;
      }
      CHECK(share == Approx(1.0).epsilon(1e-9));
      if (involute) CHECK(sum == Approx(s.mesh_stiffness).epsilon(1e-6));
      // The rigid overlaps at the loaded rotation, per tooth pair of the loaded flanks.
      geometry::PairPoses poses = pair.Poses(s.angle);
      poses.gear1.rotation += s.rotation;
      std::map<std::pair<int, int>, double> rigid;
      for (const auto& c : pair.Contacts(poses, search)) {
        if (c.side_a != pair.loaded_side()) continue;
        auto [it, fresh] = rigid.try_emplace({c.tooth_a, c.tooth_b}, c.overlap);
        if (!fresh) it->second = std::max(it->second, c.overlap);
      }
      int overlapping = 0;
      for (const auto& [teeth, overlap] : rigid) overlapping += overlap >= 0 ? 1 : 0;
      if (overlapping >= 2) ++rigid_two;
      for (const auto& p : s.pairs) {
        const auto it = rigid.find({p.tooth1, p.tooth2});
        REQUIRE(it != rigid.end());
        CHECK(it->second >= -1e-9);  // loaded ⇒ rigidly overlapping at the loaded rotation
      }
    }
    const double n = static_cast<double>(r.result.samples.size());
    const double measured = two / n;
    Figure("stiffness " + file + ": two-pair share " + compliance::testing::Sci(measured) +
           " (rigid at the loaded rotation " + compliance::testing::Sci(rigid_two / n) +
           ", eps_alpha - 1 = " + compliance::testing::Sci(r.contact_ratio - 1.0) +
           "); mesh stiffness " + compliance::testing::Sci(r.result.min_stiffness) + " .. " +
           compliance::testing::Sci(r.result.max_stiffness) + " N/m, mean " +
           compliance::testing::Sci(r.result.mean_per_width()) + " N/(mm um)");
    CHECK(measured >= r.contact_ratio - 1.0 - 1.0 / n);
    CHECK(two <= rigid_two);
    if (file == "paper_planet_ring.toml") {
      const double c_gamma = compliance::iso6336::MeshStiffness(r.iso);
      test::ReportRow("mesh stiffness paper_planet_ring.toml (internal): mean [N/(mm um)]",
                      "ISO 6336-1 c_gamma_alpha = " + test::Sci(c_gamma),
                      test::Sci(r.result.mean_per_width()),
                      test::Sci(r.result.mean_per_width() / c_gamma - 1.0) + " relative",
                      "reported beside the external meshes");
    }
  }
}

namespace {

verification::pem::Gear PemGear(const geometry::Gear& g, const transmission::Scene& scene) {
  verification::pem::Gear p;
  p.teeth = g.teeth();
  p.module_m = g.module();
  p.pressure_angle_rad = g.spec().pressure_angle;
  p.profile_shift = g.spec().profile_shift;
  p.tip_radius_m = g.tip_radius();
  p.root_radius_m = g.root_radius();
  p.bore_radius_m = g.spec().hub_radius;
  p.face_width_m = g.spec().face_width;
  p.youngs_modulus_pa = scene.material.youngs_modulus;
  p.poisson_ratio = scene.material.poisson_ratio;
  p.tool_tip_radius_coefficient = g.spec().rack->tip_radius / g.module();
  return p;
}

}  // namespace

TEST_CASE("Mesh stiffness against the potential-energy method", "[reference][stiffness]") {
  // The PEM treats each tooth pair as a spring of its own: the fillet-foundation term of a tooth
  // sees only that tooth's load. Two comparisons are like with like:
  //  - single-contact zone: the model's one loaded pair against PEM's single pair at the same
  //    point of the line of action (s = r_b1 · roll of gear 1), position by position;
  //  - mean mesh stiffness of the model with the teeth uncoupled (off-diagonal C_jk dropped)
  //    against PEM's mean.
  // Both within ±15 % (docs/model.md §8). The model's coupled mean is reported beside them: the bodies
  // couple the two loaded pairs of the double-contact zone, which PEM omits.
  for (const std::string file :
       {"iso_pair_20_40.toml", "iso_pair_30_30.toml", "paper_sun_planet.toml"}) {
    const PairRun& r = Run(file);
    INFO(file);
    REQUIRE(r.result.failed == 0);
    REQUIRE(r.uncoupled.failed == 0);
    const geometry::GearPair pair(transmission::MakeMeshPair(r.scene, nullptr, "").spec);
    verification::pem::GearPair pem;
    pem.gear1 = PemGear(pair.gear1(), r.scene);
    pem.gear2 = PemGear(pair.gear2(), r.scene);
    pem.centre_distance_m = pair.spec().centre_distance;
    double worst = 0.0;
    int single = 0;
    for (const auto& s : r.result.samples) {
      if (s.pairs.size() != 1 || s.pairs[0].kind != geometry::ContactKind::kInvolute) continue;
      const double position = pair.gear1().base_radius() * s.pairs[0].roll1;
      const double k_pem = verification::pem::SinglePairStiffness(pem, position);
      const double ratio = s.pairs[0].stiffness / k_pem;
      worst = std::max(worst, std::abs(ratio - 1.0));
      CHECK(ratio >= 0.85);
      CHECK(ratio <= 1.15);
      ++single;
    }
    CHECK(single >= 3);
    const double b = r.result.face_width;
    const double pem_mean =
        verification::pem::PerUnitWidth(verification::pem::MeanMeshStiffness(pem), b);
    const double uncoupled = r.uncoupled.mean_per_width(), coupled = r.result.mean_per_width();
    Figure("stiffness " + file + " vs PEM: single-pair zone worst deviation " +
           compliance::testing::Sci(worst) + " over " + std::to_string(single) +
           " positions; mean uncoupled " + compliance::testing::Sci(uncoupled) + " vs PEM " +
           compliance::testing::Sci(pem_mean) + " N/(mm um) (ratio " +
           compliance::testing::Sci(uncoupled / pem_mean) + "); coupled mean " +
           compliance::testing::Sci(coupled) + " (ratio to PEM " +
           compliance::testing::Sci(coupled / pem_mean) + ")");
    CHECK(uncoupled / pem_mean >= 0.85);
    CHECK(uncoupled / pem_mean <= 1.15);
    test::VerifyRow("mesh stiffness " + file + ": single pair along the single-contact zone",
                    "potential-energy method at the same point of the LOA",
                    std::to_string(single) + " positions", test::Sci(worst) + " largest relative",
                    "15 %", worst <= 0.15);
    test::VerifyRow("mesh stiffness " + file + ": mean, teeth uncoupled [N/(mm um)]",
                    "potential-energy method " + test::Sci(pem_mean), test::Sci(uncoupled),
                    test::Sci(uncoupled / pem_mean - 1.0) + " relative", "15 %",
                    std::abs(uncoupled / pem_mean - 1.0) <= 0.15);
    test::ReportRow("mesh stiffness " + file + ": mean, the model (teeth coupled by the bodies)",
                    "potential-energy method " + test::Sci(pem_mean) + " (no coupling)",
                    test::Sci(coupled), test::Sci(coupled / pem_mean - 1.0) + " relative",
                    "issue: 15 %; the coupling PEM omits, see docs/verification.md");
    // Coupling through the bodies can only soften the double-contact zone.
    CHECK(coupled <= uncoupled * (1.0 + 1e-9));
  }
}
