// The 3D deck across the face width (fe3d.hpp): the plane reference's outline and mesh (sector of
// teeth), extruded into layers of C3D15 wedges, one contact pair per layer.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "epicycle/io/number_format.hpp"
#include "fe3d.hpp"
#include "fe_deck_detail.hpp"
#include "epicycle/geometry/helical.hpp"
#include "epicycle/transmission/helical_slices.hpp"

namespace epicycle::fe_reference {

namespace {

using detail::Vec2;
using io::Num;

constexpr double kMm = 1e3;  // the deck is in mm, N, MPa

// The teeth of a sector: the loaded ones (consecutive in the cyclic order) and `extra` either
// side, in outline order; all of them when the sector would close on itself.
std::vector<int> SectorTeeth(const std::set<int>& loaded, int extra, int z) {
  int first = -1;
  for (int k : loaded)
    if (!loaded.count((k - 1 + z) % z)) first = k;
  const int count = static_cast<int>(loaded.size());
  if (first < 0 || count + 2 * extra >= z) return {};
  for (int i = 0; i < count; ++i)
    if (!loaded.count((first + i) % z))
      throw std::runtime_error("fe3d deck: the loaded teeth are not consecutive");
  std::vector<int> teeth;
  for (int i = -extra; i < count + extra; ++i) teeth.push_back(((first + i) % z + z) % z);
  return teeth;
}

// Node ids of the extruded mesh: level j = 0..2 N_z (even: layer faces, odd: mid-layer, corner
// nodes only) above plane node i: j·n2 + i + 1.
struct Extrusion {
  int n2 = 0, layers = 1;
  std::vector<char> corner;
  int Id(int level, int i) const { return level * n2 + i + 1; }
  template <class F>
  void Each(int i, F&& emit) const {
    for (int level = 0; level <= 2 * layers; ++level)
      if (level % 2 == 0 || corner[i]) emit(level, Id(level, i));
  }
};

// The helix of a deck (fe3d.hpp): the section at z [mm] from the z = 0 face is the mid-face
// section turned by each gear's SectionTurn(z − b/2) about its axis (docs/model.md §10, "Helical
// meshes in slices"); no turn for spur gears.
struct Sweep {
  const geometry::Gear* gear[2] = {nullptr, nullptr};
  Vec2 centre[2] = {Vec2::Zero(), Vec2::Zero()};  // the gears' axes [mm]
  double b_mm = 0;
  double Turn(int body, double z_mm) const {
    return geometry::SectionTurn(*gear[body], (z_mm - 0.5 * b_mm) / kMm);
  }
  // p [mm] of body `body`'s mid-face section carried to the section at z [mm]; `back` the
  // inverse.
  Vec2 At(int body, const Vec2& p, double z_mm, bool back = false) const {
    const double t = back ? -Turn(body, z_mm) : Turn(body, z_mm);
    return t == 0 ? p : Vec2(centre[body] + geometry::Rotate(p - centre[body], t));
  }
};

// The loaded contacts of a swept deck: the tooth pairs within the gap window in any of `samples`
// + 1 sections across the face, their rigid gap the smallest over the sections, and each
// section's contact point carried back to the mid-face section on either gear (points1_of on
// gear 1's flank, points2_of on gear 2's; lc.points_of and contact_points hold both). A spur
// deck: the plane search.
struct SweptContacts {
  detail::LoadedContacts lc;
  std::map<std::pair<int, int>, std::vector<Vec2>> points1_of, points2_of;
};

SweptContacts FindSweptContacts(const geometry::GearPair& pair, const geometry::PairPoses& poses,
                                const FeContactOptions& contact, const Sweep& sweep,
                                int samples) {
  SweptContacts out;
  const bool helical = pair.gear1().spec().helix.helical();
  if (!helical) {
    out.lc = detail::FindLoadedContacts(pair, poses, contact);
    out.points1_of = out.points2_of = out.lc.points_of;
    return out;
  }
  detail::LoadedContacts& lc = out.lc;
  for (int k = 0; k <= samples; ++k) {
    const double z = sweep.b_mm * k / samples;
    geometry::PairPoses section = poses;
    section.gear1.rotation += sweep.Turn(0, z);
    section.gear2.rotation += sweep.Turn(1, z);
    detail::LoadedContacts found;
    try {
      found = detail::FindLoadedContacts(pair, section, contact);
    } catch (const std::invalid_argument&) {
      continue;  // no tooth pair within the window in this section
    }
    for (const auto& [teeth, p] : found.by_teeth) {
      auto [it, fresh] = lc.by_teeth.try_emplace(teeth, p);
      if (!fresh) it->second.rigid_gap = std::min(it->second.rigid_gap, p.rigid_gap);
      for (const Vec2& q : found.points_of.at(teeth)) {
        out.points1_of[teeth].push_back(sweep.At(0, q, z, true));
        out.points2_of[teeth].push_back(sweep.At(1, q, z, true));
        for (const Vec2& r : {out.points1_of[teeth].back(), out.points2_of[teeth].back()}) {
          lc.contact_points.push_back(r);
          lc.points_of[teeth].push_back(r);
        }
      }
    }
    lc.teeth1.insert(found.teeth1.begin(), found.teeth1.end());
    lc.teeth2.insert(found.teeth2.begin(), found.teeth2.end());
    lc.side1 = found.side1;
    lc.side2 = found.side2;
  }
  if (lc.by_teeth.empty())
    throw std::invalid_argument("fe3d deck: no tooth pair within the gap window in any section");
  return out;
}

void WriteMesh(std::ostream& f, const detail::DeckMesh& dm, const Extrusion& ex,
               const std::vector<int>& body_of, const Sweep& sweep, Fe3dDeckInfo& info) {
  const double b_mm = sweep.b_mm;
  int nodes = 0;
  for (int i = 0; i < ex.n2; ++i)
    ex.Each(i, [&](int level, int id) {
      const double z = b_mm * level / (2.0 * ex.layers);
      const Vec2 p = sweep.At(body_of[static_cast<std::size_t>(i)], dm.xy[i], z);
      f << id << ", " << p.x() << ", " << p.y() << ", " << z << "\n";
      ++nodes;
    });
  const int ntri = static_cast<int>(dm.tris.size());
  for (int body = 0; body < 2; ++body) {
    f << "*ELEMENT, TYPE=C3D15, ELSET=GEAR" << body + 1 << "\n";
    for (int l = 0; l < ex.layers; ++l) {
      const int lo = 2 * l, mid = 2 * l + 1, hi = 2 * l + 2;
      for (int e = 0; e < ntri; ++e) {
        const detail::Tri& t = dm.tris[e];
        if (t.body != body) continue;
        const auto& n = t.n;
        f << l * ntri + e + 1 << ", " << ex.Id(lo, n[0]) << ", " << ex.Id(lo, n[1]) << ", "
          << ex.Id(lo, n[2]) << ", " << ex.Id(hi, n[0]) << ", " << ex.Id(hi, n[1]) << ", "
          << ex.Id(hi, n[2]) << ", " << ex.Id(lo, n[3]) << ", " << ex.Id(lo, n[4]) << ", "
          << ex.Id(lo, n[5]) << ",\n"
          << ex.Id(hi, n[3]) << ", " << ex.Id(hi, n[4]) << ", " << ex.Id(hi, n[5]) << ", "
          << ex.Id(mid, n[0]) << ", " << ex.Id(mid, n[1]) << ", " << ex.Id(mid, n[2]) << "\n";
      }
    }
  }
  info.deck.nodes = nodes;
  info.deck.elements = ntri * ex.layers;
}

// Gear 2's hub motion at a node (x, y relative to c_2, z) [mm]: the rigid rotation ψ about
// e_z × n through (c_2, b/2) (fe3d.hpp).
std::array<double, 3> Misalign(double psi, const Vec2& n, double x, double y, double z,
                               double b_mm) {
  const double dz = z - 0.5 * b_mm;
  return {psi * dz * n.x(), psi * dz * n.y(), -psi * (n.x() * x + n.y() * y)};
}

// The read point of gear `gear` (triangles of `body`) at p [mm]: the triangle around p, whose
// corners give p's barycentric coordinates (the triangles near the contact are straight-sided:
// their mid-side nodes at the edges' midpoints, checked), and its quadratic shape functions
// there, N_a = λ_a(2λ_a − 1) at the corners and 4 λ_a λ_b at the mid-sides.
Fe3dReadPoint ReadPointAt(const detail::DeckMesh& dm, const Extrusion& ex, int body, int gear,
                          const Vec2& p) {
  for (const detail::Tri& t : dm.tris) {
    if (t.body != body) continue;
    const Vec2 a = dm.xy[t.n[0]], b = dm.xy[t.n[1]], c = dm.xy[t.n[2]];
    const double det = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    const double l1 = ((p - a).x() * (c - a).y() - (p - a).y() * (c - a).x()) / det;
    const double l2 = ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x()) / det;
    const double l[3] = {1 - l1 - l2, l1, l2};
    if (l[0] < -1e-12 || l[1] < -1e-12 || l[2] < -1e-12) continue;
    for (int k = 0; k < 3; ++k) {
      const Vec2 mid = 0.5 * (dm.xy[t.n[k]] + dm.xy[t.n[(k + 1) % 3]]);
      if ((dm.xy[t.n[3 + k]] - mid).norm() > 1e-3 * (dm.xy[t.n[k]] - mid).norm())
        throw std::runtime_error("fe3d influence deck: the triangle around gear " +
                                 std::to_string(gear) + "'s read point is curved");
    }
    Fe3dReadPoint r;
    r.gear = gear;
    for (int k = 0; k < 3; ++k) r.weight.push_back(l[k] * (2 * l[k] - 1));
    for (int k = 0; k < 3; ++k) r.weight.push_back(4 * l[k] * l[(k + 1) % 3]);
    for (int k = 0; k < 6; ++k) {
      const int i = t.n[static_cast<std::size_t>(k)];
      r.corner.push_back(ex.corner[i] != 0);
      r.levels.emplace_back();
      for (int level = 0; level <= 2 * ex.layers; ++level)
        r.levels.back().push_back(level % 2 == 0 || ex.corner[i] ? ex.Id(level, i) : -1);
    }
    return r;
  }
  throw std::runtime_error("fe3d influence deck: gear " + std::to_string(gear) +
                           "'s read point (" + Num(p.x(), 6) + ", " + Num(p.y(), 6) +
                           ") mm lies in none of its triangles");
}

// The corner node of the flank faces nearest to `point` [mm].
int NearestCornerNode(const std::vector<std::pair<int, int>>& faces, const detail::DeckMesh& dm,
                      const Vec2& point) {
  int best = -1;
  for (const auto& [tri, edge] : faces)
    for (int k : {edge, (edge + 1) % 3}) {
      const int i = dm.tris[static_cast<std::size_t>(tri)].n[static_cast<std::size_t>(k)];
      if (best < 0 || (dm.xy[i] - point).norm() < (dm.xy[best] - point).norm()) best = i;
    }
  return best;
}

// The influence deck's model and steps (Fe3dOptions::influence): both hubs held, the read
// points at depth h below each gear's loaded node, and per layer l a step with the force pair
// −F n on gear 1's node and +F n on gear 2's, spread over the layer's quadratic edge (1/6, 4/6,
// 1/6 at its levels 2l, 2l + 1, 2l + 2: a uniform line load over the station).
void WriteInfluenceSteps(std::ostream& f, const transmission::Scene& scene,
                         const Fe3dOptions& options, const detail::DeckMesh& dm,
                         const Extrusion& ex, const detail::GearModel& m1,
                         const detail::GearModel& m2, const detail::LoadedContacts& lc,
                         const Vec2& normal, const Vec2& contact_point, Fe3dDeckInfo& info) {
  // The deck loads the tooth pair of the smallest rigid gap (the one the contact normal is
  // taken from); the others in the window are modelled, unloaded. An internal mesh keeps a
  // neighbouring pair within the window at every position (its flanks nearly conform).
  if (lc.by_teeth.empty())
    throw std::invalid_argument("fe3d influence deck: no tooth pair in the gap window");
  auto loaded = lc.by_teeth.begin();
  for (auto it = lc.by_teeth.begin(); it != lc.by_teeth.end(); ++it)
    if (it->second.rigid_gap < loaded->second.rigid_gap) loaded = it;
  const auto& [teeth, p] = *loaded;
  const std::vector<Vec2>& near = lc.points_of.at(teeth);
  const int node1 = NearestCornerNode(
      detail::FlankFaces(p.slave, m1.flank_curves.at({p.tooth1, lc.side1}), near,
                         options.contact.slave_reach * kMm, dm),
      dm, contact_point);
  const int node2 = NearestCornerNode(
      detail::FlankFaces(p.master, m2.flank_curves.at({p.tooth2, lc.side2}), near,
                         options.contact.master_reach * kMm, dm),
      dm, contact_point);
  info.normal_x = normal.x();
  info.normal_y = normal.y();
  info.influence_force = 1.0;  // [N] per station
  info.read_points = {
      ReadPointAt(dm, ex, 0, 1, dm.xy[node1] - options.read_depth[0] * kMm * normal),
      ReadPointAt(dm, ex, 1, 2, dm.xy[node2] + options.read_depth[1] * kMm * normal)};
  std::vector<int> read;
  for (const Fe3dReadPoint& r : info.read_points)
    for (const auto& ids : r.levels)
      for (int id : ids)
        if (id > 0) read.push_back(id);
  std::sort(read.begin(), read.end());
  read.erase(std::unique(read.begin(), read.end()), read.end());
  detail::WriteNodeSet(f, "READ", read);
  detail::WriteMaterialAndPairs(f, scene, options.contact, {});
  f << "*BOUNDARY\nHUB1, 1, 3\nHUB2, 1, 3\n";
  if (options.plane_strain) f << "NALL, 3, 3\n";
  const double force = info.influence_force;
  for (int l = 0; l < ex.layers; ++l) {
    f << "*STEP\n*STATIC\n*CLOAD, OP=NEW\n";
    for (const auto& [node, sign] : {std::pair{node1, -1.0}, std::pair{node2, 1.0}})
      for (int k = 0; k < 3; ++k) {
        const double share = k == 1 ? 4.0 / 6.0 : 1.0 / 6.0;
        const int id = ex.Id(2 * l + k, node);
        f << id << ", 1, " << Num(sign * share * force * normal.x(), 15) << "\n"
          << id << ", 2, " << Num(sign * share * force * normal.y(), 15) << "\n";
      }
    f << "*NODE PRINT, NSET=READ\nU\n*END STEP\n";
  }
}

// The deck's load: a finite non-zero torque, and at least one rotation step, all of one sign.
void CheckLoadSteps(double torque, const std::vector<double>& rotations) {
  if (rotations.empty())
    throw std::invalid_argument("fe3d deck: rotations: at least one step is needed");
  for (double r : rotations)
    if (!(r * rotations.front() > 0) || !std::isfinite(r))
      throw std::invalid_argument("fe3d deck: rotation = " + Num(r, 13) +
                                  ": every step's rotation must be non-zero and of one sign");
  if (!(torque != 0) || !std::isfinite(torque))
    throw std::invalid_argument("fe3d deck: torque = " + Num(torque, 13) +
                                " N m: must be finite and non-zero");
}

// Each gear's nodes inside its root circle, at the mid-face level (`kBodyMidPlane`) or at every
// level (`kBody`), the teeth and the fillets free: the sets BODY1, BODY2 held axially; with the
// hub's, AXIAL1, AXIAL2, the sets whose reactions are printed.
void WriteBodySets(std::ostream& f, const Sweep& sweep, const detail::DeckMesh& dm,
                   const Extrusion& ex, const std::vector<int>& body_of, AxialSupport support,
                   const std::vector<int>& hub1, const std::vector<int>& hub2) {
  std::vector<int> held[2] = {hub1, hub2};
  std::vector<int> mid[2];
  for (int i = 0; i < ex.n2; ++i) {
    const int g = body_of[static_cast<std::size_t>(i)];
    const geometry::Gear& gear = *sweep.gear[g];
    const double r = (dm.xy[i] - sweep.centre[g]).norm();
    const double r_f = gear.root_radius() * kMm;
    if (gear.internal() ? r > r_f * (1 + 1e-9) : r < r_f * (1 - 1e-9))
      ex.Each(i, [&](int level, int id) {
        if (level == ex.layers || support == AxialSupport::kBody) mid[g].push_back(id);
      });
  }
  for (int g = 0; g < 2; ++g) {
    detail::WriteNodeSet(f, "BODY" + std::to_string(g + 1), mid[g]);
    held[g].insert(held[g].end(), mid[g].begin(), mid[g].end());
    std::sort(held[g].begin(), held[g].end());
    held[g].erase(std::unique(held[g].begin(), held[g].end()), held[g].end());
    detail::WriteNodeSet(f, "AXIAL" + std::to_string(g + 1), held[g]);
  }
}

}  // namespace

