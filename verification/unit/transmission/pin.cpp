// A planet's pin (pin.hpp; docs/model.md §10, "The planet's pin"): the rotation compliances of a
// straddle and a cantilever pin against an Euler–Bernoulli finite-element beam (cubic Hermite
// elements, exact for point loads at nodes: an independent solve of the same beam equation), the
// tilt's direction against the rigid rotation of the planet's axis by the moment's rotation
// vector, and the scene's [[face_width.pin]] keys refused with the key, value and rule.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/transmission/pin.hpp"
#include "epicycle/transmission/scene.hpp"
#include "stage_fixtures.hpp"
#include "thrown_message.hpp"

using namespace epicycle;
using transmission::PinCompliances;
using transmission::PinMounting;
using transmission::PinSpec;

namespace {

// An Euler–Bernoulli beam of `elements` equal cubic Hermite elements over [0, length] with
// bending stiffness EI; unknowns (w, θ) per node; `clamped` nodes held in w and θ. Returns the
// rotation θ at node `at` under a force P and a moment M applied there. Hermite elements
// reproduce the exact solution at the nodes for nodal loads (the solution is cubic between
// them), so the result is the beam table's to round-off.
double BeamRotation(double length, double ei, int elements, const std::vector<int>& clamped,
                    int at, double force, double moment) {
  const int nodes = elements + 1, n = 2 * nodes;
  const double h = length / elements;
  Eigen::Matrix4d k;
  k << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h, 6 * h,
      2 * h * h, -6 * h, 4 * h * h;
  k *= ei / (h * h * h);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int e = 0; e < elements; ++e) a.block(2 * e, 2 * e, 4, 4) += k;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  f(2 * at) = force;
  f(2 * at + 1) = moment;
  for (int c : clamped) {
    for (int d : {2 * c, 2 * c + 1}) {
      a.row(d).setZero();
      a.col(d).setZero();
      a(d, d) = 1;
      f(d) = 0;
    }
  }
  const Eigen::VectorXd u = a.fullPivLu().solve(f);
  return u(2 * at + 1);
}

PinSpec Pin(PinMounting mounting, double length) {
  PinSpec p;
  p.mounting = mounting;
  p.diameter = 30e-3;
  p.bore = 10e-3;
  p.length = length;
  p.youngs_modulus = 207e9;
  p.where = "test pin";
  return p;
}

}  // namespace

TEST_CASE("pin: the straddle and cantilever compliances are the Euler-Bernoulli beam's",
          "[unit][transmission][pin]") {
  const double ei = 207e9 * std::numbers::pi * (std::pow(30e-3, 4) - std::pow(10e-3, 4)) / 64;
  CHECK(transmission::PinBendingStiffness(207e9, 30e-3, 10e-3) == Approx(ei).epsilon(1e-15));
  // Round-off of a 2- or 8-unknown solve: 1e-12 relative.
  const double tol = 1e-12;
  SECTION("straddle: clamped in both plates, the planet at mid-span") {
    const double span = 45e-3;
    const transmission::PinCompliance c = PinCompliances(Pin(PinMounting::kStraddle, span));
    // Clamped at nodes 0 and 4 of four elements, loaded at node 2 (mid-span).
    CHECK(c.moment == Approx(BeamRotation(span, ei, 4, {0, 4}, 2, 0, 1)).epsilon(tol));
    // A force at mid-span bows the pin symmetrically: no rotation there.
    CHECK(std::abs(BeamRotation(span, ei, 4, {0, 4}, 2, 1, 0)) < tol * c.moment * span);
    CHECK(c.force == 0);
  }
  SECTION("cantilever: clamped in one plate, the bearing centre at the distance a") {
    const double a = 20e-3;
    PinSpec p = Pin(PinMounting::kCantilever, a);
    p.clamped_side = -1;
    const transmission::PinCompliance c = PinCompliances(p);
    CHECK(c.moment == Approx(BeamRotation(a, ei, 3, {0}, 3, 0, 1)).epsilon(tol));
    CHECK(c.force == Approx(BeamRotation(a, ei, 3, {0}, 3, 1, 0)).epsilon(tol));
    // Clamped at −z the free end points to +z: a force along +x turns the axis towards +x at +z.
    CHECK(c.side == 1);
    p.clamped_side = 1;
    CHECK(PinCompliances(p).side == -1);
  }
  SECTION("a given tilting stiffness; +inf is a rigid pin") {
    PinSpec p;
    p.tilting_stiffness = 2.5e6;
    CHECK(PinCompliances(p).moment == Approx(1 / 2.5e6).epsilon(1e-15));
    p.tilting_stiffness = std::numeric_limits<double>::infinity();
    CHECK(PinCompliances(p).rigid());
    CHECK_FALSE(transmission::PinModel({p}, 3).active());
  }
}

