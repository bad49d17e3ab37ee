// The helical 3D deck's geometry (docs/fe_reference.md, "The helical deck"), no ccx needed: the
// ISO 20/40 pair at β = 15°, b = 10 mm (verification/data/fe_reference/
// iso_pair_20_40_helical_b10.toml), gear-1 angle 13°, 4 layers.
//  - Every node of gear 1's loaded flank (tooth 19) lies on the closed-form involute helicoid at
//    its level z. Closed form: the transverse section at z' = z − b/2 of a right-hand flank is the
//    mid-face involute turned by z' tan β_b / r_b (the lead p_z = 2π r_b / tan β_b), with
//    tan β_b = tan β cos α_t, tan α_t = tan α_n / cos β (ISO 21771), computed here from the
//    scene's β and α_n, not from the deck's turn. A point at radius r on that involute has the
//    polar angle S + H(u − atan u), u = √(r²/r_b² − 1); a point's normal distance from it is
//    r_b Δφ (the normal is tangent to the base circle). The flank's nodes at mid-face are those
//    within 10 µm of the involute (the mesh's elements there are 200 µm: no interior node is that
//    close); at every level they must be within the mid-face's own distance (gmsh's spline through
//    12 points per profile segment: 37 nm at most, bounded by kSpline = 0.1 µm) plus the deck's printing (13 digits of
//    coordinates below 100 mm: 1e-11 mm), tolerance 1e-9 mm on the difference.
//  - The deck's rigid gaps: tooth pair 19/21 touches in every section; the neighbours are more
//    than 40 µm away (the single-contact position of docs/fe_reference.md).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "epicycle/geometry/contact.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "fe3d.hpp"

using namespace epicycle;

namespace {

constexpr double kSpline = 1e-4;  // the plane mesh's flank nodes off the involute [mm], bound

transmission::Scene HelicalScene() {
  std::ifstream in(std::string(EPICYCLE_TEST_DATA_DIR) +
                   "/fe_reference/iso_pair_20_40_helical_b10.toml");
  std::ostringstream text;
  text << in.rdbuf();
  return transmission::ParseScene(text.str(), "iso_pair_20_40_helical_b10.toml");
}

// deck.inp's nodes, id → (x, y, z) [mm], and the ids of gear 1's elements' nodes (ELSET=GEAR1:
// a C3D15 on two lines, the first starting with the element's id and ending with a comma).
struct DeckNodes {
  std::map<int, std::array<double, 3>> xyz;
  std::set<int> gear1;
};
DeckNodes ReadNodes(const std::string& path) {
  std::ifstream f(path);
  DeckNodes nodes;
  std::string line;
  enum { kOther, kNodes, kGear1 } block = kOther;
  bool continued = false;
  while (std::getline(f, line)) {
    if (!line.empty() && line[0] == '*') {
      block = line.rfind("*NODE", 0) == 0                      ? kNodes
              : line.find("ELSET=GEAR1") != std::string::npos ? kGear1
                                                               : kOther;
      continued = false;
      continue;
    }
    const bool ends_with_comma = !line.empty() && line.back() == ',';
    for (char& c : line)
      if (c == ',') c = ' ';
    std::istringstream s(line);
    if (block == kNodes) {
      int id = 0;
      std::array<double, 3> p{};
      if (s >> id >> p[0] >> p[1] >> p[2]) nodes.xyz[id] = p;
    } else if (block == kGear1) {
      int id = 0;
      if (!continued) s >> id;  // the element's id
      while (s >> id) nodes.gear1.insert(id);
      continued = ends_with_comma;
    }
  }
  return nodes;
}

}  // namespace

