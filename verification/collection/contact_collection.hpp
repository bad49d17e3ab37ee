// The contact problem collection (verification/data/contact/, docs/solvers.md): closed-form
// cases, seeded random SPD problems, gear-like problems sized like the paper's stage and
// stiff/extreme cases. Deterministic for a given seed (own uniform generator on std::mt19937_64).
// "Gear-like" means plausible magnitudes and structure only; no gear geometry is used.
// A test fixture (library epicycle_contact_collection, verification/collection/): the production
// libraries carry none. Written to files by generate_contact_collection.
#pragma once

#include <cstdint>
#include <vector>

#include "epicycle/solvers/contact_io.hpp"

namespace epicycle::solvers {

/// Every case of the collection; the closed-form ones carry their `expected` solution.
std::vector<ContactProblemFile> GenerateContactCollection(std::uint64_t seed);

/// Parameters of one gear-like problem: `planets` planets, each with a sun and a ring mesh, each
/// mesh with `drive_pairs` candidate tooth pairs on the loaded flank and `coast_pairs` on the
/// unloaded one (closed by the backlash); free members: sun rotation and translation, planet
/// rotations (m = planets + 3; carrier held, ring fixed).
struct GearLikeSpec {
  int planets = 3;
  int drive_pairs = 3;
  int coast_pairs = 2;
  double sun_torque = 600.0;      ///< [N·m]
  double runout = 20e-6;          ///< [m], on planet 1, projected on its lines of action
  double scatter = 3e-6;          ///< [m], uniform scatter of the drive-flank overlaps
  bool local = true;              ///< Hertzian local terms on every contact
  double support_stiffness = 0;  ///< [N/m] elastic sun bearing (0: sun translation free)
  std::uint64_t seed = 1;
};
ContactProblemFile MakeGearLikeProblem(const GearLikeSpec& spec, const std::string& name);

}  // namespace epicycle::solvers
