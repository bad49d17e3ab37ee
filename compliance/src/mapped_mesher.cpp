#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "epicycle/compliance/mesher.hpp"

#include "mesher_common.hpp"

namespace epicycle::compliance {

Curve StraightLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return [a, b](double t) -> Eigen::Vector2d { return a + t * (b - a); };
}

Curve CircularArc(const Eigen::Vector2d& c, double r, double theta0, double theta1) {
  return [c, r, theta0, theta1](double t) -> Eigen::Vector2d {
    const double th = theta0 + t * (theta1 - theta0);
    return c + r * Eigen::Vector2d(std::cos(th), std::sin(th));
  };
}

Curve Reversed(Curve curve) {
  return [c = std::move(curve)](double t) -> Eigen::Vector2d { return c(1.0 - t); };
}

Patch Rotated(const Patch& patch, double angle) {
  Patch q = patch;
  const double c = std::cos(angle), s = std::sin(angle);
  for (int k = 0; k < 4; ++k) {
    q.sides[k] = [curve = patch.sides[k], c, s](double t) -> Eigen::Vector2d {
      const Eigen::Vector2d x = curve(t);
      return {c * x.x() - s * x.y(), s * x.x() + c * x.y()};
    };
  }
  return q;
}

Distribution Distribution::Graded(int n, double last_over_first) {
  const double ratio = n > 1 ? std::pow(last_over_first, 1.0 / (n - 1)) : 1.0;
  return Distribution{n, ratio, {}};
}

std::vector<double> Distribution::Parameters(const std::string& field) const {
  auto fail = [&](const std::string& text) { throw std::invalid_argument(field + ": " + text); };
  if (!breaks.empty()) {
    if (breaks.size() < 2 || breaks.front() != 0.0 || breaks.back() != 1.0) {
      fail("breaks must start at exactly 0 and end at exactly 1 (got " +
           std::to_string(breaks.size()) + " values)");
    }
    for (std::size_t k = 1; k < breaks.size(); ++k) {
      if (!(breaks[k] > breaks[k - 1])) {
        std::ostringstream msg;
        msg << "breaks[" << k << "] = " << breaks[k] << " must be > breaks[" << k - 1
            << "] = " << breaks[k - 1] << " (strictly increasing)";
        fail(msg.str());
      }
    }
    return breaks;
  }
  if (divisions < 1 || divisions > 1000000) {
    fail("divisions = " + std::to_string(divisions) + ": the rule is 1 <= divisions <= 1e6");
  }
  if (!std::isfinite(ratio) || ratio <= 0.0) {
    std::ostringstream msg;
    msg << "ratio = " << ratio << ": must be finite and > 0";
    fail(msg.str());
  }
  const int n = divisions;
  std::vector<double> t(n + 1);
  const double total = std::abs(ratio - 1.0) < 1e-14 ? static_cast<double>(n)
                                                     : (std::pow(ratio, n) - 1.0) / (ratio - 1.0);
  double size = 1.0 / total;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    t[k] = sum;
    sum += size;
    size *= ratio;
  }
  t[n] = 1.0;
  for (int k = 1; k <= n; ++k) {
    if (!(t[k] > t[k - 1])) {
      std::ostringstream msg;
      msg << "ratio = " << ratio << " with " << n
          << " divisions gives intervals below round-off; use a milder grading";
      fail(msg.str());
    }
  }
  return t;
}

void MappedMesherOptions::Validate() const {
  auto check = [](const char* field, double value) {
    if (!std::isfinite(value) || value <= 0.0 || value >= 1e-3) {
      std::ostringstream msg;
      msg << "MappedMesherOptions." << field << " = " << value
          << ": must be finite, > 0 and < 1e-3 (relative to the region size)";
      throw std::invalid_argument(msg.str());
    }
  };
  check("merge_tolerance", merge_tolerance);
  check("corner_tolerance", corner_tolerance);
}

MappedMesher::MappedMesher(MappedMesherOptions options) : options_(options) { options_.Validate(); }

