// The helical pair's slices at the 3D helical deck's position (docs/fe_reference.md, "The helical
// deck"), shared by its crosscheck (crosscheck/transmission_helical_fe3d.cpp), its [slow] ccx
// test (fe_reference/fe3d_helical_test.cpp) and its figure (`fe_reference fe3d-helical`): the
// mesh-stiffness driver's sample of the pair scene at gear-1 angle `angle_deg` (its slices of the
// face, each the transverse section turned by its lead, the local term per unit length of
// contact line, the scene's coupling along the face: docs/model.md §10, "Helical meshes in
// slices"), the line load per slice and the approach δ = |θ| r_b1 at the scene's torque.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::test {

struct HelicalSliceSample {
  std::vector<double> line_load;  ///< w_s [N/m] per slice, z from the face z = −b/2
  double width = 0;               ///< b [m]
  double approach = 0;            ///< δ = |θ| r_b1 [m]
  double force = 0;               ///< Σ F_t [N]
  /// The means over `stations` equal stations [N/m] (the slices a multiple of them).
  std::vector<double> Stations(int stations) const {
    const std::size_t per = line_load.size() / static_cast<std::size_t>(stations);
    if (per * static_cast<std::size_t>(stations) != line_load.size())
      throw std::invalid_argument("helical slices: " + std::to_string(line_load.size()) +
                                  " slices in " + std::to_string(stations) + " stations");
    std::vector<double> out(static_cast<std::size_t>(stations), 0.0);
    for (std::size_t s = 0; s < line_load.size(); ++s)
      out[s / per] += line_load[s] / static_cast<double>(per);
    return out;
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
  const transmission::FePairCompliance compliance(scene, pair, tables);
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

}  // namespace epicycle::test
