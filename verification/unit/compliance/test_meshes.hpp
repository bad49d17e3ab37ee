// Regions and meshes shared by the compliance tests: a distorted Q8 patch, a cantilever strip,
// a quarter of a thick cylinder, and a half-disc around a surface point load.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "epicycle/compliance/mesher.hpp"

namespace epicycle::compliance::testing {

/// Prints a measured figure (for docs/compliance.md) when EPICYCLE_FIGURES is set in the
/// environment; silent otherwise.
inline void Figure(const std::string& text) {
  if (std::getenv("EPICYCLE_FIGURES") != nullptr) std::printf("FIGURE %s\n", text.c_str());
}
inline std::string Sci(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3e", x);
  return buf;
}

/// The distorted five-element patch of MacNeal and Harder (1985) on [0, 0.24] × [0, 0.12] m, as
/// Q8: the mid-side nodes of the four inner sides are pushed off their chords by `bulge` × length
/// (curved interior sides). Node set "boundary" holds the outer nodes, edge set "outer" the four
/// outer sides; node "interior" the others.
inline Mesh DistortedPatch(double bulge) {
  Mesh m;
  const std::array<Eigen::Vector2d, 8> c = {
      Eigen::Vector2d(0.0, 0.0),   Eigen::Vector2d(0.24, 0.0),  Eigen::Vector2d(0.24, 0.12),
      Eigen::Vector2d(0.0, 0.12),  Eigen::Vector2d(0.04, 0.02), Eigen::Vector2d(0.18, 0.03),
      Eigen::Vector2d(0.16, 0.08), Eigen::Vector2d(0.08, 0.08)};
  for (const auto& x : c) m.nodes.push_back(x);
  std::map<std::pair<int, int>, int> mid;
  auto side = [&](int a, int b, bool curved) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const Eigen::Vector2d t = c[b] - c[a];
    Eigen::Vector2d x = 0.5 * (c[a] + c[b]);
    if (curved) x += bulge * Eigen::Vector2d(-t.y(), t.x());
    m.nodes.push_back(x);
    mid[key] = m.num_nodes() - 1;
    return m.num_nodes() - 1;
  };
  // Corners counter-clockwise; sides between two inner corners (4..7) are curved.
  const std::array<std::array<int, 4>, 5> quads = {
      {{0, 1, 5, 4}, {1, 2, 6, 5}, {7, 6, 2, 3}, {0, 4, 7, 3}, {4, 5, 6, 7}}};
  for (const auto& q : quads) {
    std::array<int, 8> el{};
    for (int k = 0; k < 4; ++k) el[k] = q[k];
    for (int k = 0; k < 4; ++k) {
      const int a = q[k], b = q[(k + 1) % 4];
      el[4 + k] = side(a, b, a >= 4 && b >= 4);
    }
    m.elements.push_back(el);
  }
  // Outer sides: element 0 side 0 (0→1), element 1 side 0 (1→2), element 2 side 2 (2→3),
  // element 3 side 3 (3→0).
  m.edge_sets["outer"] = {
      BoundaryEdge{{0, m.elements[0][4], 1}, 0}, BoundaryEdge{{1, m.elements[1][4], 2}, 1},
      BoundaryEdge{{2, m.elements[2][6], 3}, 2}, BoundaryEdge{{3, m.elements[3][7], 0}, 3}};
  std::vector<int> boundary, interior;
  for (const auto& e : m.edge_sets["outer"]) {
    for (int v : e.nodes) {
      if (std::find(boundary.begin(), boundary.end(), v) == boundary.end()) boundary.push_back(v);
    }
  }
  for (int v = 0; v < m.num_nodes(); ++v) {
    if (std::find(boundary.begin(), boundary.end(), v) == boundary.end()) interior.push_back(v);
  }
  m.node_sets["boundary"] = boundary;
  m.node_sets["interior"] = interior;
  return m;
}

/// A rectangular strip [0, length] × [−height/2, height/2] as one patch: sides "bottom", "tip"
/// (x = length), "top", "root" (x = 0).
inline Region CantileverRegion(double length, double height, int nx, int ny) {
  const Eigen::Vector2d p00(0.0, -height / 2), p10(length, -height / 2), p11(length, height / 2),
      p01(0.0, height / 2);
  Patch p;
  p.name = "beam";
  p.sides = {StraightLine(p00, p10), StraightLine(p10, p11), StraightLine(p01, p11),
             StraightLine(p00, p01)};
  p.side_names = {"bottom", "tip", "top", "root"};
  p.u = Distribution::Uniform(nx);
  p.v = Distribution::Uniform(ny);
  return Region{{p}};
}

