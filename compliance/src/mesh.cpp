#include "epicycle/compliance/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace epicycle::compliance {
namespace {

// The parameter ξ ∈ [−1, 1] of the point of a quadratic edge (nodes x) closest to p: the chord
// projection, then Newton on f(ξ) = (x(ξ) − p)·x'(ξ) = 0, clamped to [−1, 1].
double ProjectOnQuadraticEdge(const Eigen::Matrix<double, 2, 3>& x, const Eigen::Vector2d& p) {
  const Eigen::Vector2d chord = x.col(2) - x.col(0);
  double xi = std::clamp(2.0 * (p - x.col(0)).dot(chord) / chord.squaredNorm() - 1.0, -1.0, 1.0);
  const Eigen::Vector2d tt = x.col(0) - 2.0 * x.col(1) + x.col(2);  // x''(ξ)
  for (int it = 0; it < 30; ++it) {
    const Eigen::Vector2d r = x * EdgeShapeFunctions(xi) - p;
    const Eigen::Vector2d t = x * EdgeShapeDerivatives(xi);
    const double df = t.squaredNorm() + r.dot(tt);
    if (!(df > 0.0)) break;
    const double next = std::clamp(xi - r.dot(t) / df, -1.0, 1.0);
    const bool done = std::abs(next - xi) < 1e-15;
    xi = next;
    if (done) break;
  }
  return xi;
}

template <typename T>
const T& FindSet(const std::map<std::string, T>& sets, const std::string& name, const char* kind) {
  const auto it = sets.find(name);
  if (it != sets.end()) return it->second;
  std::ostringstream msg;
  msg << "mesh: " << kind << " set '" << name << "' does not exist; the mesh has " << kind
      << " sets: ";
  if (sets.empty()) msg << "(none)";
  bool first = true;
  for (const auto& [key, value] : sets) {
    msg << (first ? "" : ", ") << "'" << key << "'";
    first = false;
  }
  throw std::invalid_argument(msg.str());
}

Eigen::Matrix<double, 2, 3> EdgeCoordinates(const Mesh& mesh, const BoundaryEdge& e) {
  Eigen::Matrix<double, 2, 3> x;
  for (int a = 0; a < 3; ++a) x.col(a) = mesh.nodes[e.nodes[a]];
  return x;
}

const BoundaryEdge& EdgeAt(const Mesh& mesh, const std::string& set, const EdgePoint& p) {
  const auto& edges = mesh.EdgeSet(set);
  if (p.edge < 0 || p.edge >= static_cast<int>(edges.size()) || !(std::abs(p.xi) <= 1.0)) {
    std::ostringstream msg;
    msg << "edge point (edge " << p.edge << ", xi " << p.xi << ") on edge set '" << set
        << "': the rule is 0 <= edge < " << edges.size() << " and -1 <= xi <= 1";
    throw std::invalid_argument(msg.str());
  }
  return edges[p.edge];
}

}  // namespace

const std::vector<int>& Mesh::NodeSet(const std::string& name) const {
  return FindSet(node_sets, name, "node");
}
const std::vector<BoundaryEdge>& Mesh::EdgeSet(const std::string& name) const {
  return FindSet(edge_sets, name, "edge");
}
const std::vector<int>& Mesh::ElementSet(const std::string& name) const {
  return FindSet(element_sets, name, "element");
}

Q8Coordinates Mesh::ElementCoordinates(int e) const {
  Q8Coordinates x;
  for (int a = 0; a < kQ8Nodes; ++a) x.col(a) = nodes[elements[e][a]];
  return x;
}

void Mesh::Validate() const {
  const int n = num_nodes();
  auto fail = [](const std::string& text) { throw std::invalid_argument("mesh: " + text); };
  if (elements.empty()) fail("has no elements");
  for (int i = 0; i < n; ++i) {
    if (!nodes[i].allFinite()) fail("node " + std::to_string(i) + " has a non-finite position");
  }
  std::vector<char> used(nodes.size(), 0);
  for (int e = 0; e < num_elements(); ++e) {
    for (int a = 0; a < kQ8Nodes; ++a) {
      const int v = elements[e][a];
      if (v < 0 || v >= n) {
        fail("element " + std::to_string(e) + " local node " + std::to_string(a) + " = " +
             std::to_string(v) + ": the rule is 0 <= node < " + std::to_string(n));
      }
      for (int b = 0; b < a; ++b) {
        if (elements[e][b] == v) {
          fail("element " + std::to_string(e) + " uses node " + std::to_string(v) +
               " twice (local nodes " + std::to_string(b) + " and " + std::to_string(a) +
               "): the element is degenerate");
        }
      }
      used[v] = 1;
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!used[i]) fail("node " + std::to_string(i) + " belongs to no element (singular stiffness)");
  }
  for (const auto& [name, list] : node_sets) {
    for (int v : list) {
      if (v < 0 || v >= n) {
        fail("node set '" + name + "' holds node " + std::to_string(v) +
             ": the rule is 0 <= node < " + std::to_string(n));
      }
    }
  }
  for (const auto& [name, list] : element_sets) {
    for (int v : list) {
      if (v < 0 || v >= num_elements()) {
        fail("element set '" + name + "' holds element " + std::to_string(v) +
             ": the rule is 0 <= element < " + std::to_string(num_elements()));
      }
    }
  }
  for (int e = 0; e < num_elements(); ++e) CheckQ8Jacobian(ElementCoordinates(e), e);
  for (const auto& [name, list] : edge_sets) {
    for (std::size_t k = 0; k < list.size(); ++k) {
      const BoundaryEdge& edge = list[k];
      bool ok = edge.element >= 0 && edge.element < num_elements();
      if (ok) {
        ok = false;
        for (const auto& side : kQ8Sides) {
          const auto& el = elements[edge.element];
          if (el[side[0]] == edge.nodes[0] && el[side[1]] == edge.nodes[1] &&
              el[side[2]] == edge.nodes[2]) {
            ok = true;
          }
        }
      }
      if (!ok) {
        fail("edge " + std::to_string(k) + " of edge set '" + name + "' (nodes " +
             std::to_string(edge.nodes[0]) + ", " + std::to_string(edge.nodes[1]) + ", " +
             std::to_string(edge.nodes[2]) + ") is not a counter-clockwise side of element " +
             std::to_string(edge.element));
      }
    }
  }
}

