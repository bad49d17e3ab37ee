// The pieces of the FE reference's deck writer that the plane deck (fe_deck.cpp) and the 3D deck
// across the face width (fe3d_deck.cpp) share: the gmsh session, a gear's outline, the plane
// triangle mesh, the loaded tooth pairs, hub nodes and the flank faces of the contact surfaces.
// Private to verification/fe_reference (gmsh.h is included here).
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gmsh.h>

#include "fe_deck.hpp"

namespace epicycle::fe_reference::detail {

using geometry::Vec2;

// gmsh state is global: one session per deck, finalized even when an exception leaves.
struct GmshSession {
  GmshSession() {
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::add("pair");
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

// Which curves of a gear's outline carry which tooth flank.
struct GearModel {
  int surface = 0;
  int hub_curve = 0;
  // (tooth, side) → the curves of its involute and tip round (the loaded part of a flank).
  std::map<std::pair<int, int>, std::vector<int>> flank_curves;
  // (tooth, side) → the curves of its root land and fillet.
  std::map<std::pair<int, int>, std::vector<int>> fillet_curves;
  std::set<int> curves;
  int crack_curve = 0, crack_tip = 0;  // the crack's curve and its tip point (0: none)
  Vec2 tip_xy = Vec2::Zero();          // the tip [mm]
};

// The mesh-size rule of one gear near the mesh: h_tooth on the teeth within `zone` of a loaded
// tooth (and the rim under them, to 2 modules below the root circle), growing with the distance
// outside that zone.
struct ToothZone {
  Vec2 centre;  // [mm]
  double rotation = 0, pitch = 0, half_width = 0, r_in = 0, r_out = 0;
  std::vector<int> teeth;
  double Distance(double x, double y) const {
    const double dx = x - centre.x(), dy = y - centre.y();
    const double r = std::hypot(dx, dy);
    const double phi = std::atan2(dy, dx) - rotation;
    double ang = 1e300;
    for (int k : teeth)
      ang = std::min(ang, std::abs(geometry::WrapAngle(phi - k * pitch)) - half_width);
    const double radial = std::max({0.0, r_in - r, r - r_out});
    return std::max(std::max(0.0, ang * r), radial);
  }
};

struct Tri {
  std::array<int, 6> n;  // corners a, b, c, mid-sides ab, bc, ca (compact 0-based indices)
  int body = 0;
};

// The second-order triangle mesh of the two gears: gmsh's node tags → compact 0-based indices,
// the nodes' points [mm], the 6-node triangles counter-clockwise and each corner pair's
// (triangle, edge). The spline interpolation points are model vertices of their own, meshed as
// free nodes: left out.
struct DeckMesh {
  std::map<std::size_t, int> index;
  std::vector<Vec2> xy;
  std::vector<Tri> tris;
  std::map<std::pair<int, int>, std::pair<int, int>> edge_of;  // sorted corners → (tri, edge)
};

// The tooth pairs in or near contact on the loaded flanks (keyed by their teeth), their contact
// points [mm], the loaded teeth of each gear and the loaded sides.
struct LoadedContacts {
  std::map<std::pair<int, int>, FeToothPair> by_teeth;
  std::map<std::pair<int, int>, std::vector<Vec2>> points_of;  // each pair's contact points [mm]
  std::vector<Vec2> contact_points;                            // [mm]
  std::set<int> teeth1, teeth2;
  int side1 = 0, side2 = 0;
};

// The ToothZone of `gear` at `pose` around its `loaded` teeth (mesh.tooth_zone either side).
ToothZone MakeToothZone(const geometry::Gear& gear, const geometry::GearPose& pose,
                        const std::set<int>& loaded, const FeMeshOptions& mesh);
// gmsh's options for the plane mesh: sizes from the size callback only, Frontal-Delaunay,
// curved second-order elements.
void SetPlaneMeshOptions();

GearModel BuildGear(const geometry::Gear& gear, const geometry::GearPose& pose,
                    const std::set<int>& fine_teeth, int fine_points, const FeCrack* crack,
                    const FeSpall* spall, const std::vector<int>* sector);
LoadedContacts FindLoadedContacts(const geometry::GearPair& pair, const geometry::PairPoses& poses,
                                  const FeContactOptions& contact);
DeckMesh ReadDeckMesh(const GearModel& m1, const GearModel& m2);
int StraightenInvertedTriangles(DeckMesh& dm);
std::vector<int> HubNodes(const GearModel& g, const DeckMesh& dm);
void WriteNodeSet(std::ostream& f, const std::string& name, const std::vector<int>& ids);
std::vector<std::pair<int, int>> FlankFaces(const std::string& name, const std::vector<int>& curves,
                                            const std::vector<Vec2>& near, double reach,
                                            const DeckMesh& dm);

// Deck blocks shared by the plane and the 3D deck: material and contact pairs; a static step with
// gear 1's hub turned by θ [rad] (its *BOUNDARY block left open for more); the step's outputs and
// its end.
void WriteMaterialAndPairs(std::ostream& f, const transmission::Scene& scene,
                           const FeContactOptions& contact, const std::vector<FeToothPair>& pairs);
void WriteStepAndHubRotation(std::ostream& f, double theta, const FeDeckInfo& info);
void WriteStepOutputAndEnd(std::ostream& f, const FeDeckInfo& info, const char* more);

}  // namespace epicycle::fe_reference::detail