namespace {

using internal::kSideNames;
using internal::PatchLabel;
using internal::Point;

// Spatial hash on cells of size `cell` for merging coincident nodes.
struct CellKey {
  std::int64_t i, j;
  bool operator==(const CellKey& o) const { return i == o.i && j == o.j; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return std::hash<std::int64_t>()(k.i * 73856093LL) ^
           std::hash<std::int64_t>()(k.j * 19349663LL);
  }
};

struct PatchGrid {
  int nu = 0, nv = 0;     // elements per direction
  std::vector<int> node;  // (2nu+1)×(2nv+1) raw → global node, −1 for element centres
  int At(int i, int j) const { return node[static_cast<std::size_t>(j) * (2 * nu + 1) + i]; }
  bool positive = true;  // counter-clockwise in (u, v)
};

}  // namespace

namespace {

// The scale of the region (its bounding box's diagonal [m]), its side curves checked present and
// finite.
double MappedRegionScale(const Region& region) {
  const int num_patches = static_cast<int>(region.patches.size());
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (int p = 0; p < num_patches; ++p) {
    const Patch& patch = region.patches[p];
    for (int s = 0; s < 4; ++s) {
      if (!patch.sides[s]) {
        throw std::invalid_argument("mapped mesher: " + PatchLabel(region, p) + ": the " +
                                    kSideNames[s] + " side curve is empty");
      }
      for (int k = 0; k <= 16; ++k) {
        const Eigen::Vector2d x = patch.sides[s](k / 16.0);
        if (!x.allFinite()) {
          throw std::invalid_argument(
              "mapped mesher: " + PatchLabel(region, p) + ": the " + kSideNames[s] +
              " side curve gives a non-finite point at t = " + std::to_string(k / 16.0));
        }
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
    }
  }
  return (hi - lo).norm();
}

// The named sides of a patch (its grid `g`, its elements `patch_elements` row by row): node sets
// in curve order, edge sets counter-clockwise per element.
void AddNamedSides(const Patch& patch, const PatchGrid& g, const std::vector<int>& patch_elements,
                   Mesh& mesh) {
  const int mu = 2 * g.nu + 1;
  const int mv = 2 * g.nv + 1;
  for (int s = 0; s < 4; ++s) {
    const std::string& name = patch.side_names[s];
    if (name.empty()) continue;
    const bool along_u = (s == 0 || s == 2);
    const int count = along_u ? mu : mv;
    auto& nodes = mesh.node_sets[name];
    for (int k = 0; k < count; ++k) {
      const int id = along_u ? g.At(k, s == 0 ? 0 : mv - 1) : g.At(s == 3 ? 0 : mu - 1, k);
      if (std::find(nodes.begin(), nodes.end(), id) == nodes.end()) nodes.push_back(id);
    }
    // Walking the side curve forward, the patch lies to the left on bottom and right sides of
    // a counter-clockwise patch; to the right on top and left sides.
    const bool forward_is_ccw = ((s == 0 || s == 1) == g.positive);
    auto& edges = mesh.edge_sets[name];
    const int n_edges = along_u ? g.nu : g.nv;
    for (int k = 0; k < n_edges; ++k) {
      std::array<int, 3> tri;
      int element;
      if (along_u) {
        const int j = s == 0 ? 0 : mv - 1;
        tri = {g.At(2 * k, j), g.At(2 * k + 1, j), g.At(2 * k + 2, j)};
        element = patch_elements[static_cast<std::size_t>(s == 0 ? 0 : g.nv - 1) * g.nu + k];
      } else {
        const int i = s == 3 ? 0 : mu - 1;
        tri = {g.At(i, 2 * k), g.At(i, 2 * k + 1), g.At(i, 2 * k + 2)};
        element = patch_elements[static_cast<std::size_t>(k) * g.nu + (s == 3 ? 0 : g.nu - 1)];
      }
      if (!forward_is_ccw) std::swap(tri[0], tri[2]);
      const bool duplicate = std::any_of(edges.begin(), edges.end(), [&](const BoundaryEdge& e) {
        return e.nodes[1] == tri[1] && std::min(e.nodes[0], e.nodes[2]) == std::min(tri[0], tri[2]);
      });
      if (!duplicate) edges.push_back(BoundaryEdge{tri, element});
    }
  }
}

}  // namespace

Mesh MappedMesher::BuildMesh(const Region& region) const {
  if (region.patches.empty())
    throw std::invalid_argument("mapped mesher: the region has no patches");
  const int num_patches = static_cast<int>(region.patches.size());

  // Sides present, scale of the region, corners consistent.
  const double scale = MappedRegionScale(region);
  if (!(scale > 0.0)) throw std::invalid_argument("mapped mesher: the region has zero size");
  const double merge_tol = options_.merge_tolerance * scale;
  const double corner_tol = options_.corner_tolerance * scale;

  for (int p = 0; p < num_patches; ++p) {
    const std::string mismatch = internal::PatchCornerMismatch(region, p, corner_tol);
    if (!mismatch.empty()) throw std::invalid_argument("mapped mesher: " + mismatch);
  }

  Mesh mesh;
  std::unordered_map<CellKey, std::vector<int>, CellHash> cells;
  const double cell = 2.0 * merge_tol;
  auto key_of = [&](const Eigen::Vector2d& x) {
    return CellKey{static_cast<std::int64_t>(std::floor(x.x() / cell)),
                   static_cast<std::int64_t>(std::floor(x.y() / cell))};
  };
  auto add_node = [&](const Eigen::Vector2d& x) -> int {
    const CellKey k = key_of(x);
    for (std::int64_t di = -1; di <= 1; ++di) {
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        const auto it = cells.find(CellKey{k.i + di, k.j + dj});
        if (it == cells.end()) continue;
        for (int v : it->second) {
          if ((mesh.nodes[v] - x).norm() <= merge_tol) return v;
        }
      }
    }
    const int id = mesh.num_nodes();
    mesh.nodes.push_back(x);
    cells[k].push_back(id);
    return id;
  };

