#include "epicycle/compliance/cracked_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "epicycle/compliance/gmsh_mesher.hpp"
#include "epicycle/io/number_format.hpp"
#include "slit_mesh.hpp"

namespace epicycle::compliance {
namespace {

using io::Num;

// One interval of the sector's boundary loop: its first corner and its mid-side node (global ids,
// or −1 for a node made here), with positions, and the names of the sets the interval belongs to.
struct LoopInterval {
  int corner = -1, mid = -1;
  Eigen::Vector2d corner_x, mid_x;
  std::vector<std::string> names;
};

std::pair<int, int> Key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

}  // namespace

void CrackMeshOptions::Validate() const {
  auto fail = [](const std::string& field, const std::string& value, const std::string& rule) {
    throw std::invalid_argument("CrackMeshOptions." + field + " = " + value + ": " + rule);
  };
  if (crack_elements < 2 || crack_elements > 200)
    fail("crack_elements", std::to_string(crack_elements), "must be in [2, 200]");
  if (!(tip_grading >= 1.0 && tip_grading <= 100.0))
    fail("tip_grading", Num(tip_grading, 9), "must be in [1, 100]");
  if (!(max_element > 0.0 && max_element <= 1.0))
    fail("max_element", Num(max_element, 9), "must be in (0, 1] modules");
}

namespace {

// The sector's elements: centroid within ±π/z of the tooth's centre line (`rot` turns tooth 0
// onto the cracked tooth, `hp` = π/z).
std::vector<char> SectorElements(const Mesh& mesh, const Eigen::Matrix2d& rot, double hp) {
  std::vector<char> in_sector(static_cast<std::size_t>(mesh.num_elements()), 0);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (int a = 0; a < 4; ++a) c += 0.25 * mesh.nodes[mesh.elements[e][a]];
    const Eigen::Vector2d q = rot.transpose() * c;
    in_sector[e] = std::abs(std::atan2(q.y(), q.x())) < hp ? 1 : 0;
  }
  return in_sector;
}

// The sector's boundary: the element sides used once within it, counter-clockwise (the sector on
// the left), chained into one loop, each interval with the edge sets it belongs to.
std::vector<LoopInterval> SectorLoop(const Mesh& mesh, const std::vector<char>& in_sector,
                                     const std::string& who) {
  std::map<std::pair<int, int>, int> uses;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (!in_sector[e]) continue;
    for (const auto& side : kQ8Sides)
      ++uses[Key(mesh.elements[e][side[0]], mesh.elements[e][side[2]])];
  }
  std::map<int, std::pair<int, int>> next;  // corner → (mid, next corner)
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (!in_sector[e]) continue;
    for (const auto& side : kQ8Sides) {
      const int a = mesh.elements[e][side[0]], m = mesh.elements[e][side[1]],
                b = mesh.elements[e][side[2]];
      if (uses[Key(a, b)] == 1) next[a] = {m, b};
    }
  }
  std::map<std::pair<int, int>, std::vector<std::string>> names;
  for (const auto& [name, edges] : mesh.edge_sets) {
    for (const BoundaryEdge& edge : edges) {
      if (in_sector[edge.element]) names[Key(edge.nodes[0], edge.nodes[2])].push_back(name);
    }
  }
  std::vector<LoopInterval> loop;
  const int start = next.begin()->first;
  int a = start;
  do {
    const auto it = next.find(a);
    if (it == next.end() || loop.size() > next.size())
      throw std::invalid_argument(who + "the cracked tooth's sector has no closed boundary");
    LoopInterval li;
    li.corner = a;
    li.mid = it->second.first;
    li.corner_x = mesh.nodes[a];
    li.mid_x = mesh.nodes[li.mid];
    const auto n = names.find(Key(a, it->second.second));
    if (n != names.end()) li.names = n->second;
    loop.push_back(li);
    a = it->second.second;
  } while (a != start);
  if (loop.size() != next.size())
    throw std::invalid_argument(who + "the cracked tooth's sector boundary is not one loop");
  return loop;
}

