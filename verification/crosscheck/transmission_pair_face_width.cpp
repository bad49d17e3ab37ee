// The mesh-stiffness driver on a gear pair with slices of the face width and a lead slope
// (docs/model.md §10, "Face width"): at every position where the whole face of every loaded tooth
// pair carries, K_Hβ is the closed form of uncoupled slices, 1 + c F_β b/(2F) (1 − 1/S), with
// c b = k the pair's own mesh stiffness at that position from the plane driver (one slice).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "epicycle/transmission/stiffness_run.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"

using namespace epicycle;

namespace {

constexpr int kSlices = 8;
constexpr double kLeadSlope = 10e-6;  // f_Hβ of gear 1 over its face [m]

// The stiffness driver on the scene `text` (named `name`) over `positions` positions of mesh cycle
// `cycle` (< 0: the cycles a damaged tooth meshes in), with the structural compliance alone: the
// slices are then linear springs, the closed form's assumption (the local term's Hertzian
// flattening makes a slice's stiffness grow with its load).
transmission::StiffnessRecord RunLinear(const std::string& text, const std::string& name,
                                        int positions, int cycle) {
  transmission::StiffnessRequest request;
  request.scene = transmission::ParseScene(text, name);
  request.positions = positions;
  request.cycle = cycle;
  request.threads = 1;
  request.local_terms = false;
  request.tables = test::CachedTables();
  transmission::StiffnessSink none;
  return transmission::RunStiffness(request, none);
}

transmission::StiffnessRecord Run(const std::string& extra) {
  return RunLinear(test::SceneText("paper_sun_planet.toml") + extra,
                   "paper_sun_planet.toml" + extra, 24, 0);
}

// The positions of `sliced` (kSlices uncoupled linear slices) at which every slice of every loaded
// tooth pair carries and every loaded contact is an involute one (a tip round's lever is not r_b1):
// the closed forms' assumptions. At each, K_Hβ against `closed(sliced sample, plane sample)`, the
// closed form with a mesh stiffness k. Tolerance: each run settles gear 1's rotation to 1e-11 m
// on the base circle, 7e-7 of the ~15 µm approach, and k enters K − 1 linearly: 2e-6 of K − 1 for
// two runs.
struct WholeFace {
  int used = 0;      // positions checked
  double worst = 0;  // largest |K − K_cf|/(K_cf − 1)
};
template <class Closed>
WholeFace CheckWholeFace(const transmission::StiffnessRecord& plane,
                         const transmission::StiffnessRecord& sliced, Closed closed) {
  WholeFace fit;
  for (std::size_t i = 0; i < plane.result.samples.size(); ++i) {
    const transmission::MeshSample& p = plane.result.samples[i];
    const transmission::MeshSample& s = sliced.result.samples[i];
    REQUIRE(s.face_load.line_load.size() == kSlices);
    bool whole = true;
    for (std::size_t j = 0; j + kSlices <= s.contacts.size(); j += kSlices) {
      int loaded = 0;
      for (int k = 0; k < kSlices; ++k) {
        loaded += s.force(static_cast<Eigen::Index>(j + k)) > 0;
        if (s.force(static_cast<Eigen::Index>(j + k)) > 0 &&
            s.contacts[j + k].kind != geometry::ContactKind::kInvolute)
          whole = false;
      }
      whole = whole && (loaded == 0 || loaded == kSlices);
    }
    if (!whole) continue;
    ++fit.used;
    INFO("gear 1 at " << geometry::Deg(p.angle) << " deg: k " << p.mesh_stiffness << " N/m");
    const double k_cf = closed(s, p);
    CHECK(std::abs(s.face_load.k_h_beta - k_cf) <= 2e-6 * (k_cf - 1));
    fit.worst = std::max(fit.worst, std::abs(s.face_load.k_h_beta - k_cf) / (k_cf - 1));
  }
  return fit;
}

}  // namespace

