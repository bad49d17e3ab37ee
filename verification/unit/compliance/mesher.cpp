// Mapped (Coons) mesher: nodes on the boundary curves, grading, conforming joins, orientation,
// named sets, and clear messages for bad regions.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "epicycle/compliance/mesher.hpp"
#include "test_meshes.hpp"

using namespace epicycle::compliance;
using Catch::Matchers::Contains;

namespace {

// Area ∫∫ det J dξdη of the whole mesh (3×3 Gauss per element).
double MeshArea(const Mesh& m) {
  const GaussRule g = GaussLegendre(5);
  double area = 0.0;
  for (int e = 0; e < m.num_elements(); ++e) {
    const Q8Coordinates x = m.ElementCoordinates(e);
    for (int i = 0; i < g.size; ++i) {
      for (int k = 0; k < g.size; ++k) {
        double det = 0.0;
        Q8StrainDisplacement(x, g.points[i], g.points[k], &det);
        area += g.weights[i] * g.weights[k] * det;
      }
    }
  }
  return area;
}

int Q8GridNodes(int nu, int nv) { return (2 * nu + 1) * (2 * nv + 1) - nu * nv; }

// Area between the origin and the quadratic (mid-angle node) interpolant of a circular arc of
// radius r and angle 2h: by Green's theorem on p(θ) = r(1 + θ²(cos h − 1)/h², θ sin h/h),
// A = r² sin h (4 − cos h)/3  (= r² h (1 − h⁴/30 + …): the quadratic arc's area defect).
double QuadraticArcSectorArea(double r, double h) {
  return r * r * std::sin(h) * (4.0 - std::cos(h)) / 3.0;
}

}  // namespace

TEST_CASE("Mapped mesher: quarter ring nodes lie on the arcs, Coons gives polar coordinates",
          "[unit]") {
  const double a = 0.05, b = 0.1;
  const Mesh m = MappedMesher().BuildMesh(testing::QuarterRingRegion(a, b, 3, 7));
  CHECK(m.num_elements() == 21);
  CHECK(m.num_nodes() == Q8GridNodes(3, 7));
  for (int v : m.NodeSet("inner")) CHECK(m.nodes[v].norm() == Approx(a).epsilon(1e-15));
  for (int v : m.NodeSet("outer")) CHECK(m.nodes[v].norm() == Approx(b).epsilon(1e-15));
  CHECK(m.NodeSet("inner").size() == 15u);
  // For a ring sector the Coons map is exactly r = a + (b−a)u, θ = (π/2)v: radii on the grid.
  for (const auto& x : m.nodes) {
    const double u = (x.norm() - a) / (b - a) * 6.0;  // in half-element steps
    CHECK(std::abs(u - std::round(u)) < 1e-12);
  }
  // Edge normals of the counter-clockwise edge sets point out of the body.
  for (int k = 0; k < static_cast<int>(m.EdgeSet("outer").size()); ++k) {
    const EdgePoint p{k, 0.3};
    CHECK(m.EdgeNormal("outer", p).dot(m.EdgePosition("outer", p).normalized()) ==
          Approx(1.0).epsilon(1e-3));
    CHECK(m.EdgeNormal("inner", p).dot(m.EdgePosition("inner", p).normalized()) ==
          Approx(-1.0).epsilon(1e-3));
  }
  // The area: 7 quadratic arc segments of angle π/14 on each arc (no gap, no overlap).
  const double h = std::numbers::pi / 28;
  CHECK(MeshArea(m) ==
        Approx(7 * (QuadraticArcSectorArea(b, h) - QuadraticArcSectorArea(a, h))).epsilon(1e-13));
}

