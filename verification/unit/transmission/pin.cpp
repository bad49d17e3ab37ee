// A planet's pin (pin.hpp; docs/model.md §10, "The planet's pin"): the rotation compliances of a
// straddle and a cantilever pin against an Euler–Bernoulli finite-element beam (cubic Hermite
// elements, exact for point loads at nodes: an independent solve of the same beam equation), the
// tilt's direction against the rigid rotation of the planet's axis by the moment's rotation
// vector, the tilt's feedback on one mesh of uniform stiffness in uncoupled slices against its
// closed form (K_Hβ = 1 + c F_β b/(2F) with the settled tilt as F_β), and the scene's
// [[face_width.pin]] keys refused with the key, value and rule.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/face_width.hpp"
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

TEST_CASE("pin feedback on one mesh of uniform stiffness in uncoupled slices: the settled tilt and "
          "K_Hbeta = 1 + c F_beta b/(2F) in closed form",
          "[unit][transmission][pin]") {
  // One mesh pushes the planet along +x with F = 6500 N over a face b = 25 mm of S = 20 uncoupled
  // slices of stiffness c = 20 N/(mm·µm) per unit width; an external moment M0 = 163 N·m about +y
  // (a helical planet's axial forces) and the slices' forces load a pin of k_tilt = 2.926e6
  // N·m/rad. The pin turns the axis by t_x = c_M M_y (pin.hpp); the section at z moves by z t_x
  // along +x, away from the mate: the gap of slice s grows by z_s t_x. In full contact the line
  // load is w(z) = F/b − c t z, whose moment Σ z_s F_s = −c t Σ z_s² Δz = −c t I with
  // I = b³ (1 − 1/S²)/12 (the slices' centres), so the fixed point t = c_M (M0 − c t I) is
  //   t = c_M M0 / (1 + c_M c I),
  // and K_Hβ = max w/mean = 1 + c t (b − Δz)/2 · b/F = 1 + c F_β b (1 − 1/S)/(2F), F_β = t b.
  const int S = 20;
  const double b = 25e-3, c = 2e10, force = 6500, m0 = 163, k = 2.926e6;
  PinSpec spec;
  spec.tilting_stiffness = k;
  const transmission::PinModel pins({spec}, 1);
  const std::vector<double> z = transmission::SliceCentres(S, b);
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  Eigen::VectorXd f;
  int iterations = 0;
  for (double change = 1; change > 1e-15 && iterations < 100; ++iterations) {
    solvers::ContactProblemData d;
    d.compliance = Eigen::MatrixXd::Identity(S, S) * (S / (c * b));  // strips: C0 S I
    d.overlap.resize(S);
    for (int s = 0; s < S; ++s) d.overlap(s) = -z[static_cast<std::size_t>(s)] * t.x();
    d.equality_matrix = Eigen::MatrixXd::Ones(1, S);  // Σ F_s = F, λ the approach
    d.equality_rhs = Eigen::VectorXd::Constant(1, force);
    const solvers::ContactProblem problem(d);
    solvers::ContactSolution solution;
    const solvers::ContactReport report =
        solver->Solve(problem, solvers::ContactOptions{}, &solution);
    REQUIRE(report.status == solvers::ContactStatus::kConverged);
    f = solution.force;
    transmission::PinLoad load;
    load.force = Eigen::Vector2d(force, 0);
    load.moment = Eigen::Vector2d(0, m0);
    for (int s = 0; s < S; ++s) load.moment.y() += z[static_cast<std::size_t>(s)] * f(s);
    const Eigen::Vector2d next = pins.Tilt(0, load);
    change = (next - t).norm() / next.norm();
    t = next;
  }
  INFO(iterations << " iterations");
  const double inertia = b * b * b * (1 - 1.0 / (S * S)) / 12;
  const double settled = (m0 / k) / (1 + c * inertia / k);
  // The fixed point contracts by c I/k ≈ 0.02 per step: 100 steps settle it to round-off; the
  // contact solve's tolerance (1e-10 relative) bounds the forces' error: 1e-9 relative.
  CHECK(t.x() == Approx(settled).epsilon(1e-9));
  CHECK(t.y() == 0);
  const double k_hbeta = f.maxCoeff() / (force / S);
  const double closed = 1 + c * (settled * b) * b * (1 - 1.0 / S) / (2 * force);
  CHECK(k_hbeta == Approx(closed).epsilon(1e-9));
  // The load gathers at −z: the end the tilt moves towards the mate.
  CHECK(f(0) == f.maxCoeff());
  // Without the feedback (a rigid pin) the face would carry uniformly: K_Hβ = 1.
  CHECK(closed > 1.01);
}