Eigen::Vector2d Mesh::EdgePosition(const std::string& set, const EdgePoint& p) const {
  return EdgeCoordinates(*this, EdgeAt(*this, set, p)) * EdgeShapeFunctions(p.xi);
}

Eigen::Vector2d Mesh::EdgeNormal(const std::string& set, const EdgePoint& p) const {
  const Eigen::Vector2d t =
      EdgeCoordinates(*this, EdgeAt(*this, set, p)) * EdgeShapeDerivatives(p.xi);
  return Eigen::Vector2d(t.y(), -t.x()).normalized();
}

EdgePoint Mesh::LocateOnEdgeSet(const std::string& set, const Eigen::Vector2d& point,
                                double* distance) const {
  const auto& edges = EdgeSet(set);
  if (edges.empty()) {
    throw std::invalid_argument("mesh: edge set '" + set + "' is empty: cannot locate a point");
  }
  EdgePoint best;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Eigen::Matrix<double, 2, 3> x = EdgeCoordinates(*this, edges[k]);
    // Start from the chord projection, then Newton on f(ξ) = (x(ξ) − p)·x'(ξ) = 0 clamped to
    // [−1, 1]; the end points are candidates too (the minimum may sit at a corner).
    const double xi = ProjectOnQuadraticEdge(x, point);
    for (double candidate : {xi, -1.0, 1.0}) {
      const double d2 = (x * EdgeShapeFunctions(candidate) - point).squaredNorm();
      if (d2 < best_d2) {
        best_d2 = d2;
        best = EdgePoint{static_cast<int>(k), candidate};
      }
    }
  }
  if (distance != nullptr) *distance = std::sqrt(best_d2);
  return best;
}

std::optional<HangingNode> FindHangingNode(const Mesh& mesh) {
  // Sides by (lower corner, mid node, upper corner): count and the last element using it.
  std::map<std::tuple<int, int, int>, std::pair<int, int>> sides;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (const auto& s : kQ8Sides) {
      const int a = mesh.elements[e][s[0]], m = mesh.elements[e][s[1]], b = mesh.elements[e][s[2]];
      auto& entry = sides[{std::min(a, b), m, std::max(a, b)}];
      entry.first += 1;
      entry.second = e;
    }
  }
  std::vector<int> free_nodes;
  std::vector<std::pair<std::array<int, 3>, int>> free_sides;
  for (const auto& [key, entry] : sides) {
    if (entry.first != 1) continue;
    const std::array<int, 3> tri = {std::get<0>(key), std::get<1>(key), std::get<2>(key)};
    free_sides.push_back({tri, entry.second});
    for (int v : tri) free_nodes.push_back(v);
  }
  // Sweep in x: only free nodes within a side's bounding box are tried.
  std::sort(free_nodes.begin(), free_nodes.end());
  free_nodes.erase(std::unique(free_nodes.begin(), free_nodes.end()), free_nodes.end());
  std::sort(free_nodes.begin(), free_nodes.end(),
            [&](int a, int b) { return mesh.nodes[a].x() < mesh.nodes[b].x(); });
  for (const auto& [tri, element] : free_sides) {
    Eigen::Matrix<double, 2, 3> x;
    for (int a = 0; a < 3; ++a) x.col(a) = mesh.nodes[tri[a]];
    const double tol = 1e-6 * (x.col(2) - x.col(0)).norm();
    const Eigen::Vector2d lo = x.rowwise().minCoeff().array() - tol;
    const Eigen::Vector2d hi = x.rowwise().maxCoeff().array() + tol;
    auto first = std::lower_bound(free_nodes.begin(), free_nodes.end(), lo.x(),
                                  [&](int v, double value) { return mesh.nodes[v].x() < value; });
    for (auto it = first; it != free_nodes.end() && mesh.nodes[*it].x() <= hi.x(); ++it) {
      const int v = *it;
      if (v == tri[0] || v == tri[1] || v == tri[2]) continue;
      const Eigen::Vector2d& q = mesh.nodes[v];
      if (q.y() < lo.y() || q.y() > hi.y()) continue;
      const double xi = ProjectOnQuadraticEdge(x, q);
      if ((x * EdgeShapeFunctions(xi) - q).norm() <= tol && std::abs(xi) < 1.0 - 1e-9)
        return HangingNode{v, tri, element};
    }
  }
  return std::nullopt;
}

}  // namespace epicycle::compliance
