// The gmsh mesher (EPICYCLE_WITH_GMSH=ON); the design is documented in gmsh_mesher.hpp.
#include "epicycle/compliance/gmsh_mesher.hpp"

#include "mesher_common.hpp"
#include "quad_repair.hpp"
#include "slit_mesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace epicycle::compliance {

bool GmshMesher::Available() { return true; }

std::string GmshMesher::LibraryVersion() { return GMSH_API_VERSION; }

namespace {

using namespace internal;  // mesher_common.hpp, quad_repair.hpp

// gmsh's MSH element types of a linear 2D mesh.
constexpr int kGmshTriangle3 = 2;
constexpr int kGmshQuad4 = 3;
// Growth rate g of the element size away from the boundary vertices [-] (see MeshPatch).
constexpr double kSizeGrowth = 0.3;

[[noreturn]] void Fail(const std::string& text) {
  throw std::invalid_argument("gmsh mesher: " + text);
}

// Empties gmsh's log: stop + start (the caller holds the mutex). One flag for the process,
// hence not inside the CallGmsh template (one static per instantiation).
void RestartGmshLog() {
  static bool logging = false;
  if (logging) gmsh::logger::stop();
  gmsh::logger::start();
  logging = true;
}

// Runs a block of gmsh calls (the caller holds the mutex) and turns every failure into the
// mesher's std::invalid_argument naming `what` (the patch). gmsh runs with General.AbortOnError
// = 0: it meshes inside an OpenMP parallel region, from which an exception (its default reaction
// to an error) cannot escape and would terminate the process; so errors are collected by gmsh's
// logger and reported here; gmsh 4.8's API throws std::string. The block throws PatchFailure for
// the mesher's own checks.
template <typename F>
void CallGmsh(const std::string& what, F&& f) {
  std::string error;
  try {
    RestartGmshLog();
    f();
    std::vector<std::string> log;
    gmsh::logger::get(log);
    for (const std::string& line : log) {
      if (line.rfind("Error", 0) == 0) error += (error.empty() ? "" : "; ") + line;
    }
    if (error.empty()) return;
    error = "gmsh: " + error;
  } catch (const PatchFailure& e) {
    error = e.what;
  } catch (const std::string& e) {
    error = "gmsh: " + e;
  } catch (const char* e) {
    error = std::string("gmsh: ") + e;
  } catch (const std::exception& e) {
    error = std::string("gmsh: ") + e.what();
  } catch (...) {
    error = "gmsh: unknown exception";
  }
  Fail(what + ": " + error);
}

// The boundary nodes of one patch: for each side its node parameters and points in curve order
// (element corners at even indices, mid-sides at odd ones), and the loop bottom → right → top
// reversed → left reversed, whose even entries are element corners and odd entries mid-sides.
struct PatchSamples {
  std::array<std::vector<double>, 4> param;
  std::array<std::vector<Eigen::Vector2d>, 4> side;
  std::vector<Eigen::Vector2d> loop;
  int loop_size() const { return static_cast<int>(loop.size()); }
  int count(int s) const { return static_cast<int>(side[s].size()); }
  // Loop index of node k of side s.
  int LoopIndex(int s, int k) const {
    const int c0 = count(0) - 1, c1 = count(1) - 1, c2 = count(2) - 1, c3 = count(3) - 1;
    switch (s) {
      case 0:
        return k;
      case 1:
        return c0 + k;
      case 2:
        return c0 + c1 + (c2 - k);
      default:
        return (c0 + c1 + c2 + (c3 - k)) % (c0 + c1 + c2 + c3);
    }
  }
  void BuildLoop() {
    loop.assign(static_cast<std::size_t>(count(0) + count(1) + count(2) + count(3) - 4), {});
    for (int s = 0; s < 4; ++s) {
      for (int k = 0; k < count(s); ++k) loop[LoopIndex(s, k)] = side[s][k];
    }
  }
};

std::vector<double> NodeParameters(const std::vector<double>& t) {
  const int n = static_cast<int>(t.size()) - 1;
  std::vector<double> out(2 * n + 1);
  for (int k = 0; k < n; ++k) {
    out[2 * k] = t[k];
    out[2 * k + 1] = 0.5 * (t[k] + t[k + 1]);
  }
  out[2 * n] = 1.0;
  return out;
}

// The gmsh mesh of one patch in patch-local numbering: indices below the loop size are the loop
// samples, the others `interior` nodes; elements counter-clockwise.
struct LocalMesh {
  std::vector<Eigen::Vector2d> interior;
  std::vector<std::array<int, kQ8Nodes>> elements;
};

// Where a patch's mesh comes from: its own gmsh mesh (master == itself, identity rotation) or
// the mesh of an earlier patch rotated by (cos θ, sin θ).
struct Source {
  int master = -1;
  double c = 1.0, s = 0.0;
};

std::mutex& GmshMutex() {
  static std::mutex mutex;
  return mutex;
}

// Initialises gmsh once per process and sets every option the meshes depend on (the caller holds
// the mutex). gmsh is never finalised: it lives until the process exits.
void PrepareGmsh() {
  static bool initialized = false;
  if (!initialized) {
    try {
      gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    } catch (...) {
      Fail("gmsh::initialize failed");
    }
    initialized = true;
  }
  CallGmsh("options", [&] {
    const std::pair<const char*, double> options[] = {
        {"General.Terminal", 0.0},
        {"General.Verbosity", 2.0},     // errors and warnings reach the logger
        {"General.AbortOnError", 0.0},  // see CallGmsh
        {"General.NumThreads", 1.0},
        {"Geometry.AutoCoherence", 0.0},
        {"Mesh.RecombineAll", 0.0},
        {"Mesh.RecombinationAlgorithm", 1.0},  // Blossom
        {"Mesh.SubdivisionAlgorithm", 0.0},
        {"Mesh.Smoothing", 1.0},
        {"Mesh.MeshSizeFromPoints", 0.0},  // the background field alone sets the size
        {"Mesh.MeshSizeExtendFromBoundary", 0.0},
        {"Mesh.MeshSizeFromCurvature", 0.0},
        {"Mesh.MeshSizeMin", 0.0},
        {"Mesh.MeshSizeMax", 1e22},
        {"Mesh.ElementOrder", 1.0},
    };
    for (const auto& [name, value] : options) gmsh::option::setNumber(name, value);
  });
}

// Removes the current gmsh model on scope exit.
class ModelScope {
 public:
  explicit ModelScope(const std::string& name) { gmsh::model::add(name); }
  ~ModelScope() {
    try {
      gmsh::model::remove();
    } catch (...) {  // nothing to do: the next call adds a fresh model
    }
  }
  ModelScope(const ModelScope&) = delete;
  ModelScope& operator=(const ModelScope&) = delete;
};

// gmsh settings of one attempt at a patch (see BuildMesh).
struct Attempt {
  int algorithm = 6;         // Mesh.Algorithm
  double size_factor = 1.0;  // Mesh.MeshSizeFactor
};

// Meshes one patch with gmsh (the caller holds the mutex).
// The quadrilaterals and triangles gmsh made of `surface`, as cells of our node ids (`local`:
// gmsh node tag → id). @throws PatchFailure for another element type, a node of no entity or no
// element at all.
std::vector<Cell> SurfaceCells(int surface, const std::unordered_map<std::size_t, int>& local) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, surface);
  std::vector<Cell> cells;
  for (std::size_t t = 0; t < types.size(); ++t) {
    const int per = types[t] == kGmshQuad4 ? 4 : types[t] == kGmshTriangle3 ? 3 : 0;
    if (per == 0) throw PatchFailure{"unexpected element type " + std::to_string(types[t])};
    for (std::size_t e = 0; e < element_tags[t].size(); ++e) {
      Cell cell{{}, per};
      for (int a = 0; a < per; ++a) {
        const auto it = local.find(node_tags[t][e * static_cast<std::size_t>(per) + a]);
        if (it == local.end()) throw PatchFailure{"an element uses a node of no entity"};
        cell.v[a] = it->second;
      }
      cells.push_back(cell);
    }
  }
  if (cells.empty()) throw PatchFailure{"gmsh generated no elements"};
  return cells;
}

