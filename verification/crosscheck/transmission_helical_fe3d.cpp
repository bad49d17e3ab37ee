// The helical pair's slices against the 3D full-FE contact reference of the same pair
// (docs/fe_reference.md, "The helical deck"; its rows in
// verification/data/fe_reference/iso_pair_20_40_helical_face_load.csv, written by `fe_reference
// fe3d` as the docs say): the ISO 20/40 pair at β = 15° on b = 10 mm
// (verification/data/fe_reference/iso_pair_20_40_helical_b10.toml), gear-1 angle 13°, one tooth
// pair carrying the whole face (its contact line crosses it, 2.5 mm along the line of action).
// The model: the mesh-stiffness driver's sample there (verification/support/fe3d_helical.hpp),
// 20 slices with the scene's coupling (none), the local term per unit length of contact line.
// The quantity: the load per unit length of contact line at four stations across the face, the
// means of 2.5 mm (the 3D layers' F_l cos β_b/Δz, the slices' F_t,s/Δz; the same number, fe3d.hpp).
//
// The reference: whole gears (both bodies' every tooth: a sector's free cut faces would let the
// helical mesh's axial force bend it out of plane, docs/fe_reference.md), 4 layers, in-plane
// refinement 1. Tolerance, from the reference's own convergence and the slices' discretisation
// (fe3d_helical.hpp, ReferenceTolerance): T = 2 (Δ_axial + Δ_plane) + Δ_slices, Δ_axial the
// largest change of a 5 mm mean from 2 to 4 layers, Δ_plane the largest change of a station from
// in-plane refinement 1 to 1.41 (on the sector deck, the same mesh rule at the contact), each
// doubled (the remaining error of a level bounded by its change from the coarser one), Δ_slices
// the largest change of a station's mean from 20 to 40 slices.
//
// Not met, measured (hence [!shouldfail]): T = 2 (0.74 + 4.44) + 0.0001 = 10.4 N/mm; the 3D
// stations 247.0, 270.2, 277.8, 273.9 N/mm, the slices 266.3, 267.3, 267.6, 267.4: the first
// station (from z = 0) differs by 19.3 N/mm, the others
// by 2.9, 10.2 and 6.5. The slices miss the 3D line's unloading of that end: each slice is the
// plane model at its own point of the path, which varies by < 1 % over the 2.5 mm the line
// spans; what the 3D tooth adds (its twisted end, the load's spread along the inclined line) is
// not in them. The pair is also 35 % softer in 3D (k′ 8.79 against 13.48 N/(mm·µm)),
// docs/fe_reference.md.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "csv_rows.hpp"
#include "fe3d_helical.hpp"
#include "fe_fixtures.hpp"

using namespace epicycle;

namespace {

constexpr int kStations = 4;

std::string Csv() {
  return std::string(EPICYCLE_TEST_DATA_DIR) + "/fe_reference/iso_pair_20_40_helical_face_load.csv";
}

// The slices' station means [N/mm] with `slices` slices.
std::vector<double> Model(int slices) {
  transmission::Scene scene = transmission::ReadScene(
      std::string(EPICYCLE_TEST_DATA_DIR) + "/fe_reference/iso_pair_20_40_helical_b10.toml");
  scene.face_width.slices = slices;
  const test::HelicalSliceSample s = test::HelicalSlicesAt(scene, test::CachedTables(), 13.0, 18);
  std::vector<double> q = s.Stations(kStations);
  for (double& v : q) v /= 1e3;
  return q;
}

}  // namespace

TEST_CASE(
    "helical pair: the load per unit length of contact line of the slices against the 3D "
    "full-FE reference",
    "[crosscheck][transmission][helical][!shouldfail]") {
  const std::vector<double> reference = test::CommittedRun(Csv(), "helical", 4, "1").line_load;
  const std::vector<double> model = Model(20);
  const test::HelicalTolerance t = test::ReferenceTolerance(Csv(), test::LargestChange(model, Model(40)));
  const double tolerance = t.total();
  for (int i = 0; i < kStations; ++i) {
    INFO("station " << i << ": 3D " << reference[i] << " N/mm, slices " << model[i]
                    << " N/mm; tolerance " << tolerance << " N/mm (axial " << t.axial
                    << ", in-plane " << t.plane << ", slices " << t.slices << ")");
    CHECK(std::abs(model[i] - reference[i]) <= tolerance);
  }
}