TEST_CASE(
    "face width of a gear pair: a lead slope's K_Hbeta over the mesh cycle is the closed "
    "form 1 + c F_beta b/(2F)(1 - 1/S) with the pair's own mesh stiffness",
    "[crosscheck][transmission][face_width]") {
  const transmission::StiffnessRecord plane = Run("");
  const transmission::StiffnessRecord sliced = Run(
      "\n[face_width]\nslices = " + std::to_string(kSlices) +
      "\n[[face_width.lead]]\ngear = \"gear1\"\nslope_um = " + std::to_string(kLeadSlope * 1e6) +
      "\n");
  REQUIRE(plane.result.failed == 0);
  REQUIRE(sliced.result.failed == 0);
  REQUIRE(sliced.result.slices == kSlices);
  REQUIRE(plane.result.samples.size() == sliced.result.samples.size());
  const transmission::Scene scene =
      transmission::ParseScene(test::SceneText("paper_sun_planet.toml"), "paper_sun_planet.toml");
  const geometry::GearPair pair = transmission::MakePair(scene, scene.pair);
  // F: the normal force of gear 1's torque on its base circle (every involute contact's lever).
  const double force = std::abs(scene.pair_torque) / pair.gear1().base_radius();
  // Each slice is a linear spring of stiffness k/S under the gap −z_s F_β/b (the lead slope's
  // turn of gear 1's sections times its involute contacts' lever r_b1), whose mean is 0: slice s
  // carries F/S + (k/S) z_s F_β/b, and the largest, at z = ±(b/2)(1 − 1/S), gives the closed form.
  // Positions where a tooth pair enters or leaves are left out (CheckWholeFace).
  const WholeFace fit = CheckWholeFace(
      plane, sliced, [&](const transmission::MeshSample& s, const transmission::MeshSample& p) {
        // A gear 1 lead slope turns its +z sections ahead: the load gathers at one end. The end
        // follows from the sign of the gap change, −z F_β/b: the −z end for F_β > 0.
        CHECK(s.face_load.largest_z ==
              Approx(-0.5 * pair.gear1().spec().face_width * (1 - 1.0 / kSlices)));
        // The stiffness of the mesh as a whole is the plane pair's (the gap's mean is 0).
        CHECK(s.mesh_stiffness == Approx(p.mesh_stiffness).epsilon(2e-6));
        return 1 + p.mesh_stiffness * kLeadSlope / (2 * force) * (1.0 - 1.0 / kSlices);
      });
  const int used = fit.used;
  const double worst = fit.worst;
  CHECK(used >= 12);  // most of the cycle
  // Over the cycle, with the pair's mean stiffness per width c̄: K̄ = 1 + c̄ F_β b/(2F)(1 − 1/S)
  // where every position is used (an aside: the record's figures).
  const double c_b = plane.result.mean_stiffness;
  test::VerifyRow("pair with a lead slope: K_Hbeta per position (8 slices, structural)",
                  "closed form 1 + c F_beta b/(2F)(1 - 1/S), c b the plane run's k",
                  std::to_string(used) + " of 24 positions; mean K_Hbeta " +
                      test::Sci(sliced.result.k_h_beta_mean, 6) + ", with mean c: " +
                      test::Sci(1 + c_b * kLeadSlope / (2 * force) * (1.0 - 1.0 / kSlices), 6),
                  "largest |K - K_cf|/(K_cf - 1) " + test::Sci(worst), "<= 2e-6", worst <= 2e-6);
}