LocalMesh MeshPatch(const PatchSamples& smp, const std::string& label, const Attempt& attempt) {
  const int n_loop = smp.loop_size();
  const int n_corners = n_loop / 2;
  LocalMesh out;
  CallGmsh(label, [&] {
    gmsh::option::setNumber("Mesh.Algorithm", attempt.algorithm);
    gmsh::option::setNumber("Mesh.MeshSizeFactor", attempt.size_factor);
    ModelScope model("epicycle_gmsh_mesher");
    // Boundary: the corner samples, one straight line with a single element per interval.
    std::vector<double> size(n_corners);
    double size_max = 0.0;
    for (int k = 0; k < n_corners; ++k) {
      const Eigen::Vector2d& x = smp.loop[2 * k];
      const Eigen::Vector2d& prev = smp.loop[(2 * k + n_loop - 2) % n_loop];
      const Eigen::Vector2d& next = smp.loop[(2 * k + 2) % n_loop];
      size[k] = 0.5 * ((x - prev).norm() + (next - x).norm());
      size_max = std::max(size_max, size[k]);
    }
    std::vector<int> points(n_corners), lines(n_corners);
    for (int k = 0; k < n_corners; ++k) {
      const Eigen::Vector2d& x = smp.loop[2 * k];
      points[k] = gmsh::model::geo::addPoint(x.x(), x.y(), 0.0, size[k]);
    }
    for (int k = 0; k < n_corners; ++k) {
      lines[k] = gmsh::model::geo::addLine(points[k], points[(k + 1) % n_corners]);
      gmsh::model::geo::mesh::setTransfiniteCurve(lines[k], 2);
    }
    const int loop = gmsh::model::geo::addCurveLoop(lines);
    const int surface = gmsh::model::geo::addPlaneSurface({loop});
    gmsh::model::geo::mesh::setRecombine(2, surface);
    gmsh::model::geo::synchronize();
    // Interior size: h(x) = min_k (h_k + g |x − x_k|), h_k the size at boundary vertex k, so
    // that the elements grow at rate g away from short boundary intervals.
    std::vector<double> thresholds;
    for (int k = 0; k < n_corners; ++k) {
      const int distance = gmsh::model::mesh::field::add("Distance");
      gmsh::model::mesh::field::setNumbers(distance, "PointsList",
                                           {static_cast<double>(points[k])});
      const int threshold = gmsh::model::mesh::field::add("Threshold");
      gmsh::model::mesh::field::setNumber(threshold, "InField", distance);
      gmsh::model::mesh::field::setNumber(threshold, "SizeMin", size[k]);
      gmsh::model::mesh::field::setNumber(threshold, "SizeMax", size_max);
      gmsh::model::mesh::field::setNumber(threshold, "DistMin", 0.0);
      gmsh::model::mesh::field::setNumber(
          threshold, "DistMax", std::max((size_max - size[k]) / kSizeGrowth, 1e-6 * size_max));
      thresholds.push_back(threshold);
    }
    const int smallest = gmsh::model::mesh::field::add("Min");
    gmsh::model::mesh::field::setNumbers(smallest, "FieldsList", thresholds);
    gmsh::model::mesh::field::setAsBackgroundMesh(smallest);
    gmsh::model::mesh::generate(2);

    // Patch-local numbering: loop sample index for boundary vertices, n_loop + k for interior.
    std::unordered_map<std::size_t, int> local;
    std::vector<std::size_t> tags;
    std::vector<double> coord, param;
    for (int k = 0; k < n_corners; ++k) {
      gmsh::model::mesh::getNodes(tags, coord, param, 0, points[k], false, false);
      if (tags.size() != 1) {
        throw PatchFailure{"boundary vertex " + std::to_string(k) + " has no mesh node"};
      }
      local[tags[0]] = 2 * k;
      gmsh::model::mesh::getNodes(tags, coord, param, 1, lines[k], false, false);
      if (!tags.empty()) {
        throw PatchFailure{"boundary interval " + std::to_string(k) +
                           " was split by gmsh (the rule: one element per interval; is the patch "
                           "boundary self-intersecting?)"};
      }
    }
    gmsh::model::mesh::getNodes(tags, coord, param, 2, surface, false, false);
    for (std::size_t a = 0; a < tags.size(); ++a) {
      local[tags[a]] = n_loop + static_cast<int>(out.interior.size());
      out.interior.emplace_back(coord[3 * a], coord[3 * a + 1]);
    }
    auto position = [&](int id) -> const Eigen::Vector2d& {
      return id < n_loop ? smp.loop[id] : out.interior[id - n_loop];
    };
    std::vector<Cell> cells = SurfaceCells(surface, local);
    // gmsh orients all elements of a surface alike; turn them counter-clockwise together, so
    // that an element its smoothing has tangled keeps a negative area (and gets untangled).
    double area2 = 0.0;
    for (const Cell& cell : cells) {
      for (int a = 0; a < cell.n; ++a) {
        const Eigen::Vector2d& p = position(cell.v[a]);
        const Eigen::Vector2d& q = position(cell.v[(a + 1) % cell.n]);
        area2 += p.x() * q.y() - p.y() * q.x();
      }
    }
    if (area2 < 0.0) {
      for (Cell& cell : cells) std::reverse(cell.v.begin() + 1, cell.v.begin() + cell.n);
    }
    SmoothInterior(cells, n_loop, position, &out.interior);
    RepairTriangles(&cells, position, [&](const Eigen::Vector2d& x) {
      out.interior.push_back(x);
      return n_loop + static_cast<int>(out.interior.size()) - 1;
    });
    SmoothInterior(cells, n_loop, position, &out.interior);

    // Second order: the mid-side node of a boundary interval is its mid-side sample (on the
    // side curve); inside, the straight midpoint, shared by the two elements of the side.
    std::map<std::pair<int, int>, int> mid;
    auto mid_node = [&](int a, int b) {
      if (a < n_loop && b < n_loop) {
        if ((a + 2) % n_loop == b) return (a + 1) % n_loop;
        if ((b + 2) % n_loop == a) return (b + 1) % n_loop;
      }
      const auto k = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = mid.find(k);
      if (it != mid.end()) return it->second;
      const int id = n_loop + static_cast<int>(out.interior.size());
      out.interior.push_back(0.5 * (position(a) + position(b)));
      mid[k] = id;
      return id;
    };
    for (const Cell& cell : cells) {
      std::array<int, kQ8Nodes> el{};
      for (int a = 0; a < 4; ++a) el[a] = cell.v[a];
      for (int a = 0; a < 4; ++a) el[4 + a] = mid_node(cell.v[a], cell.v[(a + 1) % 4]);
      out.elements.push_back(el);
    }
    // Every element valid, with its boundary mid-side nodes on the (curved) sides.
    for (std::size_t e = 0; e < out.elements.size(); ++e) {
      Q8Coordinates x;
      for (int a = 0; a < kQ8Nodes; ++a) x.col(a) = position(out.elements[e][a]);
      try {
        CheckQ8Jacobian(x, static_cast<int>(e));
      } catch (const std::invalid_argument& error) {
        throw PatchFailure{std::string(error.what()) + " (element of the patch's own numbering)"};
      }
    }
  });
  return out;
}