  std::vector<int> element_patch;
  std::vector<PatchGrid> grids(num_patches);
  for (int p = 0; p < num_patches; ++p) {
    const Patch& patch = region.patches[p];
    const std::vector<double> tu =
        patch.u.Parameters("mapped mesher: " + PatchLabel(region, p) + " u");
    const std::vector<double> tv =
        patch.v.Parameters("mapped mesher: " + PatchLabel(region, p) + " v");
    PatchGrid& g = grids[p];
    g.nu = static_cast<int>(tu.size()) - 1;
    g.nv = static_cast<int>(tv.size()) - 1;
    const int mu = 2 * g.nu + 1;
    const int mv = 2 * g.nv + 1;
    std::vector<double> u(mu), v(mv);
    for (int k = 0; k < g.nu; ++k) {
      u[2 * k] = tu[k];
      u[2 * k + 1] = 0.5 * (tu[k] + tu[k + 1]);
    }
    u[mu - 1] = 1.0;
    for (int k = 0; k < g.nv; ++k) {
      v[2 * k] = tv[k];
      v[2 * k + 1] = 0.5 * (tv[k] + tv[k + 1]);
    }
    v[mv - 1] = 1.0;
    std::vector<Eigen::Vector2d> bottom(mu), top(mu), left(mv), right(mv);
    for (int i = 0; i < mu; ++i) {
      bottom[i] = patch.sides[0](u[i]);
      top[i] = patch.sides[2](u[i]);
    }
    for (int j = 0; j < mv; ++j) {
      right[j] = patch.sides[1](v[j]);
      left[j] = patch.sides[3](v[j]);
    }
    const Eigen::Vector2d p00 = bottom.front(), p10 = bottom.back(), p01 = top.front(),
                          p11 = top.back();
    // Orientation from the signed area of the boundary polygon (counter-clockwise > 0).
    std::vector<Eigen::Vector2d> loop;
    for (int i = 0; i < mu - 1; ++i) loop.push_back(bottom[i]);
    for (int j = 0; j < mv - 1; ++j) loop.push_back(right[j]);
    for (int i = mu - 1; i > 0; --i) loop.push_back(top[i]);
    for (int j = mv - 1; j > 0; --j) loop.push_back(left[j]);
    double area2 = 0.0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Eigen::Vector2d& a = loop[k];
      const Eigen::Vector2d& b = loop[(k + 1) % loop.size()];
      area2 += a.x() * b.y() - a.y() * b.x();
    }
    if (!(std::abs(area2) > 0.0)) {
      throw std::invalid_argument("mapped mesher: " + PatchLabel(region, p) +
                                  ": the patch encloses zero area (degenerate patch)");
    }
    g.positive = area2 > 0.0;