FeMeshOptions Fe3dDefaultMesh() {
  FeMeshOptions m;
  m.contact_size = 200e-6;
  m.tooth_size_per_module = 0.5;
  m.body_size_per_module = 4.0;
  m.grading = 0.5;
  m.tooth_zone = 0;
  m.points_per_segment = 12;
  m.fillet_size_per_module = m.tooth_size_per_module;  // no fillet stress is read
  m.fillet_zone = 0;
  return m;
}

void Fe3dOptions::Validate() const {
  mesh.Validate();
  if (!(face_width >= 0) || !std::isfinite(face_width))
    throw std::invalid_argument("fe3d: face_width = " + Num(face_width, 13) +
                                " m: must be >= 0 (0: the pair's)");
  if (layers < 1 || layers > 200)
    throw std::invalid_argument("fe3d: layers = " + std::to_string(layers) +
                                ": must be in [1, 200]");
  if (!std::isfinite(misalignment) || std::abs(misalignment) > 1e-3)
    throw std::invalid_argument("fe3d: misalignment = " + Num(misalignment, 13) +
                                " m: must be finite and within ±1 mm");
  if (sector_teeth < 0)
    throw std::invalid_argument("fe3d: sector_teeth = " + std::to_string(sector_teeth) +
                                ": must be >= 0");
  if (plane_strain && misalignment != 0)
    throw std::invalid_argument("fe3d: plane_strain with misalignment = " + Num(misalignment, 13) +
                                " m: the plane-strain deck (u_z = 0) takes no misalignment");
  if (axial_support != AxialSupport::kHubs && (misalignment != 0 || influence))
    throw std::invalid_argument(
        "fe3d: axial_support of the bodies with " +
        (influence ? std::string("influence") : "misalignment = " + Num(misalignment, 13) + " m") +
        ": the bodies' mid-planes are held only in the aligned contact deck (gear 2's hub turns "
        "out of plane with a misalignment)");
  if (influence && misalignment != 0)
    throw std::invalid_argument("fe3d: influence with misalignment = " + Num(misalignment, 13) +
                                " m: the influence deck holds both hubs (no misalignment)");
  for (int g = 0; g < 2 && influence; ++g)
    if (!(read_depth[g] > 0) || !std::isfinite(read_depth[g]))
      throw std::invalid_argument("fe3d: read_depth of gear " + std::to_string(g + 1) + " = " +
                                  Num(read_depth[g], 13) + " m: must be > 0 with influence");
  if (!(contact.penalty > 0) || !(contact.gap_window > 0) || !(contact.slave_reach > 0) ||
      !(contact.master_reach > 0))
    throw std::invalid_argument(
        "fe3d: contact penalty, gap_window, slave_reach, master_reach: must be > 0");
}