// Points merged within a tolerance (spatial hash on cells of twice the tolerance).
class PointIndex {
 public:
  explicit PointIndex(double tolerance) : tolerance_(tolerance), cell_(2.0 * tolerance) {}
  // The index of the point within the tolerance of x, or of x added.
  int Add(const Eigen::Vector2d& x) {
    const Key k = KeyOf(x);
    for (std::int64_t di = -1; di <= 1; ++di) {
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        const auto it = cells_.find(Key{k.i + di, k.j + dj});
        if (it == cells_.end()) continue;
        for (int v : it->second) {
          if ((points_[v] - x).norm() <= tolerance_) return v;
        }
      }
    }
    cells_[k].push_back(static_cast<int>(points_.size()));
    points_.push_back(x);
    return static_cast<int>(points_.size()) - 1;
  }
  // x added without merging (a node inside a patch).
  int AddUnmerged(const Eigen::Vector2d& x) {
    points_.push_back(x);
    return static_cast<int>(points_.size()) - 1;
  }
  std::vector<Eigen::Vector2d>& points() { return points_; }

 private:
  struct Key {
    std::int64_t i, j;
    bool operator==(const Key& o) const { return i == o.i && j == o.j; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return std::hash<std::int64_t>()(k.i * 73856093LL) ^
             std::hash<std::int64_t>()(k.j * 19349663LL);
    }
  };
  Key KeyOf(const Eigen::Vector2d& x) const {
    return Key{static_cast<std::int64_t>(std::floor(x.x() / cell_)),
               static_cast<std::int64_t>(std::floor(x.y() / cell_))};
  }
  double tolerance_, cell_;
  std::vector<Eigen::Vector2d> points_;
  std::unordered_map<Key, std::vector<int>, Hash> cells_;
};

// Subdivision of an unnamed boundary interval of chord length L whose end vertices carry the
// element sizes h_a and h_b: the size along it is σ(x) = min(h_a + g x, h_b + g (L − x)), and it
// is cut into N pieces of equal ∫ dx/σ, N the odd number nearest to ∫_0^L dx/σ (odd, so that the
// number of intervals around a patch stays even, as an all-quadrilateral mesh needs). The cuts
// in the half next to each end are computed from that end, so that a patch that runs the side
// the other way cuts it at the same points. Returns the cut fractions 0 < f < 1 of the interval,
// or nothing when the interval is at most kSplitThreshold sizes long.
constexpr double kSplitThreshold = 2.0;

std::vector<double> SplitFractions(double length, double h_a, double h_b) {
  if (!(h_a > 0.0 && h_b > 0.0 && length > 0.0)) return {};
  const double g = kSizeGrowth;
  // ∫_0^s dx/σ from the end with size h (h_other at the far end), 0 ≤ s ≤ L.
  auto integral = [&](double h, double h_other, double s) {
    const double cross = std::clamp((h_other - h + g * length) / (2.0 * g), 0.0, length);
    if (s <= cross) return std::log1p(g * s / h) / g;
    return std::log1p(g * cross / h) / g +
           std::log((h_other + g * (length - cross)) / (h_other + g * (length - s))) / g;
  };
  const double total_a = integral(h_a, h_b, length), total_b = integral(h_b, h_a, length);
  const double total = 0.5 * (total_a + total_b);  // symmetric in (a, b) to the last bit
  if (total <= kSplitThreshold) return {};
  const int n = std::max(3, 2 * static_cast<int>(std::floor(0.5 * total)) + 1);
  std::vector<double> out;
  for (int j = 1; j < n; ++j) {
    const bool from_a = 2 * j < n;
    const double h = from_a ? h_a : h_b, h_other = from_a ? h_b : h_a;
    const double target = from_a ? total_a * j / n : total_b * (n - j) / n;
    double lo = 0.0, hi = length;
    for (int it = 0; it < 200 && hi - lo > 1e-15 * length; ++it) {
      const double mid = 0.5 * (lo + hi);
      (integral(h, h_other, mid) < target ? lo : hi) = mid;
    }
    const double f = 0.5 * (lo + hi) / length;
    out.push_back(from_a ? f : 1.0 - f);
  }
  return out;
}