TEST_CASE("3D FE reference: the helical deck's flank nodes on the closed-form involute helicoid",
          "[unit][fe3d]") {
  const transmission::Scene scene = HelicalScene();
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  const double angle = 13.0 * geometry::kPi / 180.0;
  const std::string dir =
      (std::filesystem::temp_directory_path() / "epicycle_fe3d_helical_deck").string();
  std::filesystem::remove_all(dir);
  fe_reference::Fe3dOptions o;
  o.layers = 4;
  const fe_reference::Fe3dDeckInfo info =
      fe_reference::WriteDeck3d(scene, pair, setup.torque, angle, {1e-4, 2e-4}, o, dir);

  // Rigid gaps: 19/21 touching, the neighbours beyond 40 µm.
  int touching = 0;
  for (const auto& p : info.deck.pairs) {
    if (p.tooth1 == 19 && p.tooth2 == 21) {
      CHECK(std::abs(p.rigid_gap) < 1e-9);
      ++touching;
    } else {
      CHECK(p.rigid_gap > 40e-6);
    }
  }
  CHECK(touching == o.layers);

  // The closed form (header), in mm.
  const double beta = 15.0 * geometry::kPi / 180.0, alpha_n = 20.0 * geometry::kPi / 180.0;
  const double alpha_t = std::atan(std::tan(alpha_n) / std::cos(beta));
  const double tan_beta_b = std::tan(beta) * std::cos(alpha_t);
  const geometry::PairPoses poses = pair.Poses(angle);
  const geometry::WorldInvolute flank =
      geometry::FlankInWorld(pair.A(poses), 19, pair.loaded_side());
  const double rb = flank.base_radius * 1e3, b = 10.0;
  const double cx = flank.centre.x() * 1e3, cy = flank.centre.y() * 1e3;
  // The right-hand gear 1's section at z' turns by +z' tan β_b / r_b.
  auto distance = [&](const std::array<double, 3>& p) {
    const double r = std::hypot(p[0] - cx, p[1] - cy);
    const double u = std::sqrt(std::max(0.0, r * r / (rb * rb) - 1));
    const double start = flank.start + (p[2] - 0.5 * b) * tan_beta_b / rb;
    const double phi = start + flank.hand * (u - std::atan(u));
    return rb * geometry::WrapAngle(std::atan2(p[1] - cy, p[0] - cx) - phi);
  };
  const DeckNodes deck = ReadNodes(dir + "/deck.inp");
  const auto& nodes = deck.xyz;
  const int n2 = info.deck.nodes_2d, levels = 2 * o.layers + 1, mid = o.layers;
  const double r_lo = rb * std::sqrt(1 + flank.u_min * flank.u_min);
  const double r_hi = rb * std::sqrt(1 + flank.u_max * flank.u_max);
  int flank_nodes = 0;
  double worst_mid = 0, worst_change = 0;
  for (int i = 0; i < n2; ++i) {
    const auto it = nodes.find(mid * n2 + i + 1);  // level N_z: z = b/2, every node has it
    REQUIRE(it != nodes.end());
    if (!deck.gear1.count(it->first)) continue;  // gear 2's flank touches at the contact line
    const double r = std::hypot(it->second[0] - cx, it->second[1] - cy);
    if (r < r_lo || r > r_hi) continue;
    const double d_mid = distance(it->second);
    if (std::abs(d_mid) > 10e-3) continue;
    ++flank_nodes;

    worst_mid = std::max(worst_mid, std::abs(d_mid));
    for (int level = 0; level < levels; ++level) {
      const auto at = nodes.find(level * n2 + i + 1);
      if (at == nodes.end()) continue;  // a mid-side node has no mid-layer level
      CHECK(std::abs(at->second[2] - b * level / (levels - 1)) < 1e-9);
      worst_change = std::max(worst_change, std::abs(distance(at->second) - d_mid));
    }
  }
  INFO(flank_nodes << " flank nodes, " << worst_mid * 1e3 << " um off the involute at mid-face, "
                   << worst_change * 1e6 << " nm change over the levels");
  CHECK(flank_nodes >= 20);
  CHECK(worst_mid <= kSpline);
  CHECK(worst_change <= 1e-9);
  std::filesystem::remove_all(dir);
}