// The scene's lead modifications ([[face_width.lead]] crowning_um, end_relief_um with
// end_relief_length_mm; docs/scenes.md "Face width") through the same driver: each slice's gap
// is the material removed at its centre, as docs/model.md §10 defines it, and K_Hβ is the closed
// form of uncoupled linear slices under that gap.
TEST_CASE(
    "face width of a gear pair: a crowning's K_Hbeta is 1 + k C_beta/(3F)(1 - 4/S^2) and an end "
    "relief's 1 + k (mean gap)/F, k the mesh's stiffness at its pose",
    "[crosscheck][transmission][face_width]") {
  const transmission::StiffnessRecord plane = Run("");
  REQUIRE(plane.result.failed == 0);
  const transmission::Scene scene =
      transmission::ParseScene(test::SceneText("paper_sun_planet.toml"), "paper_sun_planet.toml");
  const geometry::GearPair pair = transmission::MakePair(scene, scene.pair);
  const double force = std::abs(scene.pair_torque) / pair.gear1().base_radius();  // F [N]
  const double b = pair.gear1().spec().face_width;
  const std::string table = "\n[face_width]\nslices = " + std::to_string(kSlices) +
                            "\n[[face_width.lead]]\ngear = \"gear1\"\n";
  // Slice s, a linear spring of stiffness k/S under the gap g_s, carries (k/S)(a − g_s), the
  // approach a from Σ = F: a = F/k + ḡ, the line load over the mean 1 + (k/F)(ḡ − g_s), and
  // the largest the slice of the smallest gap: K_Hβ = 1 + (k/F)(ḡ − min g). A gap of mean ḡ > 0
  // turns gear 1 by ḡ/r_b1 further than the plane run does, which moves its contacts along the
  // flanks and k with them (K − 1 then differs by up to 6e-5 from the plane run at that angle);
  // k is therefore the sliced mesh's own at its pose, F/(a − ḡ) with a its approach.
  const auto own_k = [&](const transmission::MeshSample& s, double mean_gap) {
    return force / (s.approach - mean_gap);
  };
  SECTION("crowning C_beta = 4 um: g = C (2z/b)^2") {
    // Midpoints z_s = (s + 1/2 − S/2) b/S: ḡ = (C/3)(1 − 1/S²); the smallest gap at z = ±b/(2S),
    // C/S²: K_Hβ = 1 + (k C/(3F))(1 − 4/S²) (even S), the whole face loaded while
    // C (1 − 1/S)² ≈ 3.1 µm stays below the ~15 µm approach.
    constexpr double kCrown = 4e-6;
    const double mean_gap = kCrown / 3 * (1 - 1.0 / (kSlices * kSlices));
    const transmission::StiffnessRecord sliced = Run(table + "crowning_um = 4.0\n");
    REQUIRE(sliced.result.failed == 0);
    const WholeFace fit = CheckWholeFace(
        plane, sliced, [&](const transmission::MeshSample& s, const transmission::MeshSample&) {
          // The two middle slices carry alike; either is the largest.
          CHECK(std::abs(s.face_load.largest_z) == Approx(0.5 * b / kSlices));
          return 1 + own_k(s, mean_gap) * kCrown / (3 * force) * (1 - 4.0 / (kSlices * kSlices));
        });
    INFO("largest |K - K_cf|/(K_cf - 1) " << fit.worst);
    CHECK(fit.used >= 12);
  }
  SECTION("end relief C_I = 4 um over L_I = b/4: g = C_I (|z| - b/4)/L_I beyond b/4") {
    // S = 8 on b: the centres at |z| = 5b/16 and 7b/16 lie 1/16 and 3/16 of b into the relief,
    // g = C_I/4 and 3 C_I/4 (two slices each), the middle four untouched: ḡ = C_I/4, min g = 0,
    // K_Hβ = 1 + k C_I/(4F), the largest load on the untouched middle.
    static_assert(kSlices == 8, "the gaps above are the 8 slices'");
    constexpr double kRelief = 4e-6;
    const transmission::StiffnessRecord sliced =
        Run(table + "end_relief_um = 4.0\nend_relief_length_mm = " + std::to_string(b / 4 * 1e3) +
            "\n");
    REQUIRE(sliced.result.failed == 0);
    const WholeFace fit = CheckWholeFace(
        plane, sliced, [&](const transmission::MeshSample& s, const transmission::MeshSample&) {
          CHECK(std::abs(s.face_load.largest_z) < b / 4);
          return 1 + own_k(s, kRelief / 4) * kRelief / (4 * force);
        });
    INFO("largest |K - K_cf|/(K_cf - 1) " << fit.worst);
    CHECK(fit.used >= 12);
  }
}