// The mouth: splits the fillet interval of `loop` that holds it (in profile arc length of tooth
// 0's σ = +1 side) into two, or three to keep the interval count even. Returns the index of the
// loop interval that starts at the mouth.
int SplitAtMouth(const geometry::Gear& gear, const RootCrack& crack, const Eigen::Matrix2d& rot,
                 const std::string& who, std::vector<LoopInterval>& loop) {
  const ProfilePath path(gear);
  const double s_form = path.RoleStart(geometry::SegmentRole::kInvolute);
  const double sigma = crack.side > 0 ? 1.0 : -1.0;
  auto arc_of = [&](const Eigen::Vector2d& x) {
    Eigen::Vector2d q = rot.transpose() * x;
    q.y() *= sigma;
    return path.Project(q, 0.0, s_form);
  };
  auto point_at = [&](double s) {
    Eigen::Vector2d q = path.Point(s);
    q.y() *= sigma;
    return Eigen::Vector2d(rot * q);
  };
  const std::string fillet_set =
      "fillet" + std::to_string(crack.tooth) + (crack.side > 0 ? "+" : "-");
  int mouth_interval = -1;
  double sa = 0, sb = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    if (std::find(loop[i].names.begin(), loop[i].names.end(), fillet_set) == loop[i].names.end())
      continue;
    const double s0 = arc_of(loop[i].corner_x);
    const double s1 = arc_of(loop[(i + 1) % loop.size()].corner_x);
    if (crack.start_arc >= std::min(s0, s1) && crack.start_arc <= std::max(s0, s1)) {
      mouth_interval = static_cast<int>(i);
      sa = s0;
      sb = s1;
      break;
    }
  }
  if (mouth_interval < 0)
    throw std::invalid_argument(
        who + "no interval of set '" + fillet_set +
        "' holds the crack's start (start_arc = " + Num(crack.start_arc, 9) + " m)");
  std::vector<double> cuts = {crack.start_arc};
  if (loop.size() % 2 == 0) {  // three pieces: also cut the longer part in its middle
    const double far = std::abs(sb - crack.start_arc) > std::abs(crack.start_arc - sa) ? sb : sa;
    cuts.push_back(0.5 * (crack.start_arc + far));
  }
  // Cuts ordered from sa to sb.
  std::sort(cuts.begin(), cuts.end(),
            [&](double x, double y) { return std::abs(x - sa) < std::abs(y - sa); });
  std::vector<LoopInterval> pieces;
  {
    const LoopInterval& old = loop[static_cast<std::size_t>(mouth_interval)];
    std::vector<double> s = {sa};
    s.insert(s.end(), cuts.begin(), cuts.end());
    s.push_back(sb);
    for (std::size_t p = 0; p + 1 < s.size(); ++p) {
      LoopInterval li;
      li.corner = p == 0 ? old.corner : -1;
      li.corner_x = p == 0 ? old.corner_x : point_at(s[p]);
      li.mid_x = point_at(0.5 * (s[p] + s[p + 1]));
      li.names = old.names;
      pieces.push_back(li);
    }
  }
  const int mouth_piece =
      1 + static_cast<int>(std::find(cuts.begin(), cuts.end(), crack.start_arc) - cuts.begin());
  loop.erase(loop.begin() + mouth_interval);
  loop.insert(loop.begin() + mouth_interval, pieces.begin(), pieces.end());
  return mouth_interval + mouth_piece;
}

// The crack's points after the mouth, as distances along its path [m] from 0 (the mouth) to the
// depth: crack_elements (or more, for max_element) intervals in geometric progression toward the
// tip, the polyline's vertices (`at_vertex`, their distances) among them.
std::vector<double> CrackStations(const geometry::Gear& gear, const std::vector<double>& at_vertex,
                                  const GearMeshOptions& options,
                                  const CrackMeshOptions& crack_options) {
  const double depth = at_vertex.back();
  const int refinement = options.refinement;
  int n = crack_options.crack_elements * refinement;
  const double ratio_total = 1.0 / crack_options.tip_grading;  // last over first
  auto first_size = [&](int count) {
    if (count == 1) return depth;
    const double r = std::pow(ratio_total, 1.0 / (count - 1));
    return r == 1.0 ? depth / count : depth * (1.0 - r) / (1.0 - std::pow(r, count));
  };
  while (first_size(n) > crack_options.max_element * gear.module() / refinement && n < 2000) ++n;
  std::vector<double> ell = {0.0};
  {
    const double r = n > 1 ? std::pow(ratio_total, 1.0 / (n - 1)) : 1.0;
    double h = first_size(n);
    for (int i = 0; i < n; ++i, h *= r) ell.push_back(ell.back() + h);
    ell.back() = depth;
  }
  for (std::size_t v = 1; v + 1 < at_vertex.size(); ++v) {
    auto it = std::min_element(ell.begin() + 1, ell.end() - 1, [&](double x, double y) {
      return std::abs(x - at_vertex[v]) < std::abs(y - at_vertex[v]);
    });
    if (std::find(at_vertex.begin(), at_vertex.end(), *it) != at_vertex.end()) {
      ell.push_back(at_vertex[v]);
    } else {
      *it = at_vertex[v];
    }
    std::sort(ell.begin(), ell.end());
  }
  return ell;
}

