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
  // It needs every slice of a loaded tooth pair loaded (no slice lifted) and only involute
  // contacts (a tip round's lever is not r_b1); positions where a tooth pair enters or leaves
  // are left out. Tolerance: both runs settle gear 1's rotation to 1e-11 m on the base circle,
  // 7e-7 of the ~15 µm approach, and k enters K − 1 linearly: 2e-6 of K − 1 for the two runs.
  int used = 0;
  double worst = 0;
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
    ++used;
    const double closed = 1 + p.mesh_stiffness * kLeadSlope / (2 * force) * (1.0 - 1.0 / kSlices);
    INFO("gear 1 at " << geometry::Deg(p.angle) << " deg: k " << p.mesh_stiffness << " N/m");
    CHECK(std::abs(s.face_load.k_h_beta - closed) <= 2e-6 * (closed - 1));
    worst = std::max(worst, std::abs(s.face_load.k_h_beta - closed) / (closed - 1));
    // A gear 1 lead slope turns its +z sections ahead: the load gathers at one end. The end
    // follows from the sign of the gap change, −z F_β/b: the −z end for F_β > 0.
    CHECK(s.face_load.largest_z ==
          Approx(-0.5 * pair.gear1().spec().face_width * (1 - 1.0 / kSlices)));
    // The stiffness of the mesh as a whole is the plane pair's (the gap's mean is 0).
    CHECK(s.mesh_stiffness == Approx(p.mesh_stiffness).epsilon(2e-6));
  }
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