// Pits with slices of the face width in a gear pair (docs/face_width.md, "Slices"): each slice's
// gap grows by the depth of the pits covering its centre. The ISO 20/40 pair's spall fixture
// (verification/data/fe_reference/iso_pair_20_40_spall.toml: pinion tooth 19's loaded flank, roll
// 4.5..18°, 10 µm deep), linear slices (the structural compliance alone) as above.
namespace {

std::string SpallScene(double width_fraction, int slices) {
  std::ifstream in(std::string(EPICYCLE_TEST_DATA_DIR) + "/fe_reference/iso_pair_20_40_spall.toml");
  REQUIRE(in);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const std::string key = "width_fraction = 1.0";
  const std::size_t at = s.find(key);
  REQUIRE(at != std::string::npos);
  s.replace(at, key.size(), "width_fraction = " + std::to_string(width_fraction));
  if (slices > 1) s += "\n[face_width]\nslices = " + std::to_string(slices) + "\n";
  return s;
}

transmission::StiffnessRecord RunSpall(double width_fraction, int slices) {
  return RunLinear(SpallScene(width_fraction, slices), "iso_pair_20_40_spall.toml", 12, -1);
}

}  // namespace

TEST_CASE(
    "face width of a gear pair: a pit over the whole face in uncoupled slices is the plane "
    "model's pit, and a pit over half the face lowers the gap of the slices it covers by its "
    "depth",
    "[crosscheck][transmission][face_width][damage]") {
  constexpr int kS = 4;
  constexpr double kDepth = 10e-6;  // the fixture's [m]
  const transmission::StiffnessRecord plane = RunSpall(1.0, 1);
  const transmission::StiffnessRecord whole = RunSpall(1.0, kS);
  REQUIRE(plane.result.failed == 0);
  REQUIRE(whole.result.failed == 0);
  REQUIRE(plane.result.samples.size() == whole.result.samples.size());
  // S uncoupled slices (W = S I) of one contact's compliance C in parallel are C, each slice's
  // gap lowered by the same depth: the plane problem, slice by slice. Both runs settle gear 1's
  // rotation to 1e-11 m on the base circle, 7e-7 of the ~20 µm approach: 2e-6 for the two.
  for (std::size_t i = 0; i < plane.result.samples.size(); ++i) {
    INFO("position " << i);
    CHECK(whole.result.samples[i].mesh_stiffness ==
          Approx(plane.result.samples[i].mesh_stiffness).epsilon(2e-6));
  }
  // Half the face: slices 0 and 1 (centres at 1/8 and 3/8 of b from the pit's edge) lie in the
  // pit, 2 and 3 do not. Where the pitted flank touches within the pit's roll range the gap of
  // the covered slices is lower by the depth exactly (no lead: the slices' gaps are otherwise
  // equal), and they carry less.
  const transmission::StiffnessRecord half = RunSpall(0.5, kS);
  REQUIRE(half.result.failed == 0);
  int pitted = 0;
  for (const transmission::MeshSample& s : half.result.samples)
    for (std::size_t j = 0; j + kS <= s.contacts.size(); j += kS) {
      const double step = s.contacts[j + 3].overlap - s.contacts[j].overlap;
      CHECK(s.contacts[j].overlap == s.contacts[j + 1].overlap);
      CHECK(s.contacts[j + 2].overlap == s.contacts[j + 3].overlap);
      if (step == 0) continue;
      ++pitted;
      CHECK(step == Approx(kDepth).epsilon(1e-9));
      CHECK(s.contacts[j].tooth_a == 19);
      if (s.force(static_cast<Eigen::Index>(j + 3)) > 0)
        CHECK(s.force(static_cast<Eigen::Index>(j)) < s.force(static_cast<Eigen::Index>(j + 3)));
    }
  CHECK(pitted > 0);
}