// The healthy mesh with its sector replaced by the slit mesh: the healthy nodes, then the new
// ones; the elements outside the sector, then the sector's; unused nodes (the sector's old
// interior) dropped. Sets are not carried yet.
struct Assembly {
  Mesh out;
  std::vector<int> local_to_old;  // slit mesh node → node of the healthy mesh + new nodes
  std::vector<int> renumber;      // that node → node of `out` (−1: dropped)
  std::vector<int> element_map;   // healthy element → element of `out` (−1: in the sector)
  int first_new = 0;              // the first of the sector's elements in `out`
  int global(int local) const { return renumber[local_to_old[local]]; }
};

Assembly Assemble(const Mesh& mesh, const std::vector<char>& in_sector,
                  const std::vector<LoopInterval>& loop, const internal::SlitInput& input,
                  const internal::SlitMesh& slit) {
  Assembly a;
  const int n_loop = static_cast<int>(input.loop.size());
  std::vector<Eigen::Vector2d> nodes = mesh.nodes;
  a.local_to_old.assign(static_cast<std::size_t>(n_loop) + slit.interior.size(), -1);
  for (int i = 0; i < n_loop; ++i) {
    const LoopInterval& li = loop[static_cast<std::size_t>(i / 2)];
    const int id = i % 2 == 0 ? li.corner : li.mid;
    if (id >= 0) {
      a.local_to_old[i] = id;
    } else {
      a.local_to_old[i] = static_cast<int>(nodes.size());
      nodes.push_back(input.loop[i]);
    }
  }
  for (std::size_t k = 0; k < slit.interior.size(); ++k) {
    a.local_to_old[n_loop + k] = static_cast<int>(nodes.size());
    nodes.push_back(slit.interior[k]);
  }
  std::vector<std::array<int, kQ8Nodes>> elements;
  a.element_map.assign(static_cast<std::size_t>(mesh.num_elements()), -1);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (in_sector[e]) continue;
    a.element_map[e] = static_cast<int>(elements.size());
    elements.push_back(mesh.elements[e]);
  }
  a.first_new = static_cast<int>(elements.size());
  for (const auto& el : slit.elements) {
    std::array<int, kQ8Nodes> g{};
    for (int k = 0; k < kQ8Nodes; ++k) g[k] = a.local_to_old[el[k]];
    elements.push_back(g);
  }
  a.renumber.assign(nodes.size(), -1);
  for (auto& el : elements) {
    for (int& v : el) {
      if (a.renumber[v] < 0) {
        a.renumber[v] = static_cast<int>(a.out.nodes.size());
        a.out.nodes.push_back(nodes[v]);
      }
      v = a.renumber[v];
    }
  }
  a.out.elements = std::move(elements);
  return a;
}

// The sides of the sector's new elements by their corners: the boundary edge a side is.
class NewSides {
 public:
  NewSides(const Mesh& out, int first_new) : out_(out) {
    for (int e = first_new; e < out.num_elements(); ++e) {
      for (int q = 0; q < 4; ++q) {
        const auto& side = kQ8Sides[q];
        owner_[Key(out.elements[e][side[0]], out.elements[e][side[2]])] = {e, q};
      }
    }
  }
  std::optional<BoundaryEdge> Find(int a, int b) const {
    const auto it = owner_.find(Key(a, b));
    if (it == owner_.end()) return std::nullopt;
    const auto& side = kQ8Sides[it->second.second];
    const auto& el = out_.elements[it->second.first];
    return BoundaryEdge{{el[side[0]], el[side[1]], el[side[2]]}, it->second.first};
  }

 private:
  const Mesh& out_;
  std::map<std::pair<int, int>, std::pair<int, int>> owner_;  // → (element, local side)
};

