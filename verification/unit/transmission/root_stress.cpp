// The root-stress read-outs (transmission/root_stress.hpp) on hand-made fillet stresses: a state's
// extremes per gear, and over states the extremes with where they occur and the largest range at
// one fillet point, a point a state did not compute counting as unloaded.
#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "fe_fixtures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using namespace epicycle::transmission;

namespace {

// A coarse table of the paper's sun with its fillet points (their arc lengths locate the spots).
const compliance::InfluenceTable& Table() {
  static const compliance::InfluenceTable table = [] {
    const Scene scene = test::PaperScene();
    compliance::InfluenceTableOptions o = test::CoarseTableOptions();
    o.fillet_stress = true;
    return compliance::InfluenceTable::Build(
        geometry::Gear(scene.stage.sun),
        compliance::ElasticMaterial{scene.material.youngs_modulus, scene.material.poisson_ratio,
                                    scene.stage.sun.face_width,
                                    compliance::PlaneAssumption::kPlaneStrain},
        o);
  }();
  return table;
}

// A fillet whose first values are `head`, the others 0 (its own block of values).
compliance::FilletStress Fillet(int body, int tooth, int side, std::vector<double> head) {
  const std::size_t m = Table().fillet_points().size();
  head.resize(m, 0.0);
  const std::shared_ptr<double[]> values = std::make_shared<double[]>(m);
  std::copy(head.begin(), head.end(), values.get());
  return {body, tooth, side, std::span<const double>(values.get(), m), &Table(), values};
}

}  // namespace

TEST_CASE("root stress read-outs of hand-made states", "[unit][transmission][stress]") {
  REQUIRE(Table().fillet_points().size() >= 3);
  const auto arc = [](int m) {
    return Table().fillet_points()[static_cast<std::size_t>(m)].arc_length;
  };
  // State A (x = 1): body 0 tooth 3 loaded on side 0, compressed on side 1; body 2 tooth 0.
  const std::vector<compliance::FilletStress> a = {Fillet(0, 3, 0, {1e6, 5e6, 2e6}),
                                                   Fillet(0, 3, 1, {-4e6, -1e6}),
                                                   Fillet(2, 0, 0, {0, 0, 3e6})};
  // State B (x = 2): body 0 tooth 3 compressed a little on side 0, tooth 4 loaded.
  const std::vector<compliance::FilletStress> b = {Fillet(0, 3, 0, {-2e6, 1e6}),
                                                   Fillet(0, 4, 0, {0, 7e6})};
  const std::vector<GearRootStress> sa = SummariseRootStress(a, 3);
  REQUIRE(sa.size() == 3);
  CHECK(sa[0].tension == 5e6);
  CHECK(sa[0].tension_at.tooth == 3);
  CHECK(sa[0].tension_at.side == 0);
  CHECK(sa[0].tension_at.arc_length == arc(1));
  CHECK(sa[0].compression == -4e6);
  CHECK(sa[0].compression_at.side == 1);
  CHECK(sa[1].tension == 0.0);  // no fillet of body 1: nothing
  CHECK(sa[1].compression == 0.0);
  CHECK(sa[2].tension == 3e6);
  CHECK(sa[2].tension_at.arc_length == arc(2));

  RootStressTracker tracker({"a", "b", "c"});
  CHECK(tracker.Result().empty());
  tracker.Add({}, 0.5);  // a state without fillets adds nothing
  CHECK(tracker.Result().empty());
  tracker.Add(a, 1.0);
  tracker.Add(b, 2.0);
  const std::vector<RootStressSummary> r = tracker.Result();
  REQUIRE(r.size() == 3);
  CHECK(r[1].gear == "b");  // each body named by the tracker's list
  // Body 0: the largest tension 7 MPa in state B on tooth 4, the compression −4 MPa in state A.
  CHECK(r[0].extremes.tension == 7e6);
  CHECK(r[0].tension_x == 2.0);
  CHECK(r[0].extremes.tension_at.tooth == 4);
  CHECK(r[0].extremes.compression == -4e6);
  CHECK(r[0].compression_x == 1.0);
  // Ranges at one point: tooth 3 side 0 point 0 sees 1 and −2 (3 MPa), point 1 sees 5 and 1 with
  // 0 the floor (5 MPa); tooth 3 side 1 point 0 sees −4 (4 MPa); tooth 4 side 0 point 1 sees 7 in
  // B and, not computed in A, 0 there: 7 MPa, the largest.
  CHECK(r[0].range.range == 7e6);
  CHECK(r[0].range.at.tooth == 4);
  CHECK(r[0].range.at.arc_length == arc(1));
  CHECK(r[0].range.max == 7e6);
  CHECK(r[0].range.min == 0.0);
  CHECK(r[1].range.range == 0.0);
  CHECK(r[2].range.range == 3e6);
  CHECK(r[2].tension_x == 1.0);
}