TEST_CASE("pin: the tilt is the axis turned by the moment's rotation vector, and the force's "
          "slope of a cantilever lies along the force",
          "[unit][transmission][pin]") {
  PinSpec p;
  p.tilting_stiffness = 1e6;
  const transmission::PinModel model({p}, 3);
  transmission::PinLoad load;
  load.moment = Eigen::Vector2d(120, -75);
  // The planet turns rigidly by φ = M/k; its axis ẑ goes to ẑ + φ × ẑ.
  const Eigen::Vector3d phi(load.moment.x() / 1e6, load.moment.y() / 1e6, 0);
  const Eigen::Vector3d axis = phi.cross(Eigen::Vector3d::UnitZ());
  const Eigen::Vector2d t = model.Tilt(1, load);
  CHECK(t.x() == Approx(axis.x()).epsilon(1e-15));
  CHECK(t.y() == Approx(axis.y()).epsilon(1e-15));

  PinSpec c = Pin(PinMounting::kCantilever, 20e-3);
  c.planet = 2;  // planet 3 only; the others rigid
  const transmission::PinModel cantilever({c}, 3);
  CHECK(cantilever.compliance(0).rigid());
  transmission::PinLoad push;
  push.force = Eigen::Vector2d(0, 5000);
  const Eigen::Vector2d s = cantilever.Tilt(2, push);
  CHECK(s.x() == 0);
  CHECK(s.y() == Approx(5000 * PinCompliances(c).force).epsilon(1e-15));
}

TEST_CASE("pin: the scene's [[face_width.pin]] keys are read with their units and bad values "
          "named",
          "[unit][transmission][pin]") {
  const std::string base = test::SceneText("paper_stage.toml") + "\n[face_width]\nslices = 10\n";
  auto parse = [&](const std::string& pin) {
    return transmission::ParseScene(base + "[[face_width.pin]]\n" + pin, "pin.toml");
  };
  const transmission::Scene s =
      parse("mounting = \"cantilever\"\ndiameter_mm = 30\nlength_mm = 20\nclamped_side = \"+z\"\n");
  REQUIRE(s.face_width.pins.size() == 1);
  const PinSpec& p = s.face_width.pins[0];
  CHECK(p.planet == -1);
  CHECK(p.mounting == PinMounting::kCantilever);
  CHECK(p.diameter == Approx(30e-3));
  CHECK(p.length == Approx(20e-3));
  CHECK(p.youngs_modulus == Approx(207e9));  // the scene's [material]
  CHECK(p.clamped_side == 1);

  auto message = [&](const std::string& pin) { return test::ThrownMessage([&] { parse(pin); }); };
  const std::string both = message("tilting_stiffness_Nm_per_rad = 1e6\ndiameter_mm = 30\n");
  CHECK_THAT(both, Catch::Contains("diameter_mm") && Catch::Contains("mounting = \"stiffness\""));
  const std::string bore = message(
      "mounting = \"straddle\"\ndiameter_mm = 30\nbore_mm = 30\nlength_mm = 45\n");
  CHECK_THAT(bore, Catch::Contains("bore_mm = 30") && Catch::Contains("below its diameter"));
  const std::string shortspan =
      message("mounting = \"straddle\"\ndiameter_mm = 30\nlength_mm = 10\n");
  CHECK_THAT(shortspan, Catch::Contains("length_mm = 10") && Catch::Contains("face width"));
  const std::string negative = message("tilting_stiffness_Nm_per_rad = -5\n");
  CHECK_THAT(negative, Catch::Contains("tilting_stiffness_Nm_per_rad = -5"));
  const std::string twice =
      message("tilting_stiffness_Nm_per_rad = 1e6\n[[face_width.pin]]\n"
              "tilting_stiffness_Nm_per_rad = 2e6\n");
  CHECK_THAT(twice, Catch::Contains("already given"));
  const std::string one_slice = test::ThrownMessage([&] {
    transmission::ParseScene(test::SceneText("paper_stage.toml") +
                                 "\n[face_width]\nslices = 1\n[[face_width.pin]]\n"
                                 "tilting_stiffness_Nm_per_rad = 1e6\n",
                             "pin.toml");
  });
  CHECK_THAT(one_slice, Catch::Contains("slices = 1") && Catch::Contains("slices >= 2"));
}