// The sets of the healthy mesh carried onto the assembly. Node sets keep their surviving nodes;
// the fillet set of the crack's side gains the new fillet nodes (both copies of the mouth); the
// sector's new elements form "crack_sector" and its boundary intervals keep their edge sets.
void CarrySets(const Mesh& mesh, const std::vector<char>& in_sector,
               const std::vector<LoopInterval>& loop, const internal::SlitInput& input,
               const internal::SlitMesh& slit, const NewSides& sides, const std::string& who,
               Assembly& a) {
  Mesh& out = a.out;
  const int num_elements = out.num_elements();
  const int n_loop = static_cast<int>(input.loop.size());
  for (const auto& [name, list] : mesh.node_sets) {
    std::vector<int>& set = out.node_sets[name];
    for (int v : list)
      if (a.renumber[v] >= 0) set.push_back(a.renumber[v]);
  }
  for (const auto& [name, list] : mesh.element_sets) {
    std::vector<int>& set = out.element_sets[name];
    for (int e : list)
      if (a.element_map[e] >= 0) set.push_back(a.element_map[e]);
  }
  for (int e = a.first_new; e < num_elements; ++e) out.element_sets["crack_sector"].push_back(e);
  for (const auto& [name, edges] : mesh.edge_sets) {
    std::vector<BoundaryEdge>& set = out.edge_sets[name];
    for (const BoundaryEdge& edge : edges) {
      if (in_sector[edge.element]) continue;
      set.push_back(BoundaryEdge{
          {a.renumber[edge.nodes[0]], a.renumber[edge.nodes[1]], a.renumber[edge.nodes[2]]},
          a.element_map[edge.element]});
    }
  }
  const int mouth_copy = slit.right.front();  // = the mouth with a closed seam
  for (int i = 0; i < n_loop / 2; ++i) {
    const LoopInterval& li = loop[static_cast<std::size_t>(i)];
    if (li.names.empty()) continue;
    int p = 2 * i, q = (2 * i + 2) % n_loop;
    std::optional<BoundaryEdge> edge = sides.Find(a.global(p), a.global(q));
    if (!edge && (p == input.mouth || q == input.mouth)) {  // the interval next to the copy
      if (p == input.mouth) p = mouth_copy;
      if (q == input.mouth) q = mouth_copy;
      edge = sides.Find(a.global(p), a.global(q));
    }
    if (!edge)
      throw std::invalid_argument(who + "boundary interval " + std::to_string(i) +
                                  " is no side of the cracked sector's mesh");
    for (const std::string& name : li.names) {
      out.edge_sets[name].push_back(*edge);
      std::vector<int>& set = out.node_sets[name];
      for (int v : edge->nodes)
        if (std::find(set.begin(), set.end(), v) == set.end()) set.push_back(v);
    }
  }
}

// The crack's faces: which is on the tip's side, their nodes in `result` and their node and edge
// sets "crack_tip_side" and "crack_root_side" in the assembly.
void CrackFaces(const geometry::Gear& gear, const Eigen::Matrix2d& rot,
                const std::vector<Eigen::Vector2d>& vertex, const internal::SlitMesh& slit,
                const NewSides& sides, Assembly& a, CrackedBodyMesh& result) {
  const Eigen::Vector2d d = (vertex[1] - vertex[0]).normalized();
  const Eigen::Vector2d left(-d.y(), d.x());
  const Eigen::Vector2d e_r = (gear.internal() ? -1.0 : 1.0) * (rot * Eigen::Vector2d::UnitX());
  const bool tip_is_left = left.dot(e_r) > 0.0;
  auto face = [&](const std::vector<int>& corners, const std::vector<int>& mids,
                  std::vector<int>* c, std::vector<int>* m, const std::string& name) {
    for (int v : corners) c->push_back(a.global(v));
    for (int v : mids) m->push_back(a.global(v));
    std::vector<int>& set = a.out.node_sets[name];
    for (std::size_t k = 0; k < c->size(); ++k) {
      set.push_back((*c)[k]);
      if (k < m->size()) set.push_back((*m)[k]);
    }
    for (std::size_t k = 0; k + 1 < c->size(); ++k) {
      // The face's own element (with a closed seam, one of the two that share the side).
      const std::optional<BoundaryEdge> edge = sides.Find((*c)[k], (*c)[k + 1]);
      if (edge) a.out.edge_sets[name].push_back(*edge);
    }
  };
  const auto& tip_c = tip_is_left ? slit.left : slit.right;
  const auto& tip_m = tip_is_left ? slit.left_mid : slit.right_mid;
  const auto& root_c = tip_is_left ? slit.right : slit.left;
  const auto& root_m = tip_is_left ? slit.right_mid : slit.left_mid;
  face(tip_c, tip_m, &result.tip_side, &result.tip_side_mid, "crack_tip_side");
  face(root_c, root_m, &result.root_side, &result.root_side_mid, "crack_root_side");
  result.opening_normal = tip_is_left ? left : Eigen::Vector2d(-left);
  result.sector_elements = a.out.num_elements() - a.first_new;
}