TEST_CASE("3D FE reference: the bodies held axially are the nodes inside the root circles",
          "[unit][fe3d]") {
  // Fe3dOptions::axial_support (docs/fe_reference.md, "The helical deck"): kBodyMidPlane holds
  // u_z at the mid-face level z = b/2 of every node inside each gear's root circle r_f (ISO
  // 53 rack: r_f = m_t z/2 − 1.25 m_n), kBody at every level; the teeth are free.
  const transmission::Scene scene = HelicalScene();
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  const double angle = 13.0 * geometry::kPi / 180.0;
  const geometry::PairPoses poses = pair.Poses(angle);
  const double beta = 15.0 * geometry::kPi / 180.0, m_n = 4.0, b = 10.0;  // mm
  const double r_f[2] = {20 * m_n / std::cos(beta) / 2 - 1.25 * m_n,
                         40 * m_n / std::cos(beta) / 2 - 1.25 * m_n};
  const geometry::Vec2 centre[2] = {poses.gear1.geometric_centre * 1e3,
                                    poses.gear2.geometric_centre * 1e3};
  for (const auto support :
       {fe_reference::AxialSupport::kBodyMidPlane, fe_reference::AxialSupport::kBody}) {
    const std::string dir =
        (std::filesystem::temp_directory_path() / "epicycle_fe3d_helical_held").string();
    std::filesystem::remove_all(dir);
    fe_reference::Fe3dOptions o;
    o.layers = 2;
    o.sector_teeth = 20;
    o.axial_support = support;
    fe_reference::WriteDeck3d(scene, pair, setup.torque, angle, {1e-4, 2e-4}, o, dir);
    const DeckNodes deck = ReadNodes(dir + "/deck.inp");
    // The sets BODY1, BODY2 (ten ids a line) and the boundary lines that hold them.
    std::map<std::string, std::vector<int>> sets;
    std::ifstream f(dir + "/deck.inp");
    std::string line, set;
    bool held[2] = {false, false};
    while (std::getline(f, line)) {
      if (line == "BODY1, 3, 3") held[0] = true;
      if (line == "BODY2, 3, 3") held[1] = true;
      if (line.rfind("*", 0) == 0) {
        set = line.rfind("*NSET, NSET=BODY", 0) == 0 ? line.substr(12) : "";
        continue;
      }
      if (set.empty()) continue;
      for (char& c : line)
        if (c == ',') c = ' ';
      std::istringstream s(line);
      for (int id = 0; s >> id;) sets[set].push_back(id);
    }
    CHECK(held[0]);
    CHECK(held[1]);
    for (int g = 0; g < 2; ++g) {
      const std::vector<int>& ids = sets["BODY" + std::to_string(g + 1)];
      CHECK(ids.size() > 100);
      double r_max = 0, z_min = 1e9, z_max = -1e9;
      for (int id : ids) {
        const auto& p = deck.xyz.at(id);
        CHECK(deck.gear1.count(id) == (g == 0 ? 1u : 0u));
        r_max = std::max(r_max, std::hypot(p[0] - centre[g].x(), p[1] - centre[g].y()));
        z_min = std::min(z_min, p[2]);
        z_max = std::max(z_max, p[2]);
      }
      INFO("gear " << g + 1 << ": " << ids.size() << " held nodes, r up to " << r_max << " mm (r_f "
                   << r_f[g] << " mm), z in [" << z_min << ", " << z_max << "]");
      CHECK(r_max < r_f[g]);
      // The nodes reach the root circle within the body's element size near it (m/2 = 2 mm).
      CHECK(r_max > r_f[g] - 2.0);
      if (support == fe_reference::AxialSupport::kBodyMidPlane) {
        CHECK(z_min == Approx(b / 2).margin(1e-9));
        CHECK(z_max == Approx(b / 2).margin(1e-9));
      } else {
        CHECK(z_min == Approx(0).margin(1e-9));
        CHECK(z_max == Approx(b).margin(1e-9));
      }
    }
    std::filesystem::remove_all(dir);
  }
}
