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
// The reference: whole gears held as the slices' plane sections are, axially at mid-face inside
// the root circles (case `helical_held`; held at the hubs alone, the 10 mm discs bend under the
// mesh's axial force and tilt the sections: docs/fe_reference.md), 8 layers, in-plane refinement
// 1, pooled to the four stations. Tolerance, from the reference's own convergence and the slices'
// discretisation (fe3d_helical.hpp, ReferenceWithTolerance): T = 2 (Δ_axial + Δ_plane) +
// Δ_slices, Δ_axial the largest change of a station from 4 to 8 layers, Δ_plane the largest
// change of a station from in-plane refinement 1 to 1.41 at 4 layers, each doubled (the remaining
// error of a level bounded by its change from the coarser one), Δ_slices the largest change of a
// station's mean from 20 to 40 slices.
//
// Measured (met, a weak check: T is 9.7 % of the mean line load): Δ_axial 3.6, Δ_plane 9.3 N/mm
// (the line load concentrates toward the middle as the plane mesh refines), Δ_slices 1e-4;
// T = 2 (3.6 + 9.3) + 0.0001 = 25.9 N/mm. The 8-layer stations 264.4, 276.4, 270.7, 257.3 N/mm,
// the slices 266.3, 267.3, 267.6, 267.4: 1.9, 9.1, 3.1, 10.1 apart; the refinement-1.41 run
// (263.7, 277.2, 277.4, 250.7) 2.6, 9.9, 9.8, 16.7 apart. The slices (uncoupled strips) stay
// flat within 0.5 %; the 3D line unloads the face's ends, most at z = b.
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
    "[crosscheck][transmission][helical]") {
  const std::vector<double> model = Model(20);
  const test::HelicalReference ref = test::ReferenceWithTolerance(
      Csv(), "helical_held", 8, 4, kStations, test::LargestChange(model, Model(40)));
  const test::HelicalTolerance& t = ref.tolerance;
  for (int i = 0; i < kStations; ++i) {
    INFO("station " << i << ": 3D " << ref.line_load[i] << " N/mm, slices " << model[i]
                    << " N/mm; tolerance " << t.total() << " N/mm (axial " << t.axial
                    << ", in-plane " << t.plane << ", slices " << t.slices << ")");
    CHECK(std::abs(model[i] - ref.line_load[i]) <= t.total());
  }
  // The finer in-plane level (4 layers, refinement 1.41) is a reference as good by the same rule:
  // the converged line lies within T of it too.
  const std::vector<double> fine = test::CommittedRun(Csv(), "helical_held", 4, "1.41").line_load;
  for (int i = 0; i < kStations; ++i) {
    INFO("station " << i << ": 3D at refinement 1.41 " << fine[i] << " N/mm, slices " << model[i]
                    << " N/mm; tolerance " << t.total() << " N/mm");
    CHECK(std::abs(model[i] - fine[i]) <= t.total());
  }
}
