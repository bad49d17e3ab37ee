// A helical gear pair's slices (transmission/helical_slices.hpp, HelicalPairSlices; docs/model.md
// §10, "Helical meshes in slices"), against two references that do not go through the slices:
// at β = 0 the spur pair's expansion of one plane search (PairFaceWidth::Expand), and for a
// helical pair the plane search of the pair turned as a whole by the section's lead.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/pair_face_width.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;

namespace {

geometry::GearPair PairOf(const transmission::Scene& scene) {
  return geometry::GearPair(transmission::MakeMeshPair(scene, nullptr, "").spec);
}

}  // namespace

TEST_CASE("a spur pair's slices are the plane search expanded, bit for bit",
          "[unit][transmission]") {
  const transmission::Scene scene =
      transmission::ParseScene(test::SceneText("iso_pair_20_40.toml"), "iso_pair_20_40.toml");
  const geometry::GearPair pair = PairOf(scene);
  transmission::FaceWidthSpec spec;
  spec.slices = 5;
  const transmission::PairFaceWidth faces(spec, pair);
  geometry::ContactSearchOptions search;
  search.gap_window = 100e-6;
  for (const double cycles : {0.0, 0.31, 0.77}) {
    const geometry::PairPoses poses = pair.Poses(cycles * pair.mesh_cycle());
    std::vector<geometry::PotentialContact> expanded = pair.Contacts(poses, search);
    Eigen::MatrixXd c = Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(expanded.size()),
                                                  static_cast<Eigen::Index>(expanded.size()));
    faces.Expand(&expanded, &c);  // contact j's slice s at j S + s
    const transmission::PairSliceContacts sliced =
        transmission::HelicalPairSlices(pair, faces, poses, search);  // slice-major
    REQUIRE(sliced.contacts.size() == expanded.size());
    const std::size_t n = expanded.size() / 5;
    for (std::size_t s = 0; s < 5; ++s)
      for (std::size_t j = 0; j < n; ++j) {
        const geometry::PotentialContact& a = sliced.contacts[s * n + j];
        const geometry::PotentialContact& b = expanded[j * 5 + s];
        CHECK(sliced.slice[s * n + j] == static_cast<int>(s));
        CHECK(sliced.section_turn[s * n + j][0] == 0.0);
        CHECK(sliced.section_turn[s * n + j][1] == 0.0);
        CHECK(a.tooth_a == b.tooth_a);
        CHECK(a.tooth_b == b.tooth_b);
        CHECK(a.overlap == b.overlap);
        CHECK(a.lever_a == b.lever_a);
      }
  }
}

TEST_CASE("a helical pair's slice is the plane pair turned by its section's lead",
          "[unit][transmission]") {
  // Gear 1 right hand, gear 2 left: the section at z is turned by Δθ_1 = +2 tan β z/d_1 on
  // gear 1 and Δθ_2 = −2 tan β z/d_2 on gear 2, which is the pair's own kinematic turn by Δθ_1
  // (gear 2 follows at −z_1/z_2 Δθ_1 = −2 tan β z/d_2, the same base-circle arc): every slice is
  // the plane pair at gear-1 angle θ + Δθ_1(z_s). Overlaps agree to the rounding of the angle
  // sums: |Δ| ≲ r_b · 1e-15 rad ≈ 1e-16 m, checked to 1e-12 m.
  const transmission::Scene scene = transmission::ParseScene(
      test::SceneText("iso_pair_20_40_helical.toml"), "iso_pair_20_40_helical.toml");
  const geometry::GearPair pair = PairOf(scene);
  REQUIRE(pair.gear1().spec().helix.helical());
  transmission::FaceWidthSpec spec;
  spec.slices = 7;
  const transmission::PairFaceWidth faces(spec, pair);
  geometry::ContactSearchOptions search;
  search.gap_window = 100e-6;
  const double beta = 15.0 * std::acos(-1.0) / 180, d1 = 20 * 4e-3 / std::cos(beta);
  for (const double cycles : {0.0, 0.43}) {
    const double angle = cycles * pair.mesh_cycle();
    const transmission::PairSliceContacts sliced =
        transmission::HelicalPairSlices(pair, faces, pair.Poses(angle), search);
    for (int s = 0; s < 7; ++s) {
      INFO("slice " << s << ", cycles " << cycles);
      const double z = transmission::SliceCentre(s, 7, 20e-3);
      const double turn = 2 * std::tan(beta) * z / d1;
      const std::vector<geometry::PotentialContact> plane =
          pair.Contacts(pair.Poses(angle + turn), search);
      std::vector<const geometry::PotentialContact*> mine;
      for (std::size_t j = 0; j < sliced.contacts.size(); ++j)
        if (sliced.slice[j] == s) {
          mine.push_back(&sliced.contacts[j]);
          CHECK(sliced.section_turn[j][0] == Approx(turn).epsilon(1e-12));
        }
      REQUIRE(mine.size() == plane.size());
      for (std::size_t j = 0; j < plane.size(); ++j) {
        CHECK(mine[j]->tooth_a == plane[j].tooth_a);
        CHECK(mine[j]->tooth_b == plane[j].tooth_b);
        CHECK(std::abs(mine[j]->overlap - plane[j].overlap) < 1e-12);
      }
    }
  }
}