// The assembly is a valid mesh and conforms, checked with the seam closed (the faces' copies are
// on each other's free sides by construction). @throws std::invalid_argument if not.
void CheckCrackedMesh(const Assembly& a, const internal::SlitMesh& slit, const std::string& who) {
  try {
    a.out.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(who + e.what());
  }
  Mesh closed_seam = a.out;
  {
    std::map<int, int> to_left;
    auto close = [&](const std::vector<int>& p, const std::vector<int>& q) {
      for (std::size_t k = 0; k < p.size(); ++k) {
        const int x = a.global(p[k]), y = a.global(q[k]);
        if (x != y) to_left[y] = x;
      }
    };
    close(slit.left, slit.right);
    close(slit.left_mid, slit.right_mid);
    for (auto& el : closed_seam.elements)
      for (int& v : el)
        if (const auto it = to_left.find(v); it != to_left.end()) v = it->second;
  }
  if (const auto h = FindHangingNode(closed_seam)) {
    throw std::invalid_argument(who + "non-conforming join: node " + std::to_string(h->node) +
                                " lies inside a free side of element " +
                                std::to_string(h->element));
  }
}

}  // namespace

CrackedBodyMesh BuildCrackedGearMesh(const geometry::Gear& gear, const RootCrack& crack,
                                     const GearMeshOptions& options,
                                     const CrackMeshOptions& crack_options) {
  crack.Validate(gear);
  options.Validate();
  crack_options.Validate();
  const std::string who = "cracked body mesh of '" + gear.name() + "': ";
  if (!GmshMesher::Available()) {
    throw std::invalid_argument(
        who +
        "a root crack is meshed by gmsh, and this build has none (configured with "
        "EPICYCLE_WITH_GMSH=OFF); reconfigure with -DEPICYCLE_WITH_GMSH=ON");
  }
  GearBodyMesh healthy = BuildGearMesh(gear, options);
  const Mesh& mesh = healthy.mesh;
  const double hp = gear.pitch_angle() / 2.0;
  const Eigen::Matrix2d rot =
      Eigen::Rotation2Dd(crack.tooth * gear.pitch_angle()).toRotationMatrix();

  const std::vector<char> in_sector = SectorElements(mesh, rot, hp);
  std::vector<LoopInterval> loop = SectorLoop(mesh, in_sector, who);
  const int mouth_index = SplitAtMouth(gear, crack, rot, who, loop);

  // The slit polygon: the sector's loop, the mouth exactly at the crack's start, and the crack's
  // points after it.
  const std::vector<Eigen::Vector2d> vertex = crack.Points(gear);
  std::vector<double> at_vertex = {0.0};
  for (const CrackSegment& seg : crack.path) at_vertex.push_back(at_vertex.back() + seg.length);
  const std::vector<double> ell = CrackStations(gear, at_vertex, options, crack_options);
  auto on_path = [&](double l) {
    std::size_t s = 0;
    while (s + 2 < at_vertex.size() && l > at_vertex[s + 1]) ++s;
    const double t = (l - at_vertex[s]) / (at_vertex[s + 1] - at_vertex[s]);
    return Eigen::Vector2d(vertex[s] + t * (vertex[s + 1] - vertex[s]));
  };
  internal::SlitInput input;
  for (const LoopInterval& li : loop) {
    input.loop.push_back(li.corner_x);
    input.loop.push_back(li.mid_x);
  }
  input.mouth = 2 * mouth_index;
  input.loop[input.mouth] = vertex[0];  // exactly the crack's start
  for (std::size_t i = 1; i < ell.size(); ++i) input.crack.push_back(on_path(ell[i]));
  input.crack.back() = vertex.back();
  input.open = crack_options.open;
  internal::SlitMesh slit;
  try {
    slit = internal::MeshSlitPolygon(input);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(who + "the cracked tooth's sector: " + e.what());
  }

  Assembly a = Assemble(mesh, in_sector, loop, input, slit);
  const NewSides sides(a.out, a.first_new);
  CarrySets(mesh, in_sector, loop, input, slit, sides, who, a);
  CrackedBodyMesh result;
  CrackFaces(gear, rot, vertex, slit, sides, a, result);
  CheckCrackedMesh(a, slit, who);

  // Grid nodes renumbered (the flank grid's nodes are loop nodes: kept).
  for (auto& tooth : healthy.grid_nodes)
    for (auto& flank : tooth)
      for (int& v : flank) v = a.renumber[v];
  result.body.min_jacobian_ratio = MinJacobianRatio(a.out);
  result.body.mesh = std::move(a.out);
  result.body.grid = std::move(healthy.grid);
  result.body.teeth = healthy.teeth;
  result.body.grid_nodes = std::move(healthy.grid_nodes);
  return result;
}

}  // namespace epicycle::compliance
