// The helical pair's slices at the 3D helical deck's position (docs/fe_reference.md, "The helical
// deck"), shared by its crosscheck (crosscheck/transmission_helical_fe3d.cpp) and its figure
// (`fe_reference fe3d-helical`), with the committed runs' reader the [slow] ccx test
// (fe_reference/fe3d_helical_test.cpp) uses too: the
// mesh-stiffness driver's sample of the pair scene at gear-1 angle `angle_deg` (its slices of the
// face, each the transverse section turned by its lead, the local term per unit length of
// contact line, the scene's coupling along the face: docs/model.md §10, "Helical meshes in
// slices"), the line load per slice and the approach δ = |θ| r_b1 at the scene's torque.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "csv_rows.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::test {

/// The means of `stations` equal groups of consecutive values of `q` (its size a multiple).
inline std::vector<double> Pooled(const std::vector<double>& q, std::size_t stations) {
  if (stations == 0 || q.size() % stations != 0)
    throw std::invalid_argument("pooled stations: " + std::to_string(q.size()) + " values in " +
                                std::to_string(stations) + " stations");
  const std::size_t per = q.size() / stations;
  std::vector<double> out(stations, 0.0);
  for (std::size_t i = 0; i < q.size(); ++i) out[i / per] += q[i] / static_cast<double>(per);
  return out;
}

struct HelicalSliceSample {
  std::vector<double> line_load;  ///< w_s [N/m] per slice, z from the face z = −b/2
  double width = 0;               ///< b [m]
  double approach = 0;            ///< δ = |θ| r_b1 [m]
  double force = 0;               ///< Σ F_t [N]
  /// The means over `stations` equal stations [N/m] (the slices a multiple of them).
  std::vector<double> Stations(int stations) const {
    return Pooled(line_load, static_cast<std::size_t>(stations));
  }
};

/// The sample at `angle_deg`, a whole number of the sweep's steps: the driver's sweep of one mesh
/// cycle in `positions` positions hits it at k = angle/cycle × positions (checked within 1e-9).
/// @throws std::runtime_error when the angle is not a sample or the sample does not converge.
inline HelicalSliceSample HelicalSlicesAt(const transmission::Scene& scene,
                                          const transmission::FeComplianceOptions& tables,
                                          double angle_deg, int positions) {
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  transmission::FeComplianceOptions fe = tables;
  fe.helical_slices = transmission::IsHelical(scene);  // the driver's, stiffness_run.cpp
  const transmission::FePairCompliance compliance(scene, pair, fe);
  transmission::MeshStiffnessOptions o;
  o.positions = positions;
  o.threads = 1;
  const double k = angle_deg * geometry::kPi / 180.0 / pair.mesh_cycle() * positions;
  const int index = static_cast<int>(std::lround(k));
  if (std::abs(k - index) > 1e-9 || index < 0 || index >= positions)
    throw std::runtime_error("helical slices: " + std::to_string(angle_deg) +
                             " deg is not a position of a " + std::to_string(positions) +
                             "-position sweep");
  const transmission::MeshStiffnessResult r =
      transmission::ComputeMeshStiffness(setup, pair, compliance, o);
  const transmission::MeshSample& s = r.samples[static_cast<std::size_t>(index)];
  if (!s.converged) throw std::runtime_error("helical slices: " + s.message);
  HelicalSliceSample out;
  out.line_load = s.face_load.line_load;
  out.width = s.face_load.width;
  out.approach = s.approach;
  out.force = s.total_force;
  return out;
}

/// The committed 3D run of case `name` with `layers` layers at in-plane `refinement` of `csv`
/// (`fe_reference fe3d` rows: columns 0 case, 4 layers, 5 refinement, 20 mean k′, 26 line load):
/// its station loads [N/mm] and mean stiffness per unit width [N/(mm·µm)].
struct HelicalRun {
  std::vector<double> line_load;
  double mean_stiffness = 0;
};
inline HelicalRun CommittedRun(const std::string& csv, const std::string& name, int layers,
                               const std::string& refinement) {
  HelicalRun run;
  for (const auto& r : ReadCsvRows(csv)) {
    if (r.size() != 27 || r[0] != name || std::stoi(r[4]) != layers || r[5] != refinement) continue;
    run.line_load.push_back(std::stod(r[26]));
    run.mean_stiffness = std::stod(r[20]);
  }
  if (run.line_load.size() != static_cast<std::size_t>(layers))
    throw std::runtime_error(csv + ": " + std::to_string(run.line_load.size()) + " stations of " +
                             name + " at " + std::to_string(layers) + " layers, refinement " +
                             refinement);
  return run;
}

/// The largest |a_i − b_i|.
inline double LargestChange(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

/// The helical reference's `stations` station loads [N/mm] and the tolerance of a comparison
/// with them (docs/fe_reference.md, "The helical deck"): the reference is case `name` (whole
/// gears) at its finest axial level `layers`, in-plane refinement 1, pooled to the stations;
/// T = 2 (Δ_axial + Δ_plane) + Δ_slices, Δ_axial the largest change of a station from
/// layers/2 to `layers`, Δ_plane the largest change of a station from in-plane refinement 1 to
/// 1.41 at `plane_layers`, each doubled (the remaining error of a level bounded by its change
/// from the coarser one), and `slices` the slices' own discretisation (their change from S to 2S).
struct HelicalTolerance {
  double axial = 0, plane = 0, slices = 0;
  double total() const { return 2 * (axial + plane) + slices; }
};
struct HelicalReference {
  std::vector<double> line_load;  ///< the finest run's station loads [N/mm]
  HelicalTolerance tolerance;
};
inline HelicalReference ReferenceWithTolerance(const std::string& csv, const std::string& name,
                                               int layers, int plane_layers, std::size_t stations,
                                               double slices) {
  HelicalReference out;
  out.line_load = Pooled(CommittedRun(csv, name, layers, "1").line_load, stations);
  const std::vector<double> coarse =
      Pooled(CommittedRun(csv, name, layers / 2, "1").line_load, stations);
  const std::vector<double> plane1 =
      Pooled(CommittedRun(csv, name, plane_layers, "1").line_load, stations);
  const std::vector<double> plane141 =
      Pooled(CommittedRun(csv, name, plane_layers, "1.41").line_load, stations);
  out.tolerance = {LargestChange(coarse, out.line_load), LargestChange(plane1, plane141), slices};
  return out;
}

}  // namespace epicycle::test