void Fe3dDeckInfo::Write(const std::string& path) const {
  deck.Write(path + ".base");
  std::ofstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be written");
  f.precision(17);
  f << "misalignment_m " << misalignment << "\n";
  if (transverse_factor != 1) f << "transverse_factor " << transverse_factor << "\n";
  for (double z : z_edges) f << "z_edge_m " << z << "\n";
  for (int l : pair_layer) f << "pair_layer " << l << "\n";
  if (!read_points.empty())
    f << "normal " << normal_x << " " << normal_y << "\ninfluence_force_N " << influence_force
      << "\n";
  for (const Fe3dReadPoint& p : read_points)
    for (std::size_t k = 0; k < p.weight.size(); ++k) {
      f << "read " << p.gear << " " << p.weight[k] << " " << (p.corner[k] ? 1 : 0);
      for (int id : p.levels[k]) f << " " << id;
      f << "\n";
    }
  if (!f) throw std::runtime_error(path + ": write failed");
}

Fe3dDeckInfo Fe3dDeckInfo::Read(const std::string& path) {
  Fe3dDeckInfo info;
  info.deck = FeDeckInfo::Read(path + ".base");
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read");
  std::string line;
  for (int number = 1; std::getline(f, line); ++number) {
    std::istringstream s(line);
    std::string key;
    s >> key;
    bool ok = true;
    if (key == "misalignment_m") {
      ok = static_cast<bool>(s >> info.misalignment);
    } else if (key == "transverse_factor") {
      ok = static_cast<bool>(s >> info.transverse_factor) && info.transverse_factor > 0 &&
           info.transverse_factor <= 1;
    } else if (key == "z_edge_m") {
      double z = 0;
      ok = static_cast<bool>(s >> z);
      info.z_edges.push_back(z);
    } else if (key == "pair_layer") {
      int l = 0;
      ok = static_cast<bool>(s >> l);
      info.pair_layer.push_back(l);
    } else if (key == "normal") {
      ok = static_cast<bool>(s >> info.normal_x >> info.normal_y);
    } else if (key == "influence_force_N") {
      ok = static_cast<bool>(s >> info.influence_force);
    } else if (key == "read") {
      int gear = 0, corner = 0;
      double w = 0;
      ok = static_cast<bool>(s >> gear >> w >> corner) && (gear == 1 || gear == 2);
      if (ok) {
        if (info.read_points.empty() || info.read_points.back().gear != gear)
          info.read_points.push_back(Fe3dReadPoint{gear, {}, {}, {}});
        Fe3dReadPoint& p = info.read_points.back();
        p.weight.push_back(w);
        p.corner.push_back(corner != 0);
        p.levels.emplace_back();
        for (int id = 0; s >> id;) p.levels.back().push_back(id);
        ok = p.levels.back().size() == info.z_edges.size() * 2 - 1;
      }
    } else if (!key.empty()) {
      ok = false;
    }
    if (!ok)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": cannot read '" + line +
                               "'");
  }
  if (info.pair_layer.size() != info.deck.pairs.size() || info.z_edges.size() < 2)
    throw std::runtime_error(path + ": " + std::to_string(info.pair_layer.size()) +
                             " pair layers for " + std::to_string(info.deck.pairs.size()) +
                             " pairs, " + std::to_string(info.z_edges.size()) + " layer edges");
  return info;
}

