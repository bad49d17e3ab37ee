// Warnings from results (transmission::QuasiStaticWarnings, MeshStiffnessWarnings) on results made
// up here, whose values are known: a negative share, a transmission error past the small-rotation
// bound, a contact force twice the local term's validity limit (closed form L = h: F = h² π b E* /
// (4 R_eq)).
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/transmission/validity.hpp"
#include "local_term_fixtures.hpp"
#include "stage_fixtures.hpp"

using Catch::Matchers::Contains;
using namespace epicycle;

namespace {

transmission::PositionResult Converged(const std::vector<double>& lsr) {
  transmission::PositionResult r;
  r.converged = true;
  r.load_sharing = lsr;
  r.solution.force = Eigen::VectorXd::Zero(0);
  return r;
}

}  // namespace

TEST_CASE("result warnings: jammed planet, large rotation, load past the local term",
          "[unit][transmission]") {
  const auto scene = test::PaperScene();
  const geometry::Stage stage(scene.stage);
  // Within validity: no warning.
  CHECK(transmission::QuasiStaticWarnings(stage, {Converged({0.3, 0.3, 0.4})}).empty());

  // Planet 2 jammed at one position; the failed position is not looked at.
  auto jammed = Converged({0.7, -0.2, 0.5});
  auto failed = Converged({0.0, -5.0, 0.0});
  failed.converged = false;
  auto w = transmission::QuasiStaticWarnings(stage, {jammed, failed});
  REQUIRE(w.size() == 1);
  CHECK_THAT(w[0], Contains("planet 2: load-sharing ratio LSR = -0.2 < 0") &&
                       Contains("(1 position(s))") && Contains("jammed"));

  // The bound: 0.1 m / r_b,sun = 0.1 · 4.23 mm / (4.23·16/2 · cos 25° mm) = 0.1/(8 cos 25°) rad.
  const double bound = 0.1 / (8.0 * std::cos(25.0 * geometry::kPi / 180.0));
  auto small = Converged({0.3, 0.3, 0.4}), large = small;
  small.transmission_error = 0.99 * bound;
  large.transmission_error = -1.01 * bound;
  CHECK(transmission::QuasiStaticWarnings(stage, {small}).empty());
  w = transmission::QuasiStaticWarnings(stage, {large});
  REQUIRE(w.size() == 1);
  CHECK_THAT(w[0], Contains("transmission error") && Contains("a tenth of the module"));

  // One contact at twice its validity limit (docs in local_term_fixtures.hpp).
  const test::LocalTermWithLimit t = test::SteelLocalTerm();
  auto loaded = Converged({0.3, 0.3, 0.4});
  loaded.problem.data.local = {t.parameters, t.parameters};
  loaded.solution.force = Eigen::Vector2d(0.5 * t.limit_force, 2.0 * t.limit_force);
  w = transmission::QuasiStaticWarnings(stage, {loaded});
  REQUIRE(w.size() == 1);
  CHECK_THAT(
      w[0], Contains(" is 2 times the local term's validity limit") && Contains("on 1 contact(s)"));
}

TEST_CASE("mesh-stiffness result warnings: large rotation, load past the local term",
          "[unit][transmission]") {
  const auto scene =
      transmission::ParseScene(test::SceneText("iso_pair_20_40.toml"), "iso_pair_20_40.toml");
  const auto setup = transmission::MakeMeshPair(scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  // The bound: 0.1 m / r_b1 = 0.1 · 4 mm / (4·20/2 · cos 20° mm) = 0.1/(10 cos 20°) rad.
  const double bound = 0.1 / (10.0 * std::cos(20.0 * geometry::kPi / 180.0));
  auto sample = [](double rotation, double ratio, bool converged) {
    transmission::MeshSample s;
    s.converged = converged;
    s.rotation = rotation;
    s.local_validity_ratio = ratio;
    return s;
  };
  transmission::MeshStiffnessResult r;
  // Within validity (and a failed sample far outside, which is not looked at): no warning.
  r.samples = {sample(0.99 * bound, 0.99, true), sample(-5.0 * bound, 7.0, false)};
  CHECK(transmission::MeshStiffnessWarnings(pair, r).empty());

  r.samples.push_back(sample(-1.01 * bound, 0.5, true));
  r.samples.push_back(sample(0.5 * bound, 3.0, true));
  r.samples.push_back(sample(0.5 * bound, 1.5, true));
  const auto w = transmission::MeshStiffnessWarnings(pair, r);
  REQUIRE(w.size() == 2);
  CHECK_THAT(w[0], Contains("transmission error") && Contains("at 1 position(s)") &&
                       Contains("a tenth of the module along gear 1's line of action"));
  CHECK_THAT(w[1], Contains("contact force up to 3 times the local term's validity limit") &&
                       Contains("on 2 position(s)"));
}

// The sun out of contact with every planet at once (LSR_i = 0 for all i: no sun-mesh torque) is
// named with the count and the first carrier angle; one unloaded planet among loaded ones is a
// legitimate state (a pin error larger than the deflections) and says nothing.
TEST_CASE("result warnings: the sun touching no planet (rattle)", "[unit][transmission]") {
  const auto scene = test::PaperScene();
  const geometry::Stage stage(scene.stage);
  CHECK(transmission::QuasiStaticWarnings(stage, {Converged({0.5, 0.0, 0.5})}).empty());
  auto a = Converged({0.0, 0.0, 0.0}), b = a, c = Converged({0.3, 0.3, 0.4});
  a.carrier_angle = 10.0 * geometry::kPi / 180.0;
  b.carrier_angle = 20.0 * geometry::kPi / 180.0;
  const auto w = transmission::QuasiStaticWarnings(stage, {c, a, b});
  REQUIRE(w.size() == 1);
  CHECK_THAT(w[0], Contains("the sun touches no planet at 2 position(s)") &&
                       Contains("first at carrier 10 deg") && Contains("rattle"));
}
