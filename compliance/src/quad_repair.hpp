// Quadrilateral repair of an unstructured mesh (used by the gmsh mesher, independent of gmsh):
// pairing the triangles that a quad recombination leaves behind along chains of quadrilaterals,
// splitting a poor merged quadrilateral into five, and a smart Laplacian smoothing of the inner
// vertices. Cells are linear (3 or 4 corners, counter-clockwise) over patch-local vertex ids;
// `position(id)` gives a vertex's coordinates [m].
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace epicycle::compliance::internal {

// A check of the mesher's own on a generated mesh failed (the gmsh mesher catches it per patch).
struct PatchFailure {
  std::string what;
};

// A linear cell of the patch's gmsh mesh: 3 or 4 corners (patch-local ids), counter-clockwise.
struct Cell {
  std::array<int, 4> v{};
  int n = 0;
};

// Quality of a linear cell: the smallest sine of its corner angles (> 0 iff strictly convex).
template <typename Position>
double Quality(const Cell& c, const Position& position) {
  double q = std::numeric_limits<double>::infinity();
  for (int k = 0; k < c.n; ++k) {
    const Eigen::Vector2d a = position(c.v[(k + 1) % c.n]) - position(c.v[k]);
    const Eigen::Vector2d b = position(c.v[(k + c.n - 1) % c.n]) - position(c.v[k]);
    q = std::min(q, (a.x() * b.y() - a.y() * b.x()) / (a.norm() * b.norm()));
  }
  return q;
}

inline bool HasEdge(const Cell& c, int a, int b) {
  const auto* end = c.v.begin() + c.n;
  return std::find(c.v.begin(), end, a) != end && std::find(c.v.begin(), end, b) != end;
}

// The quadrilateral made of triangles x and y that share the edge {a, b} (n = 0 if x lacks it).
inline Cell MergeTriangles(const Cell& x, const Cell& y, int a, int b) {
  int k = 0;  // rotate x to (u, w, o) with u → w its side {a, b} in counter-clockwise order
  while (k < 3 &&
         !((x.v[k] == a && x.v[(k + 1) % 3] == b) || (x.v[k] == b && x.v[(k + 1) % 3] == a))) {
    ++k;
  }
  if (k == 3) return Cell{};
  const int u = x.v[k], w = x.v[(k + 1) % 3], o = x.v[(k + 2) % 3];
  int far = -1;
  for (int j = 0; j < 3; ++j) {
    if (y.v[j] != a && y.v[j] != b) far = y.v[j];
  }
  return Cell{{u, far, w, o}, 4};
}

// Blossom leaves triangles where it finds no quadrilateral above its quality threshold (an acute
// patch corner, a cluster of short intervals). Each leftover triangle t is paired with another
// one t' reached through a chain of quadrilaterals: every quadrilateral of the chain is split
// along a diagonal into a triangle toward t and one toward t', and the triangles are re-paired
// one step along the chain (an augmenting path of the triangle matching). A new quadrilateral
// whose smallest corner sine is below kGoodQuality (say a vertex of a straight side at 180°) is
// replaced by five: an inner one around the midpoint M of the side its two triangles share (M
// sees the whole union) and four between it and the union's sides. The diagonals are chosen by
// dynamic programming over the chain to maximise the smallest corner sine of the result. Chains
// are searched breadth-first, once for each side through which they leave t (a chain around a
// vertex is found even when t' is also t's direct neighbour); the first result with sine ≥
// kGoodQuality is taken, else the best valid one. Two adjacent triangles are the chain of length 0.
constexpr double kGoodQuality = 0.1;

// A split scores its smallest corner sine times kSplitPenalty, so that a chain of plain
// quadrilaterals of fair quality is preferred to five small ones.
constexpr double kSplitPenalty = 0.5;

// Two triangles merged across their shared side {a, b}: one quadrilateral, or five (`split`);
// `quality` is the score (smallest corner sine, times kSplitPenalty for a split).
struct Merged {
  Cell quad;
  bool split = false;
  std::array<Eigen::Vector2d, 4> inner{};  // inner corners of the split, in quad order
  double quality = -std::numeric_limits<double>::infinity();
};

template <typename Position>
Merged Merge(const Cell& x, const Cell& y, int a, int b, const Position& position) {
  Merged m;
  auto area2 = [&](const Cell& t) {
    const Eigen::Vector2d u = position(t.v[1]) - position(t.v[0]);
    const Eigen::Vector2d w = position(t.v[2]) - position(t.v[0]);
    return u.x() * w.y() - u.y() * w.x();
  };
  if (!(area2(x) > 0.0 && area2(y) > 0.0)) return m;  // an inverted piece: no merge
  m.quad = MergeTriangles(x, y, a, b);
  if (m.quad.n != 4) return m;
  m.quality = Quality(m.quad, position);
  if (m.quality >= kGoodQuality) return m;
  const Eigen::Vector2d mid = 0.5 * (position(a) + position(b));
  double reach = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) reach = std::min(reach, (position(m.quad.v[k]) - mid).norm());
  for (double beta : {0.5, 0.35, 0.65, 0.2}) {
    std::array<Eigen::Vector2d, 4> inner;
    for (int k = 0; k < 4; ++k) {
      inner[k] = mid + beta * reach * (position(m.quad.v[k]) - mid).normalized();
    }
    auto at = [&](int id) -> Eigen::Vector2d { return id < 0 ? inner[-1 - id] : position(id); };
    double q = Quality(Cell{{-1, -2, -3, -4}, 4}, at);
    for (int k = 0; k < 4; ++k) {
      const Cell trapezoid{{m.quad.v[k], m.quad.v[(k + 1) % 4], -1 - (k + 1) % 4, -1 - k}, 4};
      q = std::min(q, Quality(trapezoid, at));
    }
    if (kSplitPenalty * q > m.quality) {
      m.quality = kSplitPenalty * q;
      m.split = true;
      m.inner = inner;
    }
  }
  return m;
}