Fe3dDeckInfo WriteDeck3d(const transmission::Scene& scene, const geometry::GearPair& pair,
                         double torque, double angle, const std::vector<double>& rotations,
                         const Fe3dOptions& options, const std::string& directory) {
  options.Validate();
  CheckLoadSteps(torque, rotations);
  const geometry::Gear& g1 = pair.gear1();
  const geometry::Gear& g2 = pair.gear2();
  const geometry::PairPoses poses = pair.Poses(angle);
  const FeMeshOptions& mesh = options.mesh;
  const double b = options.face_width > 0 ? options.face_width : geometry::ContactFaceWidth(g1, g2);
  const double b_mm = b * kMm;
  Sweep sweep;
  sweep.gear[0] = &g1;
  sweep.gear[1] = &g2;
  sweep.centre[0] = poses.gear1.geometric_centre * kMm;
  sweep.centre[1] = poses.gear2.geometric_centre * kMm;
  sweep.b_mm = b_mm;
  const bool helical = g1.spec().helix.helical();
  if (helical && options.influence)
    throw std::invalid_argument(
        "fe3d: influence on a helical pair: the influence deck reads one point per layer of an "
        "extruded tooth (spur pairs only)");
  // 64 sections: the contact moves b tan β_b along the line of action, 80 µm between samples on
  // the ISO 20/40 pair at 15°, within the 0.3 mm of the contact's fine zone.
  const SweptContacts swept = FindSweptContacts(pair, poses, options.contact, sweep, 64);
  const detail::LoadedContacts& lc = swept.lc;

  // The contact normal (gear 1 → gear 2) of the pair with the smallest rigid gap: the direction
  // of the line of action in which gear 2's axis turns.
  geometry::ContactSearchOptions search;
  search.gap_window = options.contact.gap_window;
  search.both_sides = false;
  search.side_a = pair.loaded_side();
  Vec2 normal = Vec2::Zero(), contact_point = Vec2::Zero();
  double best = -1e300;
  for (const geometry::PotentialContact& c : pair.Contacts(poses, search))
    if (c.overlap > best) best = c.overlap, normal = c.normal, contact_point = c.point * kMm;

  const double m = g1.module() * kMm;
  const double h_c = mesh.contact_size * kMm / mesh.refinement;
  const double r0 = mesh.contact_radius * kMm;
  const double h_tooth = mesh.tooth_size_per_module * m / mesh.refinement;
  const double h_body = mesh.body_size_per_module * m / mesh.refinement;
  const detail::ToothZone zone1 = detail::MakeToothZone(g1, poses.gear1, lc.teeth1, mesh);
  const detail::ToothZone zone2 = detail::MakeToothZone(g2, poses.gear2, lc.teeth2, mesh);
  const std::vector<int> sector1 = SectorTeeth(lc.teeth1, options.sector_teeth, g1.teeth());
  const std::vector<int> sector2 = SectorTeeth(lc.teeth2, options.sector_teeth, g2.teeth());
  auto all_of = [](const std::vector<int>& sector, int z) {
    std::set<int> s(sector.begin(), sector.end());
    for (int k = 0; s.empty() && k < z; ++k) s.insert(k);  // an empty sector: the whole gear
    return s;
  };

  detail::GmshSession session;
  const detail::GearModel m1 =
      detail::BuildGear(g1, poses.gear1, all_of(sector1, g1.teeth()), mesh.points_per_segment,
                        nullptr, nullptr, sector1.empty() ? nullptr : &sector1);
  const detail::GearModel m2 =
      detail::BuildGear(g2, poses.gear2, all_of(sector2, g2.teeth()), mesh.points_per_segment,
                        nullptr, nullptr, sector2.empty() ? nullptr : &sector2);
  gmsh::model::occ::synchronize();
  detail::SetPlaneMeshOptions();
  // Size: the smallest of the contact refinement, the tooth zone of the entity's gear and h_body
  // (the plane reference's rule without its fillet and crack terms).
  gmsh::model::mesh::setSizeCallback([&](int dim, int tag, double x, double y, double) {
    double s = h_body;
    for (const Vec2& c : lc.contact_points)
      s = std::min(s, h_c + mesh.grading * std::max(0.0, std::hypot(x - c.x(), y - c.y()) - r0));
    const bool on1 = (dim == 2 && tag == m1.surface) || (dim == 1 && m1.curves.count(tag));
    const bool on2 = (dim == 2 && tag == m2.surface) || (dim == 1 && m2.curves.count(tag));
    if (on1 || !on2) s = std::min(s, h_tooth + mesh.grading * zone1.Distance(x, y));
    if (on2 || !on1) s = std::min(s, h_tooth + mesh.grading * zone2.Distance(x, y));
    return s;
  });
  gmsh::model::mesh::generate(2);
  gmsh::model::mesh::setOrder(2);
  detail::DeckMesh dm = detail::ReadDeckMesh(m1, m2);
  const int straightened = detail::StraightenInvertedTriangles(dm);

  Extrusion ex;
  ex.n2 = static_cast<int>(dm.xy.size());
  ex.layers = options.layers;
  ex.corner.assign(ex.n2, 0);
  for (const detail::Tri& t : dm.tris)
    for (int j = 0; j < 3; ++j) ex.corner[t.n[j]] = 1;

  Fe3dDeckInfo info;
  FeDeckInfo& deck = info.deck;
  deck.thickness = b;  // the forces read are the whole face's
  deck.face_width = b;
  deck.torque = torque;
  deck.base_radius1 = g1.base_radius();
  deck.angle = angle;
  deck.rotations = rotations;
  deck.nodes_2d = ex.n2;
  deck.triangles = static_cast<int>(dm.tris.size());
  deck.straightened = straightened;
  info.misalignment = options.misalignment;
  info.transverse_factor = transmission::LocalWidthFactor(g1, g2);
  for (int l = 0; l <= options.layers; ++l) info.z_edges.push_back(b * l / options.layers);

  std::filesystem::create_directories(directory);
  const std::string deck_path = directory + "/deck.inp";
  std::ofstream f(deck_path);
  if (!f) throw std::runtime_error(deck_path + ": cannot be written");
  f.precision(13);
  f << "** epicycle FE contact reference across the face width (verification/fe_reference): "
    << scene.name << "\n** gear-1 angle " << Num(geometry::Deg(angle), 13) << " deg, torque "
    << Num(torque, 13) << " N m, b = " << Num(b_mm, 13) << " mm in " << options.layers
    << " layers, F_beta = " << Num(options.misalignment * 1e6, 13)
    << " um; units mm, N, MPa\n*NODE, NSET=NALL\n";
  std::vector<int> body_of(static_cast<std::size_t>(ex.n2), 0);
  for (const detail::Tri& t : dm.tris)
    for (int k : t.n) body_of[static_cast<std::size_t>(k)] = t.body;
  WriteMesh(f, dm, ex, body_of, sweep, info);

  const Vec2 c1 = poses.gear1.rotation_centre * kMm;
  const Vec2 c2 = poses.gear2.rotation_centre * kMm;
  for (int i : detail::HubNodes(m1, dm))
    ex.Each(i, [&](int level, int id) {
      const Vec2 p = sweep.At(0, dm.xy[i], b_mm * level / (2.0 * ex.layers));
      deck.hub_nodes.push_back(id);
      deck.hub_x.push_back(p.x() - c1.x());
      deck.hub_y.push_back(p.y() - c1.y());
    });
  detail::WriteNodeSet(f, "HUB1", deck.hub_nodes);
  struct HubNode {
    int id;
    double x, y, z;
  };
  std::vector<HubNode> hub2;
  std::vector<int> hub2_ids;
  for (int i : detail::HubNodes(m2, dm))
    ex.Each(i, [&](int level, int id) {
      const double z = b_mm * level / (2.0 * ex.layers);
      const Vec2 p = sweep.At(1, dm.xy[i], z);
      hub2.push_back({id, p.x() - c2.x(), p.y() - c2.y(), z});
      hub2_ids.push_back(id);
    });
  detail::WriteNodeSet(f, "HUB2", hub2_ids);
  const bool body_held = options.axial_support != AxialSupport::kHubs;
  if (body_held)
    WriteBodySets(f, sweep, dm, ex, body_of, options.axial_support, deck.hub_nodes, hub2_ids);

  if (options.influence) {
    WriteInfluenceSteps(f, scene, options, dm, ex, m1, m2, lc, normal, contact_point, info);
    if (!f) throw std::runtime_error(deck_path + ": write failed");
    f.close();
    info.Write(directory + "/deck3d.info");
    return info;
  }

  // Surfaces: gear 2's flank over every layer (master), gear 1's flank one slave per layer.
  const int ntri = static_cast<int>(dm.tris.size());
  for (const auto& [teeth, p] : lc.by_teeth) {
    const auto master = detail::FlankFaces(p.master, m2.flank_curves.at({p.tooth2, lc.side2}),
                                           swept.points2_of.at(teeth),
                                           options.contact.master_reach * kMm, dm);
    const auto slave = detail::FlankFaces(p.slave, m1.flank_curves.at({p.tooth1, lc.side1}),
                                          swept.points1_of.at(teeth),
                                          options.contact.slave_reach * kMm, dm);
    f << "*SURFACE, NAME=" << p.master << ", TYPE=ELEMENT\n";
    for (int l = 0; l < options.layers; ++l)
      for (const auto& [tri, edge] : master) f << l * ntri + tri + 1 << ", S" << edge + 3 << "\n";
    for (int l = 0; l < options.layers; ++l) {
      FeToothPair layer = p;
      layer.slave = p.slave + "Z" + std::to_string(l);
      f << "*SURFACE, NAME=" << layer.slave << ", TYPE=ELEMENT\n";
      for (const auto& [tri, edge] : slave) f << l * ntri + tri + 1 << ", S" << edge + 3 << "\n";
      deck.pairs.push_back(layer);
      info.pair_layer.push_back(l);
    }
  }

  detail::WriteMaterialAndPairs(f, scene, options.contact, deck.pairs);
  // Hubs: gear 1 axially held; gear 2 held (plane strain: u_z = 0 everywhere) or turned by ψ.
  f << "*BOUNDARY\n" << (options.plane_strain ? "NALL" : "HUB1") << ", 3, 3\n";
  if (options.misalignment == 0) f << "HUB2, 1, 3\n";
  if (body_held) f << "BODY1, 3, 3\nBODY2, 3, 3\n";
  const double psi = options.misalignment * kMm / b_mm;
  for (double theta : rotations) {
    detail::WriteStepAndHubRotation(f, theta, deck);
    if (options.misalignment != 0)
      for (const HubNode& h : hub2) {
        const auto u = Misalign(psi, normal, h.x, h.y, h.z, b_mm);
        for (int d = 0; d < 3; ++d)
          f << h.id << ", " << d + 1 << ", " << d + 1 << ", " << Num(u[d], 13) << "\n";
      }
    detail::WriteStepOutputAndEnd(f, deck,
                                  body_held ? "*NODE PRINT, NSET=AXIAL1, TOTALS=ONLY\nRF\n*NODE "
                                              "PRINT, NSET=AXIAL2, TOTALS=ONLY\nRF\n"
                                            : "");
  }
  if (!f) throw std::runtime_error(deck_path + ": write failed");
  f.close();
  info.Write(directory + "/deck3d.info");
  return info;
}

}  // namespace epicycle::fe_reference