    g.node.assign(static_cast<std::size_t>(mu) * mv, -1);
    for (int j = 0; j < mv; ++j) {
      for (int i = 0; i < mu; ++i) {
        if (i % 2 == 1 && j % 2 == 1) continue;  // no centre node in a serendipity element
        Eigen::Vector2d x;
        if (j == 0) {
          x = bottom[i];
        } else if (j == mv - 1) {
          x = top[i];
        } else if (i == 0) {
          x = left[j];
        } else if (i == mu - 1) {
          x = right[j];
        } else {
          const double a = u[i], b = v[j];
          x = (1.0 - b) * bottom[i] + b * top[i] + (1.0 - a) * left[j] + a * right[j] -
              ((1.0 - a) * (1.0 - b) * p00 + a * (1.0 - b) * p10 + (1.0 - a) * b * p01 +
               a * b * p11);
        }
        g.node[static_cast<std::size_t>(j) * mu + i] = add_node(x);
      }
    }

    std::vector<int> patch_elements;
    for (int j = 0; j < g.nv; ++j) {
      for (int i = 0; i < g.nu; ++i) {
        const int c00 = g.At(2 * i, 2 * j), c10 = g.At(2 * i + 2, 2 * j);
        const int c11 = g.At(2 * i + 2, 2 * j + 2), c01 = g.At(2 * i, 2 * j + 2);
        const int mb = g.At(2 * i + 1, 2 * j), mr = g.At(2 * i + 2, 2 * j + 1);
        const int mt = g.At(2 * i + 1, 2 * j + 2), ml = g.At(2 * i, 2 * j + 1);
        std::array<int, kQ8Nodes> el;
        if (g.positive) {
          el = {c00, c10, c11, c01, mb, mr, mt, ml};
        } else {
          el = {c00, c01, c11, c10, ml, mt, mr, mb};
        }
        patch_elements.push_back(mesh.num_elements());
        mesh.elements.push_back(el);
        element_patch.push_back(p);
      }
    }
    if (!patch.name.empty()) {
      auto& set = mesh.element_sets[patch.name];
      set.insert(set.end(), patch_elements.begin(), patch_elements.end());
    }

    AddNamedSides(patch, g, patch_elements, mesh);
  }

  // Element geometry, with the patch named in the message.
  for (int e = 0; e < mesh.num_elements(); ++e) {
    try {
      CheckQ8Jacobian(mesh.ElementCoordinates(e), e);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument("mapped mesher: " + PatchLabel(region, element_patch[e]) + ": " +
                                  error.what());
    }
  }

  if (options_.check_conformity) {
    if (const auto h = FindHangingNode(mesh)) {
      std::ostringstream msg;
      msg << "mapped mesher: non-conforming join: node " << h->node << " at "
          << Point(mesh.nodes[h->node]) << " lies inside the free side (nodes " << h->side[0]
          << ", " << h->side[1] << ", " << h->side[2] << ") of element " << h->element << " of "
          << PatchLabel(region, element_patch[h->element])
          << " without being one of its nodes; patches that share a side must place the same "
             "nodes on it (same divisions and grading, possibly reversed)";
      throw std::invalid_argument(msg.str());
    }
  }

  mesh.Validate();
  return mesh;
}

}  // namespace epicycle::compliance