TEST_CASE("Mapped mesher: mid-side nodes lie on curved sides, geometric grading", "[unit]") {
  const double amp = 0.01;
  Patch p;
  auto wave = [amp](double t) -> Eigen::Vector2d {
    return {0.1 + amp * std::sin(std::numbers::pi * t), 0.05 * t};
  };
  p.sides = {StraightLine({0.0, 0.0}, {0.1, 0.0}), wave, StraightLine({0.0, 0.05}, {0.1, 0.05}),
             StraightLine({0.0, 0.0}, {0.0, 0.05})};
  p.side_names = {"bottom", "wavy", "", ""};
  p.u = Distribution::Geometric(6, 0.7);
  p.v = Distribution::Uniform(5);
  const Mesh m = MappedMesher().BuildMesh(Region{{p}});
  // Every node of the wavy side, corner or mid-side, satisfies the curve's equation.
  REQUIRE(m.NodeSet("wavy").size() == 11u);
  for (int v : m.NodeSet("wavy")) {
    const Eigen::Vector2d x = m.nodes[v];
    CHECK(x.x() == Approx(0.1 + amp * std::sin(std::numbers::pi * x.y() / 0.05)).epsilon(1e-14));
  }
  // Along the straight bottom side: corner spacings in ratio 0.7, mid-side nodes at midpoints.
  const auto& bottom = m.NodeSet("bottom");
  REQUIRE(bottom.size() == 13u);
  for (int k = 0; k + 2 < 12; k += 2) {
    const double h0 = m.nodes[bottom[k + 2]].x() - m.nodes[bottom[k]].x();
    const double h1 = m.nodes[bottom[k + 4 > 12 ? 12 : k + 4]].x() - m.nodes[bottom[k + 2]].x();
    if (k + 4 <= 12) CHECK(h1 / h0 == Approx(0.7).epsilon(1e-12));
    CHECK(m.nodes[bottom[k + 1]].x() ==
          Approx(0.5 * (m.nodes[bottom[k]].x() + m.nodes[bottom[k + 2]].x())).epsilon(1e-14));
  }
  CHECK(m.nodes[bottom.back()].x() == Approx(0.1).epsilon(1e-15));
  const auto t = Distribution::Graded(5, 16.0).Parameters("test");
  CHECK((t[5] - t[4]) / (t[1] - t[0]) == Approx(16.0).epsilon(1e-12));
}

TEST_CASE("Mapped mesher: patches sharing a side join conformingly, in either direction",
          "[unit]") {
  const bool reversed = GENERATE(false, true);
  Patch a, b;
  a.name = "patch_a";
  a.sides = {StraightLine({0, 0}, {1, 0}), StraightLine({1, 0}, {1, 1}),
             StraightLine({0, 1}, {1, 1}), StraightLine({0, 0}, {0, 1})};
  a.u = Distribution::Uniform(3);
  a.v = Distribution::Geometric(4, 1.3);
  b.name = "patch_b";
  // b lies right of a; its left side is a's right side. Described either in the same direction,
  // or with b's v running downward (the shared side reversed, the distribution too).
  if (!reversed) {
    b.sides = {StraightLine({1, 0}, {2, 0.2}), StraightLine({2, 0.2}, {2, 1.1}),
               StraightLine({1, 1}, {2, 1.1}), StraightLine({1, 0}, {1, 1})};
    b.v = Distribution::Geometric(4, 1.3);
  } else {
    b.sides = {StraightLine({1, 1}, {2, 1.1}), StraightLine({2, 1.1}, {2, 0.2}),
               StraightLine({1, 0}, {2, 0.2}), StraightLine({1, 1}, {1, 0})};
    b.v = Distribution::Geometric(4, 1.0 / 1.3);
  }
  b.u = Distribution::Uniform(2);
  const Mesh m = MappedMesher().BuildMesh(Region{{a, b}});
  CHECK(m.num_nodes() == Q8GridNodes(3, 4) + Q8GridNodes(2, 4) - 9);
  CHECK(m.ElementSet("patch_a").size() == 12u);
  CHECK(m.ElementSet("patch_b").size() == 8u);
  // Every interior side is shared by exactly two elements: the area is the polygon's.
  CHECK(MeshArea(m) == Approx(1.0 + 0.5 * (1.0 + 0.9)).epsilon(1e-13));
}