template <typename Position, typename AddNode>
void RepairTriangles(std::vector<Cell>* cells, const Position& position, const AddNode& add_node) {
  using Edge = std::pair<int, int>;
  auto key = [](int a, int b) { return Edge{std::min(a, b), std::max(a, b)}; };
  std::vector<Cell>& c = *cells;
  for (;;) {
    const auto first = std::find_if(c.begin(), c.end(), [](const Cell& x) { return x.n == 3; });
    if (first == c.end()) return;
    const int start = static_cast<int>(first - c.begin());
    std::map<Edge, std::vector<int>> by_edge;
    for (int i = 0; i < static_cast<int>(c.size()); ++i) {
      for (int k = 0; k < c[i].n; ++k) {
        by_edge[key(c[i].v[k], c[i].v[(k + 1) % c[i].n])].push_back(i);
      }
    }
    double best_quality = 0.0;
    std::vector<int> best_chain;
    std::vector<Merged> best;

    // The best re-pairing along the chain start → … → end (shared[m] between cells m and m+1).
    auto evaluate = [&](const std::vector<int>& chain, const std::vector<Edge>& shared) {
      struct State {
        Cell piece;  // the triangle carried forward
        double quality;
        std::vector<Merged> merged;
      };
      std::vector<State> states = {State{c[start], std::numeric_limits<double>::infinity(), {}}};
      const int k = static_cast<int>(chain.size()) - 2;  // quadrilaterals in the chain
      for (int m = 1; m <= k; ++m) {
        const Cell& q = c[chain[m]];
        const Edge in = shared[m - 1], out = shared[m];
        std::vector<State> next;
        for (int d = 0; d < 2; ++d) {
          const Cell t0 =
              d == 0 ? Cell{{q.v[0], q.v[1], q.v[2], 0}, 3} : Cell{{q.v[0], q.v[1], q.v[3], 0}, 3};
          const Cell t1 =
              d == 0 ? Cell{{q.v[0], q.v[2], q.v[3], 0}, 3} : Cell{{q.v[1], q.v[2], q.v[3], 0}, 3};
          for (int flip = 0; flip < 2; ++flip) {
            const Cell& toward_in = flip == 0 ? t0 : t1;
            const Cell& toward_out = flip == 0 ? t1 : t0;
            if (!HasEdge(toward_in, in.first, in.second) ||
                !HasEdge(toward_out, out.first, out.second)) {
              continue;
            }
            for (const State& st : states) {
              Merged merged = Merge(st.piece, toward_in, in.first, in.second, position);
              State ns{toward_out, std::min(st.quality, merged.quality), st.merged};
              ns.merged.push_back(std::move(merged));
              auto same = std::find_if(next.begin(), next.end(),
                                       [&](const State& x) { return x.piece.v == ns.piece.v; });
              if (same == next.end()) {
                next.push_back(std::move(ns));
              } else if (ns.quality > same->quality) {
                *same = std::move(ns);
              }
            }
          }
        }
        states = std::move(next);
      }
      for (State& st : states) {
        const Edge in = shared.back();
        Merged merged = Merge(st.piece, c[chain.back()], in.first, in.second, position);
        st.quality = std::min(st.quality, merged.quality);
        if (st.quality > best_quality) {
          st.merged.push_back(std::move(merged));
          best_quality = st.quality;
          best_chain = chain;
          best = std::move(st.merged);
        }
      }
    };

    for (int side = 0; side < 3 && best_quality < kGoodQuality; ++side) {
      const Edge exit = key(c[start].v[side], c[start].v[(side + 1) % 3]);
      // Breadth-first through quadrilaterals; parent[i] = (previous cell, shared edge).
      std::vector<std::pair<int, Edge>> parent(c.size(), {-2, {}});
      parent[start] = {-1, {}};
      std::vector<int> queue;
      for (int j : by_edge[exit]) {
        if (j == start) continue;
        parent[j] = {start, exit};
        queue.push_back(j);
      }
      for (std::size_t head = 0; head < queue.size() && best_quality < kGoodQuality; ++head) {
        const int i = queue[head];
        if (c[i].n == 3) {
          std::vector<int> chain;
          std::vector<Edge> shared;
          for (int j = i; j != start; j = parent[j].first) {
            chain.push_back(j);
            shared.push_back(parent[j].second);
          }
          chain.push_back(start);
          std::reverse(chain.begin(), chain.end());
          std::reverse(shared.begin(), shared.end());
          evaluate(chain, shared);
          continue;  // a chain ends at a triangle: do not walk through it
        }
        for (int e = 0; e < c[i].n; ++e) {
          const Edge edge = key(c[i].v[e], c[i].v[(e + 1) % c[i].n]);
          for (int j : by_edge[edge]) {
            if (parent[j].first != -2) continue;
            parent[j] = {i, edge};
            queue.push_back(j);
          }
        }
      }
    }
    if (best.empty()) {
      throw PatchFailure{
          "the recombination left triangles that no chain of quadrilaterals turns into valid "
          "quadrilaterals (the rule: an all-quadrilateral mesh)"};
    }
    for (std::size_t m = 0; m < best.size(); ++m) {
      const Merged& merged = best[m];
      Cell& target = c[best_chain[m]];
      if (!merged.split) {
        target = merged.quad;
        continue;
      }
      std::array<int, 4> ids{};
      for (int k = 0; k < 4; ++k) ids[k] = add_node(merged.inner[k]);
      target = Cell{{ids[0], ids[1], ids[2], ids[3]}, 4};
      for (int k = 0; k < 4; ++k) {
        c.push_back(
            Cell{{merged.quad.v[k], merged.quad.v[(k + 1) % 4], ids[(k + 1) % 4], ids[k]}, 4});
      }
    }
    c[best_chain.back()].n = 0;
    c.erase(std::remove_if(c.begin(), c.end(), [](const Cell& x) { return x.n == 0; }), c.end());
  }
}

