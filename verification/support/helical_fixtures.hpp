// The helical paper stage's FE compliance with the slices' flank positions (helical_slices.hpp),
// built once per test process and shared by the tests of scenes with its gears
// (paper_stage_helical.toml and its copies with pins); the read-outs of a sliced state that
// those tests share.
#pragma once

#include <catch2/catch.hpp>

#include <memory>

#include "epicycle/transmission/face_width.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "fe_fixtures.hpp"

namespace epicycle::test {

inline const transmission::FeStageCompliance& HelicalCompliance(const transmission::Scene& scene,
                                                                const geometry::Stage& stage) {
  static std::unique_ptr<transmission::FeStageCompliance> c;
  if (!c) {
    transmission::FeComplianceOptions o = CachedTables();
    o.helical_slices = true;
    c = std::make_unique<transmission::FeStageCompliance>(scene, stage, o);
  }
  return *c;
}

/// The face load of planet `planet`'s (0-based) sun mesh or ring mesh in a sliced state.
inline const transmission::MeshFaceLoad& MeshLoad(const transmission::PositionResult& r, int planet,
                                                  bool ring) {
  for (const transmission::MeshFaceLoad& m : r.face_loads)
    if (m.planet == planet && m.ring_mesh == ring) return m;
  FAIL("no face load for the mesh");
  return r.face_loads.front();
}

/// Σ_s w_s z_s Δz: a mesh's force times its load centroid's z from the mid-plane, from its line
/// loads [N·m].
inline double FaceFirstMoment(const transmission::MeshFaceLoad& f) {
  const int slices = static_cast<int>(f.line_load.size());
  double first = 0;
  for (int s = 0; s < slices; ++s)
    first += f.line_load[static_cast<std::size_t>(s)] * f.width / slices *
             transmission::SliceCentre(s, slices, f.width);
  return first;
}

/// 1e-9 (the equilibrium residual) + 2 F_tip/ΣF: how far the tip-round contacts' forces F_tip
/// (levers in [0, r_b], off the lines of action) can move the sun meshes' axial forces relative
/// to their sum, the sun meshes carrying half of all contacts' forces ΣF.
inline double TipRoundShare(const transmission::PositionResult& r) {
  double all = 0, off_line = 0;
  for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
    const double f = r.solution.force(static_cast<Eigen::Index>(j));
    all += f;
    if (r.problem.contacts[j].contact.kind != geometry::ContactKind::kInvolute) off_line += f;
  }
  return 1e-9 + 2 * off_line / all;
}

}  // namespace epicycle::test