/// Quarter of the ring a ≤ r ≤ b, 0 ≤ θ ≤ π/2, as one patch: u radial, v angular. Sides "x_axis"
/// (θ = 0), "outer", "y_axis" (θ = π/2), "inner".
inline Region QuarterRingRegion(double a, double b, int nr, int nt) {
  Patch p;
  p.name = "ring";
  p.sides = {
      StraightLine({a, 0.0}, {b, 0.0}), CircularArc({0.0, 0.0}, b, 0.0, std::numbers::pi / 2),
      StraightLine({0.0, a}, {0.0, b}), CircularArc({0.0, 0.0}, a, 0.0, std::numbers::pi / 2)};
  p.side_names = {"x_axis", "outer", "y_axis", "inner"};
  p.u = Distribution::Uniform(nr);
  p.v = Distribution::Uniform(nt);
  return Region{{p}};
}

/// Mirror image x → −x of a patch (reverses its orientation; names kept).
inline Patch Mirrored(const Patch& p) {
  Patch q = p;
  for (int s = 0; s < 4; ++s) {
    q.sides[s] = [c = p.sides[s]](double t) -> Eigen::Vector2d {
      const Eigen::Vector2d x = c(t);
      return {-x.x(), x.y()};
    };
  }
  q.name = p.name.empty() ? "" : p.name + "_mirror";
  return q;
}

/// The half-disc y ≤ 0, r ≤ radius around a surface point at the origin, as six patches (an
/// O-grid): two square halves [−s, s] × [−s, 0] graded toward the origin in both directions, and
/// around them four ring patches reaching the arc, graded toward the square. Node/edge sets:
/// "surface" (y = 0), "axis" (x = 0 inside the square), "axis_deep" (x = 0 below it),
/// "arc" (r = radius). `n` elements per square half side and `n` radially; `grading` is the
/// size ratio of the largest to the smallest element along each graded direction.
inline Region HalfDiscRegion(double radius, double s, int n, double grading) {
  const double d = radius / std::sqrt(2.0);
  const Distribution toward0 = Distribution::Graded(n, grading);        // fine at t = 0
  const Distribution toward1 = Distribution::Graded(n, 1.0 / grading);  // fine at t = 1
  Patch square;  // x ∈ [0, s], y ∈ [−s, 0]
  square.name = "square";
  square.sides = {StraightLine({0.0, -s}, {s, -s}), StraightLine({s, -s}, {s, 0.0}),
                  StraightLine({0.0, 0.0}, {s, 0.0}), StraightLine({0.0, -s}, {0.0, 0.0})};
  square.side_names = {"", "", "surface", "axis"};
  square.u = toward0;
  square.v = toward1;
  Patch side_ring;  // from the square's side x = s to the arc between −45° and 0°
  side_ring.name = "side_ring";
  side_ring.sides = {StraightLine({s, -s}, {d, -d}),
                     CircularArc({0.0, 0.0}, radius, -std::numbers::pi / 4, 0.0),
                     StraightLine({s, 0.0}, {radius, 0.0}), StraightLine({s, -s}, {s, 0.0})};
  side_ring.side_names = {"", "arc", "surface", ""};
  side_ring.u = toward0;
  side_ring.v = toward1;
  Patch bottom_ring;  // from the arc between −90° and −45° (v = 0) to the square's bottom (v = 1)
  bottom_ring.name = "bottom_ring";
  bottom_ring.sides = {
      CircularArc({0.0, 0.0}, radius, -std::numbers::pi / 2, -std::numbers::pi / 4),
      StraightLine({d, -d}, {s, -s}), StraightLine({0.0, -s}, {s, -s}),
      StraightLine({0.0, -radius}, {0.0, -s})};
  bottom_ring.side_names = {"arc", "", "", "axis_deep"};
  bottom_ring.u = toward0;
  bottom_ring.v = toward1;
  return Region{{square, side_ring, bottom_ring, Mirrored(square), Mirrored(side_ring),
                 Mirrored(bottom_ring)}};
}

/// Two curved, graded patches sharing a wavy side (outer sides curved too): node set "outer" holds
/// the region's boundary. Used by the patch tests of both meshers.
inline Region TwoCurvedPatches() {
  auto wave = [](double amp) {
    return [amp](double t) -> Eigen::Vector2d {
      return {0.05 + amp * std::sin(std::numbers::pi * t), 0.04 * t};
    };
  };
  Patch left;
  left.sides = {StraightLine({0.0, 0.0}, {0.05, 0.0}), wave(0.006),
                Reversed(CircularArc({0.025, -0.06}, std::hypot(0.025, 0.1), std::atan2(0.1, 0.025),
                                     std::atan2(0.1, -0.025))),
                StraightLine({0.0, 0.0}, {0.0, 0.04})};
  left.side_names = {"outer", "", "outer", "outer"};
  left.u = Distribution::Geometric(4, 1.5);
  left.v = Distribution::Geometric(3, 0.6);
  Patch right;
  right.sides = {StraightLine({0.05, 0.0}, {0.09, 0.0}), StraightLine({0.09, 0.0}, {0.09, 0.04}),
                 StraightLine({0.05, 0.04}, {0.09, 0.04}), wave(0.006)};
  right.side_names = {"outer", "outer", "outer", ""};
  right.u = Distribution::Uniform(3);
  right.v = Distribution::Geometric(3, 0.6);
  return Region{{left, right}};
}

}  // namespace epicycle::compliance::testing
