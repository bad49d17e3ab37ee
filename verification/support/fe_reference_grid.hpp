// The hybrid model at the positions of the FE contact reference (tools/fe_reference.sh,
// docs/fe_reference.md): its mesh-stiffness grid and which of its positions
// are tip positions (a loaded pair touches through a tip round there or one grid step away).
#pragma once

#include "epicycle/transmission/mesh_stiffness.hpp"

namespace epicycle::test {

constexpr int kFeReferenceGrid = 48;  // tools/fe_reference.sh's default grid

inline transmission::MeshStiffnessResult FeReferenceSweep(
    const transmission::MeshPairSetup& setup, const geometry::GearPair& pair,
    const transmission::FePairCompliance& compliance) {
  transmission::MeshStiffnessOptions o;
  o.positions = kFeReferenceGrid;
  return transmission::ComputeMeshStiffness(setup, pair, compliance, o);
}

inline bool TipPosition(const transmission::MeshStiffnessResult& r, int index) {
  const int n = static_cast<int>(r.samples.size());
  for (int i = index - 1; i <= index + 1; ++i)
    for (const auto& p : r.samples.at(static_cast<std::size_t>((i + n) % n)).pairs)
      if (p.kind != geometry::ContactKind::kInvolute) return true;
  return false;
}

}  // namespace epicycle::test