TEST_CASE("Mapped mesher: the half-disc O-grid, including mirrored (clockwise) patches", "[unit]") {
  const double radius = 0.2;
  const Mesh m = MappedMesher().BuildMesh(testing::HalfDiscRegion(radius, 0.02, 6, 20.0));
  CHECK(m.num_elements() == 6 * 36);
  // 8 shared sides of 13 nodes; 3 points are shared by as many sides as patches.
  CHECK(m.num_nodes() == 6 * Q8GridNodes(6, 6) - 8 * 13 + 3);
  for (int k = 0; k < static_cast<int>(m.EdgeSet("arc").size()); ++k) {
    const EdgePoint p{k, -0.5};
    CHECK(m.EdgeNormal("arc", p).dot(m.EdgePosition("arc", p).normalized()) > 0.99);
  }
  for (int k = 0; k < static_cast<int>(m.EdgeSet("surface").size()); ++k) {
    CHECK(m.EdgeNormal("surface", {k, 0.2}).y() == Approx(1.0).epsilon(1e-14));
  }
  // Area: the sum over the (graded) quadratic arc segments; the surface line passes the origin.
  double area = 0.0;
  for (const BoundaryEdge& e : m.EdgeSet("arc")) {
    const Eigen::Vector2d p0 = m.nodes[e.nodes[0]], p2 = m.nodes[e.nodes[2]];
    const double angle = std::atan2(p0.x() * p2.y() - p0.y() * p2.x(), p0.dot(p2));
    area += QuadraticArcSectorArea(radius, angle / 2);
  }
  CHECK(MeshArea(m) == Approx(area).epsilon(1e-13));
  CHECK(area == Approx(std::numbers::pi * radius * radius / 2).epsilon(1e-4));
  const EdgePoint at = m.LocateOnEdgeSet("surface", {0.0123, 1e-4});
  CHECK((m.EdgePosition("surface", at) - Eigen::Vector2d(0.0123, 0.0)).norm() < 1e-15);
}

TEST_CASE("Mapped mesher: clear messages for bad regions", "[unit]") {
  Patch a;
  a.name = "flank";
  a.sides = {StraightLine({0, 0}, {1, 0}), StraightLine({1, 0}, {1, 1}),
             StraightLine({0, 1}, {1, 1}), StraightLine({0, 0}, {0, 1})};
  a.u = Distribution::Uniform(2);
  a.v = Distribution::Uniform(2);
  SECTION("corners that do not meet") {
    Patch bad = a;
    bad.sides[1] = StraightLine({1, 0.01}, {1, 1});
    CHECK_THROWS_WITH(MappedMesher().BuildMesh(Region{{bad}}),
                      Contains("patch 0 ('flank')") && Contains("corner (u, v) = (1, 0)") &&
                          Contains("right side"));
  }
  SECTION("non-conforming join") {
    Patch b = a;
    b.name = "rim";
    b.sides = {StraightLine({1, 0}, {2, 0}), StraightLine({2, 0}, {2, 1}),
               StraightLine({1, 1}, {2, 1}), StraightLine({1, 0}, {1, 1})};
    b.v = Distribution::Uniform(3);
    CHECK_THROWS_WITH(MappedMesher().BuildMesh(Region{{a, b}}),
                      Contains("non-conforming join") && Contains("same divisions"));
  }
  SECTION("folded patch gives an inverted element") {
    Patch bad = a;  // a bow-tie: the top side runs backwards
    bad.sides = {StraightLine({0, 0}, {1, 0}), StraightLine({1, 0}, {0.2, 1}),
                 StraightLine({0.8, 1}, {0.2, 1}), StraightLine({0, 0}, {0.8, 1})};
    CHECK_THROWS_WITH(
        MappedMesher().BuildMesh(Region{{bad}}),
        Contains("patch 0 ('flank')") && Contains("element") && Contains("Jacobian determinant"));
  }
  SECTION("bad distribution and options") {
    Patch bad = a;
    bad.u = Distribution::Uniform(0);
    CHECK_THROWS_WITH(MappedMesher().BuildMesh(Region{{bad}}),
                      Contains("patch 0 ('flank') u") && Contains("divisions = 0"));
    bad.u = Distribution{2, 1.0, {0.0, 0.7, 0.6, 1.0}};
    CHECK_THROWS_WITH(MappedMesher().BuildMesh(Region{{bad}}),
                      Contains("breaks[2] = 0.6") && Contains("strictly increasing"));
    CHECK_THROWS_WITH(MappedMesher(MappedMesherOptions{-1.0, 1e-9, true}),
                      Contains("merge_tolerance = -1"));
    CHECK_THROWS_WITH(MappedMesher().BuildMesh(Region{}), Contains("no patches"));
  }
  SECTION("a node set that does not exist") {
    a.side_names = {"hub", "", "", ""};
    const Mesh m = MappedMesher().BuildMesh(Region{{a}});
    CHECK_THROWS_WITH(m.NodeSet("rim"),
                      Contains("node set 'rim' does not exist") && Contains("'hub'"));
    CHECK_THROWS_WITH(m.EdgeSet("flank"), Contains("edge set 'flank' does not exist"));
  }
}