// Smart Laplacian smoothing of the interior corners (ids ≥ n_loop, positions interior[id −
// n_loop]): each moves to the mean of its edge neighbours unless that lowers the smallest corner
// sine of its cells. Before the triangle repair it untangles what gmsh's own smoothing may have
// folded (a cell of negative area); after it, it tidies the new cells. Boundary vertices never
// move.
constexpr int kSmoothingSweeps = 10;

template <typename Position>
void SmoothInterior(const std::vector<Cell>& cells, int n_loop, const Position& position,
                    std::vector<Eigen::Vector2d>* interior) {
  const int n = static_cast<int>(interior->size());
  std::vector<std::vector<int>> neighbours(n), incident(n);
  for (int i = 0; i < static_cast<int>(cells.size()); ++i) {
    const Cell& c = cells[i];
    for (int k = 0; k < c.n; ++k) {
      const int v = c.v[k];
      if (v < n_loop) continue;
      incident[v - n_loop].push_back(i);
      for (int w : {c.v[(k + 1) % c.n], c.v[(k + c.n - 1) % c.n]}) {
        auto& list = neighbours[v - n_loop];
        if (std::find(list.begin(), list.end(), w) == list.end()) list.push_back(w);
      }
    }
  }
  auto worst = [&](int k) {
    double q = std::numeric_limits<double>::infinity();
    for (int i : incident[k]) q = std::min(q, Quality(cells[i], position));
    return q;
  };
  for (int sweep = 0; sweep < kSmoothingSweeps; ++sweep) {
    for (int k = 0; k < n; ++k) {
      if (neighbours[k].empty()) continue;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (int w : neighbours[k]) mean += position(w);
      mean /= static_cast<double>(neighbours[k].size());
      const Eigen::Vector2d old = (*interior)[k];
      const double before = worst(k);
      (*interior)[k] = mean;
      if (worst(k) < before) (*interior)[k] = old;
    }
  }
}

}  // namespace epicycle::compliance::internal