// Free sides (used by one element) must not carry another node inside them: that would be a
// hanging node of a non-conforming join between patches.
void CheckConformity(const Mesh& mesh, const Region& region, const std::vector<int>& patch_of) {
  if (const auto h = FindHangingNode(mesh)) {
    std::ostringstream msg;
    msg << "non-conforming join: node " << h->node << " at " << Point(mesh.nodes[h->node])
        << " lies inside the free side (nodes " << h->side[0] << ", " << h->side[1] << ", "
        << h->side[2] << ") of element " << h->element << " of "
        << PatchLabel(region, patch_of[h->element])
        << " without being one of its nodes; patches that share a side must place the same "
           "nodes on it (same divisions and grading, possibly reversed)";
    Fail(msg.str());
  }
}

}  // namespace

namespace {

// The region's scale (the diagonal of its bounding box [m]), its side curves checked present and
// finite.
double RegionScale(const Region& region) {
  const int num_patches = static_cast<int>(region.patches.size());
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (int p = 0; p < num_patches; ++p) {
    for (int s = 0; s < 4; ++s) {
      const Curve& curve = region.patches[p].sides[s];
      if (!curve) {
        Fail(PatchLabel(region, p) + ": the " + kSideNames[s] + " side curve is empty");
      }
      for (int k = 0; k <= 16; ++k) {
        const Eigen::Vector2d x = curve(k / 16.0);
        if (!x.allFinite()) {
          Fail(PatchLabel(region, p) + ": the " + kSideNames[s] +
               " side curve gives a non-finite point at t = " + std::to_string(k / 16.0));
        }
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
    }
  }
  return (hi - lo).norm();
}

// Boundary nodes of every patch at the distributions' parameters, with the corner checks of
// MappedMesher.
std::vector<PatchSamples> SampleBoundaries(const Region& region, double corner_tol) {
  const int num_patches = static_cast<int>(region.patches.size());
  std::vector<PatchSamples> samples(num_patches);
  for (int p = 0; p < num_patches; ++p) {
    const Patch& patch = region.patches[p];
    const auto& sides = patch.sides;
    const std::string mismatch = PatchCornerMismatch(region, p, corner_tol);
    if (!mismatch.empty()) Fail(mismatch);
    const std::string label = "gmsh mesher: " + PatchLabel(region, p);
    const std::vector<double> u = NodeParameters(patch.u.Parameters(label + " u"));
    const std::vector<double> v = NodeParameters(patch.v.Parameters(label + " v"));
    for (int s = 0; s < 4; ++s) {
      samples[p].param[s] = (s == 0 || s == 2) ? u : v;
      for (double t : samples[p].param[s]) samples[p].side[s].push_back(sides[s](t));
    }
  }
  return samples;
}

// Unnamed sides: intervals much longer than the element size at their ends are subdivided
// (SplitFractions), the same way by every patch that has the side, so that the unstructured
// interior can grade from short to long intervals. The size at a vertex is its shortest
// interval over all sides of all patches; named sides (flanks, hub) are never subdivided.
void SubdivideUnnamedSides(const Region& region, double merge_tol,
                           std::vector<PatchSamples>& samples) {
  const int num_patches = static_cast<int>(region.patches.size());
  PointIndex vertices(merge_tol);
  std::vector<double> vertex_size;
  std::vector<std::array<std::vector<int>, 4>> vertex_of(num_patches);
  for (int p = 0; p < num_patches; ++p) {
    for (int s = 0; s < 4; ++s) {
      const auto& x = samples[p].side[s];
      const int n = static_cast<int>(x.size()) / 2;  // intervals
      for (int i = 0; i <= n; ++i) {
        const int id = vertices.Add(x[2 * i]);
        vertex_of[p][s].push_back(id);
        if (id >= static_cast<int>(vertex_size.size())) {
          vertex_size.push_back(std::numeric_limits<double>::infinity());
        }
        if (i > 0) vertex_size[id] = std::min(vertex_size[id], (x[2 * i] - x[2 * i - 2]).norm());
        if (i < n) vertex_size[id] = std::min(vertex_size[id], (x[2 * i + 2] - x[2 * i]).norm());
      }
    }
  }
  std::set<std::pair<int, int>> named;
  for (int p = 0; p < num_patches; ++p) {
    for (int s = 0; s < 4; ++s) {
      if (region.patches[p].side_names[s].empty()) continue;
      const auto& ids = vertex_of[p][s];
      for (std::size_t i = 0; i + 1 < ids.size(); ++i) {
        named.insert({std::min(ids[i], ids[i + 1]), std::max(ids[i], ids[i + 1])});
      }
    }
  }
  for (int p = 0; p < num_patches; ++p) {
    for (int s = 0; s < 4; ++s) {
      const std::vector<double> t = samples[p].param[s];
      const auto& x = samples[p].side[s];
      const auto& ids = vertex_of[p][s];
      std::vector<double> refined;
      for (std::size_t i = 0; i + 1 < ids.size(); ++i) {
        const double ta = t[2 * i], tb = t[2 * i + 2];
        std::vector<double> cut;
        if (named.count({std::min(ids[i], ids[i + 1]), std::max(ids[i], ids[i + 1])}) == 0) {
          cut = SplitFractions((x[2 * i + 2] - x[2 * i]).norm(), vertex_size[ids[i]],
                               vertex_size[ids[i + 1]]);
        }
        if (cut.empty()) {
          refined.push_back(ta);
          refined.push_back(t[2 * i + 1]);
          continue;
        }
        double previous = ta;
        for (std::size_t j = 0; j <= cut.size(); ++j) {
          const double next = j < cut.size() ? ta + cut[j] * (tb - ta) : tb;
          refined.push_back(previous);
          refined.push_back(0.5 * (previous + next));
          previous = next;
        }
      }
      refined.push_back(t.back());
      if (refined.size() == t.size()) continue;
      samples[p].param[s] = refined;
      samples[p].side[s].clear();
      for (double ti : refined) samples[p].side[s].push_back(region.patches[p].sides[s](ti));
    }
  }
}

// The loop of every patch, checked to enclose an area.
void BuildLoops(const Region& region, std::vector<PatchSamples>& samples) {
  const int num_patches = static_cast<int>(region.patches.size());
  for (int p = 0; p < num_patches; ++p) {
    PatchSamples& smp = samples[p];
    smp.BuildLoop();
    double area2 = 0.0;
    for (int k = 0; k < smp.loop_size(); ++k) {
      const Eigen::Vector2d& a = smp.loop[k];
      const Eigen::Vector2d& b = smp.loop[(k + 1) % smp.loop_size()];
      area2 += a.x() * b.y() - a.y() * b.x();
    }
    if (!(std::abs(area2) > 0.0)) {
      Fail(PatchLabel(region, p) + ": the patch encloses zero area (degenerate patch)");
    }
  }
}

// Rotated copies: the loop of patch p equals R(θ) × the loop of an earlier master. Returns each
// patch's source; `masters` receives the patches that are their own.
std::vector<Source> RotatedCopies(const std::vector<PatchSamples>& samples, double merge_tol,
                                  bool reuse_rotated_copies, std::vector<int>* masters_out) {
  const int num_patches = static_cast<int>(samples.size());
  std::vector<Source> source(num_patches);
  std::vector<int> masters;
  for (int p = 0; p < num_patches; ++p) {
    const PatchSamples& sp = samples[p];
    source[p] = Source{p, 1.0, 0.0};
    if (!reuse_rotated_copies) continue;
    for (int m : masters) {
      const PatchSamples& sm = samples[m];
      if (sm.loop_size() != sp.loop_size()) continue;
      int ref = 0;
      for (int k = 1; k < sm.loop_size(); ++k) {
        if (sm.loop[k].norm() > sm.loop[ref].norm()) ref = k;
      }
      const Eigen::Vector2d a = sm.loop[ref], b = sp.loop[ref];
      if (std::abs(a.norm() - b.norm()) > merge_tol || !(a.norm() > merge_tol)) continue;
      const double theta = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
      const double c = std::cos(theta), s = std::sin(theta);
      bool same = true;
      for (int k = 0; k < sm.loop_size() && same; ++k) {
        const Eigen::Vector2d& x = sm.loop[k];
        same =
            (Eigen::Vector2d(c * x.x() - s * x.y(), s * x.x() + c * x.y()) - sp.loop[k]).norm() <=
            merge_tol;
      }
      if (same) {
        source[p] = Source{m, c, s};
        break;
      }
    }
    if (source[p].master == p) masters.push_back(p);
  }
  *masters_out = std::move(masters);
  return source;
}

// gmsh meshes the masters, one model each.
std::vector<LocalMesh> MeshMasters(const Region& region, const std::vector<PatchSamples>& samples,
                                   const std::vector<int>& masters, int algorithm) {
  std::vector<LocalMesh> local(samples.size());
  const std::lock_guard<std::mutex> lock(GmshMutex());
  PrepareGmsh();
  // The unstructured mesh of a patch can fail (gmsh leaves a tangle, or a quadrilateral that
  // the curved side makes invalid at a corner): then the patch is meshed again with the other
  // triangle algorithm and with 20 % smaller elements; the first failure is reported if all do.
  const int other = algorithm == 6 ? 5 : 6;
  const Attempt attempts[] = {{algorithm, 1.0}, {other, 1.0}, {algorithm, 0.8}, {other, 0.8}};
  for (int m : masters) {
    std::string first_error;
    bool done = false;
    for (const Attempt& attempt : attempts) {
      try {
        local[m] = MeshPatch(samples[m], PatchLabel(region, m), attempt);
        done = true;
        break;
      } catch (const std::invalid_argument& error) {
        if (first_error.empty()) first_error = error.what();
      }
    }
    if (!done) {
      throw std::invalid_argument(first_error + " (and with " +
                                  std::to_string(std::size(attempts) - 1) +
                                  " other gmsh settings)");
    }
  }
  return local;
}

// Named sides of patch p (its elements first_element … last_element − 1 of `mesh`, `global` its
// local node numbers): node sets along the curve; edge sets with the element's own (counter-
// clockwise) node order.
void AddNamedSides(const Region& region, int p, const PatchSamples& smp,
                   const std::vector<int>& global, int first_element, int last_element,
                   Mesh& mesh) {
  const Patch& patch = region.patches[p];
  std::map<std::pair<int, int>, std::pair<int, int>> edge_owner;  // corners → (element, side)
  bool have_owners = false;
  for (int side = 0; side < 4; ++side) {
    const std::string& name = patch.side_names[side];
    if (name.empty()) continue;
    if (!have_owners) {
      for (int e = first_element; e < last_element; ++e) {
        for (int q = 0; q < 4; ++q) {
          const int a = mesh.elements[e][kQ8Sides[q][0]], b = mesh.elements[e][kQ8Sides[q][2]];
          edge_owner[{std::min(a, b), std::max(a, b)}] = {e, q};
        }
      }
      have_owners = true;
    }
    const int count = static_cast<int>(smp.side[side].size());
    auto& nodes = mesh.node_sets[name];
    for (int k = 0; k < count; ++k) {
      const int id = global[smp.LoopIndex(side, k)];
      if (std::find(nodes.begin(), nodes.end(), id) == nodes.end()) nodes.push_back(id);
    }
    auto& edges = mesh.edge_sets[name];
    for (int k = 0; k + 2 < count; k += 2) {
      const int a = global[smp.LoopIndex(side, k)];
      const int m = global[smp.LoopIndex(side, k + 1)];
      const int b = global[smp.LoopIndex(side, k + 2)];
      const auto it = edge_owner.find({std::min(a, b), std::max(a, b)});
      if (it == edge_owner.end() ||
          mesh.elements[it->second.first][kQ8Sides[it->second.second][1]] != m) {
        std::ostringstream msg;
        msg << PatchLabel(region, p) << ": " << kSideNames[side] << " side '" << name
            << "', interval " << k / 2 << ": no element of the patch has the side (nodes " << a
            << ", " << m << ", " << b << ")";
        Fail(msg.str());
      }
      const int element = it->second.first;
      const auto& local_side = kQ8Sides[it->second.second];
      const std::array<int, 3> tri = {mesh.elements[element][local_side[0]],
                                      mesh.elements[element][local_side[1]],
                                      mesh.elements[element][local_side[2]]};
      const bool duplicate = std::any_of(edges.begin(), edges.end(), [&](const BoundaryEdge& edge) {
        return edge.nodes[1] == tri[1] &&
               std::min(edge.nodes[0], edge.nodes[2]) == std::min(tri[0], tri[2]);
      });
      if (!duplicate) edges.push_back(BoundaryEdge{tri, element});
    }
  }
}

}  // namespace

Mesh GmshMesher::BuildMesh(const Region& region) const {
  if (region.patches.empty()) Fail("the region has no patches");
  const int num_patches = static_cast<int>(region.patches.size());

  const double scale = RegionScale(region);
  if (!(scale > 0.0)) Fail("the region has zero size");
  const double merge_tol = options_.merge_tolerance * scale;
  const double corner_tol = options_.corner_tolerance * scale;

  std::vector<PatchSamples> samples = SampleBoundaries(region, corner_tol);
  SubdivideUnnamedSides(region, merge_tol, samples);
  BuildLoops(region, samples);
  std::vector<int> masters;
  const std::vector<Source> source =
      RotatedCopies(samples, merge_tol, options_.reuse_rotated_copies, &masters);
  const std::vector<LocalMesh> local = MeshMasters(region, samples, masters, options_.algorithm);

  // Assembly: boundary nodes are the patch's own samples (merged across patches), interior nodes
  // the master's, rotated.
  PointIndex merged(merge_tol);
  Mesh mesh;
  std::vector<int> patch_of;
  for (int p = 0; p < num_patches; ++p) {
    const Patch& patch = region.patches[p];
    const PatchSamples& smp = samples[p];
    const LocalMesh& lm = local[source[p].master];
    const double c = source[p].c, s = source[p].s;
    const int n_loop = smp.loop_size();
    std::vector<int> global(n_loop + lm.interior.size());
    for (int k = 0; k < n_loop; ++k) global[k] = merged.Add(smp.loop[k]);
    for (std::size_t k = 0; k < lm.interior.size(); ++k) {
      const Eigen::Vector2d& x = lm.interior[k];
      global[n_loop + k] = merged.AddUnmerged({c * x.x() - s * x.y(), s * x.x() + c * x.y()});
    }
    const int first_element = mesh.num_elements();
    for (const auto& el : lm.elements) {
      std::array<int, kQ8Nodes> g{};
      for (int a = 0; a < kQ8Nodes; ++a) g[a] = global[el[a]];
      mesh.elements.push_back(g);
      patch_of.push_back(p);
    }
    const int last_element = mesh.num_elements();
    if (!patch.name.empty()) {
      auto& set = mesh.element_sets[patch.name];
      for (int e = first_element; e < last_element; ++e) set.push_back(e);
    }
    AddNamedSides(region, p, smp, global, first_element, last_element, mesh);
  }

  mesh.nodes = std::move(merged.points());

  // Element geometry (the mid-side nodes moved onto curved sides included), the patch named.
  for (int e = 0; e < mesh.num_elements(); ++e) {
    try {
      CheckQ8Jacobian(mesh.ElementCoordinates(e), e);
    } catch (const std::invalid_argument& error) {
      Fail(PatchLabel(region, patch_of[e]) + ": " + error.what());
    }
  }
  if (options_.check_conformity) CheckConformity(mesh, region, patch_of);
  try {
    mesh.Validate();
  } catch (const std::invalid_argument& error) {
    Fail(error.what());
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// The slit polygon (slit_mesh.hpp): one gmsh plane surface bounded by the loop's corners, the
// crack's segments embedded in it, quadrilaterals as in MeshPatch; then, for an open crack, the
// crack's nodes (all but the tip) duplicated: around each, the cells fall into the two fans that
// the crack's sides separate, and the fan on the right of the path gets the copy. The crack's
// nodes (both copies) stay where they are through the smoothing (they are fixed like the loop),
// and the triangle repair, which runs after the duplication, sees the two faces as boundary and
// never pairs cells across them.
namespace internal {

namespace {

// gmsh's mesh of the slit polygon: the crack's nodes (mouth excluded) with their positions, the
// cells (loop ids, crack ids n_loop + k, free interior nodes −1 − a), the crack's corner ids
// from the mouth to the tip, and gmsh's interior nodes (x, y, a).
struct SlitGmshMesh {
  std::vector<Eigen::Vector2d> crack_nodes;  // positions of ids n_loop + k
  std::vector<Cell> cells;
  std::vector<int> path;                            // mouth → tip (gmsh's originals)
  std::vector<std::array<double, 3>> raw_interior;  // gmsh interior nodes (x, y, tag)
};

SlitGmshMesh GmshSlitMesh(const SlitInput& input) {
  const int n_loop = static_cast<int>(input.loop.size());
  const int n_corners = n_loop / 2;
  SlitGmshMesh g;
  std::vector<Eigen::Vector2d>& crack_nodes = g.crack_nodes;
  std::vector<Cell>& cells = g.cells;
  std::vector<int>& path = g.path;
  std::vector<std::array<double, 3>>& raw_interior = g.raw_interior;
  const std::lock_guard<std::mutex> lock(GmshMutex());
  PrepareGmsh();
  CallGmsh("slit polygon", [&] {
    gmsh::option::setNumber("Mesh.Algorithm", 6);
    gmsh::option::setNumber("Mesh.MeshSizeFactor", 1.0);
    ModelScope model("epicycle_gmsh_slit");
    std::vector<double> size(n_corners);
    double size_max = 0.0;
    for (int k = 0; k < n_corners; ++k) {
      const Eigen::Vector2d& x = input.loop[2 * k];
      size[k] = 0.5 * ((x - input.loop[(2 * k + n_loop - 2) % n_loop]).norm() +
                       (input.loop[(2 * k + 2) % n_loop] - x).norm());
      size_max = std::max(size_max, size[k]);
    }
    std::vector<Eigen::Vector2d> crack_all = {input.loop[input.mouth]};
    crack_all.insert(crack_all.end(), input.crack.begin(), input.crack.end());
    std::vector<double> crack_size(crack_all.size());
    for (std::size_t k = 0; k < crack_all.size(); ++k) {
      const double before = k > 0 ? (crack_all[k] - crack_all[k - 1]).norm() : 0.0;
      const double after =
          k + 1 < crack_all.size() ? (crack_all[k + 1] - crack_all[k]).norm() : before;
      crack_size[k] = k > 0 ? 0.5 * (before + after) : after;
    }
    size[input.mouth / 2] = std::min(size[input.mouth / 2], crack_size[0]);
    std::vector<int> points(n_corners), lines(n_corners);
    for (int k = 0; k < n_corners; ++k) {
      const Eigen::Vector2d& x = input.loop[2 * k];
      points[k] = gmsh::model::geo::addPoint(x.x(), x.y(), 0.0, size[k]);
    }
    for (int k = 0; k < n_corners; ++k) {
      lines[k] = gmsh::model::geo::addLine(points[k], points[(k + 1) % n_corners]);
      gmsh::model::geo::mesh::setTransfiniteCurve(lines[k], 2);
    }
    std::vector<int> crack_points = {points[input.mouth / 2]}, crack_lines;
    for (int k = 1; k < static_cast<int>(crack_all.size()); ++k) {
      crack_points.push_back(
          gmsh::model::geo::addPoint(crack_all[k].x(), crack_all[k].y(), 0.0, crack_size[k]));
      crack_lines.push_back(gmsh::model::geo::addLine(crack_points[k - 1], crack_points[k]));
      gmsh::model::geo::mesh::setTransfiniteCurve(crack_lines.back(), 2);
    }
    const int loop = gmsh::model::geo::addCurveLoop(lines);
    const int surface = gmsh::model::geo::addPlaneSurface({loop});
    gmsh::model::geo::mesh::setRecombine(2, surface);
    gmsh::model::geo::synchronize();
    gmsh::model::mesh::embed(1, crack_lines, 2, surface);
    std::vector<double> thresholds;
    auto threshold_at = [&](int point, double h) {
      const int distance = gmsh::model::mesh::field::add("Distance");
      gmsh::model::mesh::field::setNumbers(distance, "PointsList", {static_cast<double>(point)});
      const int threshold = gmsh::model::mesh::field::add("Threshold");
      gmsh::model::mesh::field::setNumber(threshold, "InField", distance);
      gmsh::model::mesh::field::setNumber(threshold, "SizeMin", h);
      gmsh::model::mesh::field::setNumber(threshold, "SizeMax", size_max);
      gmsh::model::mesh::field::setNumber(threshold, "DistMin", 0.0);
      gmsh::model::mesh::field::setNumber(threshold, "DistMax",
                                          std::max((size_max - h) / kSizeGrowth, 1e-6 * size_max));
      thresholds.push_back(threshold);
    };
    for (int k = 0; k < n_corners; ++k) threshold_at(points[k], size[k]);
    for (std::size_t k = 1; k < crack_points.size(); ++k)
      threshold_at(crack_points[k], crack_size[k]);
    const int smallest = gmsh::model::mesh::field::add("Min");
    gmsh::model::mesh::field::setNumbers(smallest, "FieldsList", thresholds);
    gmsh::model::mesh::field::setAsBackgroundMesh(smallest);
    gmsh::model::mesh::generate(2);

    std::unordered_map<std::size_t, int> local;
    std::vector<std::size_t> tags;
    std::vector<double> coord, param;
    for (int k = 0; k < n_corners; ++k) {
      gmsh::model::mesh::getNodes(tags, coord, param, 0, points[k], false, false);
      if (tags.size() != 1) throw PatchFailure{"a boundary vertex has no mesh node"};
      local[tags[0]] = 2 * k;
      gmsh::model::mesh::getNodes(tags, coord, param, 1, lines[k], false, false);
      if (!tags.empty()) throw PatchFailure{"a boundary interval was split by gmsh"};
    }
    path.push_back(input.mouth);
    for (std::size_t k = 1; k < crack_points.size(); ++k) {
      gmsh::model::mesh::getNodes(tags, coord, param, 0, crack_points[k], false, false);
      if (tags.size() != 1) throw PatchFailure{"a crack point has no mesh node"};
      local[tags[0]] = n_loop + static_cast<int>(crack_nodes.size());
      path.push_back(n_loop + static_cast<int>(crack_nodes.size()));
      crack_nodes.push_back(crack_all[k]);
      gmsh::model::mesh::getNodes(tags, coord, param, 1, crack_lines[k - 1], false, false);
      if (!tags.empty()) throw PatchFailure{"a crack segment was split by gmsh"};
    }
    gmsh::model::mesh::getNodes(tags, coord, param, 2, surface, false, false);
    for (std::size_t a = 0; a < tags.size(); ++a) {
      raw_interior.push_back({coord[3 * a], coord[3 * a + 1], static_cast<double>(a)});
      local[tags[a]] = -1 - static_cast<int>(a);  // free node a (renumbered below)
    }
    cells = SurfaceCells(surface, local);
  });
  return g;
}

// The sides of the cells oriented counter-clockwise; every crack side must be a cell side (gmsh
// keeps embedded segments). `position` gives a node id's point.
template <class Position>
void OrientAndCheckCells(const std::vector<int>& path, const Position& position,
                         std::vector<Cell>& cells) {
  // Counter-clockwise cells.
  double area2 = 0.0;
  for (const Cell& cell : cells) {
    for (int a = 0; a < cell.n; ++a) {
      const Eigen::Vector2d& p = position(cell.v[a]);
      const Eigen::Vector2d& q = position(cell.v[(a + 1) % cell.n]);
      area2 += p.x() * q.y() - p.y() * q.x();
    }
  }
  if (area2 < 0.0) {
    for (Cell& cell : cells) std::reverse(cell.v.begin() + 1, cell.v.begin() + cell.n);
  }
  // Every crack side must be a cell side (gmsh keeps embedded segments).
  auto has_side = [&](const Cell& c, int a, int b) {
    for (int k = 0; k < c.n; ++k) {
      const int p = c.v[k], q = c.v[(k + 1) % c.n];
      if ((p == a && q == b) || (p == b && q == a)) return true;
    }
    return false;
  };
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    int count = 0;
    for (const Cell& c : cells) count += has_side(c, path[k], path[k + 1]) ? 1 : 0;
    if (count != 2) throw PatchFailure{"crack segment " + std::to_string(k) + " is not a side"};
  }
}

// An open crack: around each of its nodes but the tip, the cells fall into the two fans that the
// crack's sides separate, and the fan on the right of the path (mouth → tip) gets the copy
// `copy_of[k]` of node path[k].
template <class Position>
void SeparateCrackFaces(const std::vector<int>& path, const std::vector<int>& copy_of,
                        const Position& position, std::vector<Cell>& cells) {
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const int p = path[k];
    const Eigen::Vector2d& x = position(p);
    const Eigen::Vector2d out_dir = position(path[k + 1]) - x;
    const Eigen::Vector2d back_dir =
        k > 0 ? Eigen::Vector2d(position(path[k - 1]) - x) : Eigen::Vector2d(-out_dir);
    auto ccw_angle = [&](const Eigen::Vector2d& v) {
      double a = std::atan2(out_dir.x() * v.y() - out_dir.y() * v.x(), out_dir.dot(v));
      if (a < 0.0) a += 2.0 * 3.14159265358979323846;
      return a;
    };
    const double beta = ccw_angle(back_dir);
    for (Cell& cell : cells) {
      int at = -1;
      for (int a = 0; a < cell.n; ++a) {
        if (cell.v[a] == p) at = a;
      }
      if (at < 0) continue;
      // The cell's direction at p: the bisector of its two sides there.
      const Eigen::Vector2d u = (position(cell.v[(at + 1) % cell.n]) - x).normalized() +
                                (position(cell.v[(at + cell.n - 1) % cell.n]) - x).normalized();
      if (k == 0) {
        if (out_dir.x() * u.y() - out_dir.y() * u.x() < 0.0) cell.v[at] = copy_of[k];
      } else if (ccw_angle(u) > beta) {
        cell.v[at] = copy_of[k];
      }
    }
  }
}

// The slit mesh's output: numbering loop, then crack nodes, then free nodes, then mid-side
// nodes; the Q8 elements of the (all-quadrilateral) cells, checked; the crack's faces.
template <class Position>
SlitMesh SlitOutput(const SlitInput& input, const std::vector<Cell>& cells,
                    const std::vector<Eigen::Vector2d>& crack_nodes,
                    const std::vector<Eigen::Vector2d>& free_nodes, const std::vector<int>& path,
                    const std::vector<int>& copy_of, const Position& position) {
  const int n_loop = static_cast<int>(input.loop.size());
  SlitMesh out;
  // Output numbering: loop, then crack nodes, then free nodes, then mid-side nodes.
  for (const Eigen::Vector2d& x : crack_nodes) out.interior.push_back(x);
  for (const Eigen::Vector2d& x : free_nodes) out.interior.push_back(x);
  std::map<std::pair<int, int>, int> mid;
  auto mid_node = [&](int a, int b) {
    if (a < n_loop && b < n_loop) {
      if ((a + 2) % n_loop == b) return (a + 1) % n_loop;
      if ((b + 2) % n_loop == a) return (b + 1) % n_loop;
    }
    // The mouth's copy is on the loop too: its boundary interval's mid-side sample.
    const int a0 = input.open && a == copy_of[0] ? input.mouth : a;
    const int b0 = input.open && b == copy_of[0] ? input.mouth : b;
    if ((a0 != a || b0 != b) && a0 < n_loop && b0 < n_loop) {
      if ((a0 + 2) % n_loop == b0) return (a0 + 1) % n_loop;
      if ((b0 + 2) % n_loop == a0) return (b0 + 1) % n_loop;
    }
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const int id = n_loop + static_cast<int>(out.interior.size());
    out.interior.push_back(0.5 * (position(a) + position(b)));
    mid[key] = id;
    return id;
  };
  for (const Cell& cell : cells) {
    if (cell.n != 4) throw PatchFailure{"a triangle is left"};
    std::array<int, kQ8Nodes> el{};
    for (int a = 0; a < 4; ++a) el[a] = cell.v[a];
    for (int a = 0; a < 4; ++a) el[4 + a] = mid_node(cell.v[a], cell.v[(a + 1) % 4]);
    out.elements.push_back(el);
  }
  for (std::size_t e = 0; e < out.elements.size(); ++e) {
    Q8Coordinates x;
    for (int a = 0; a < kQ8Nodes; ++a) {
      const int id = out.elements[e][a];
      x.col(a) = id < n_loop ? input.loop[id] : out.interior[id - n_loop];
    }
    try {
      CheckQ8Jacobian(x, static_cast<int>(e));
    } catch (const std::invalid_argument& error) {
      throw PatchFailure{std::string(error.what()) + " (element of the slit polygon)"};
    }
  }
  out.left = path;
  out.right = path;
  if (input.open) {
    for (std::size_t k = 0; k + 1 < path.size(); ++k) out.right[k] = copy_of[k];
  }
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    out.left_mid.push_back(mid_node(out.left[k], out.left[k + 1]));
    out.right_mid.push_back(mid_node(out.right[k], out.right[k + 1]));
  }
  return out;
}

}  // namespace

SlitMesh MeshSlitPolygon(const SlitInput& input) {
  const int n_loop = static_cast<int>(input.loop.size());
  const int n_corners = n_loop / 2;
  const int n_crack = static_cast<int>(input.crack.size());
  if (n_loop < 6 || n_loop % 2 != 0 || input.mouth < 0 || input.mouth >= n_loop ||
      input.mouth % 2 != 0 || n_crack < 1) {
    Fail("slit polygon: bad input (loop of " + std::to_string(n_loop) + " samples, mouth " +
         std::to_string(input.mouth) + ", " + std::to_string(n_crack) + " crack points)");
  }
  if (n_corners % 2 != 0) {
    Fail("slit polygon: " + std::to_string(n_corners) +
         " boundary intervals; the rule: an even number (an all-quadrilateral mesh)");
  }
  // Local ids: [0, n_loop) loop, [n_loop, n_fixed) crack nodes (gmsh's, then the copies),
  // [n_fixed, …) free interior nodes. gmsh's mesh is made under its lock; the rest runs outside.
  SlitGmshMesh g = GmshSlitMesh(input);
  std::vector<Eigen::Vector2d>& crack_nodes = g.crack_nodes;
  std::vector<Cell>& cells = g.cells;
  const std::vector<int>& path = g.path;
  std::vector<Eigen::Vector2d> free_nodes;
  // Duplicates (open crack): ids n_loop + n_gmsh_crack + …, so that all crack ids precede the
  // free ones; the free ids are set once the count is known.
  std::vector<int> copy_of(path.size(), -1);
  if (input.open) {
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
      copy_of[k] = n_loop + static_cast<int>(crack_nodes.size());
      crack_nodes.push_back(k == 0 ? input.loop[input.mouth] : crack_nodes[path[k] - n_loop]);
    }
  }
  const int n_fixed = n_loop + static_cast<int>(crack_nodes.size());
  for (Cell& cell : cells) {
    for (int a = 0; a < cell.n; ++a) {
      if (cell.v[a] < 0) cell.v[a] = n_fixed + (-1 - cell.v[a]);
    }
  }
  for (const auto& x : g.raw_interior) free_nodes.emplace_back(x[0], x[1]);
  auto position = [&](int id) -> const Eigen::Vector2d& {
    if (id < n_loop) return input.loop[id];
    if (id < n_fixed) return crack_nodes[id - n_loop];
    return free_nodes[id - n_fixed];
  };
  SlitMesh out;
  CallGmsh("slit polygon", [&] {
    OrientAndCheckCells(path, position, cells);
    if (input.open) SeparateCrackFaces(path, copy_of, position, cells);
    // Fixed: loop and crack; the free nodes are smoothed, the triangles repaired.
    SmoothInterior(cells, n_fixed, position, &free_nodes);
    RepairTriangles(&cells, position, [&](const Eigen::Vector2d& x) {
      free_nodes.push_back(x);
      return n_fixed + static_cast<int>(free_nodes.size()) - 1;
    });
    SmoothInterior(cells, n_fixed, position, &free_nodes);
    out = SlitOutput(input, cells, crack_nodes, free_nodes, path, copy_of, position);
  });
  return out;
}

}  // namespace internal

}  // namespace epicycle::compliance
