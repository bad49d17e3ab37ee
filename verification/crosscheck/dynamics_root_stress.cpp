// Root stresses in the dynamic driver (docs/model.md §9, docs/stresses.md) against the
// quasi-static driver at low speed: the dynamic root stress tends to the quasi-static one with the
// speed, as the load sharing does.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "figures.hpp"

using namespace epicycle;

TEST_CASE("root stress: the dynamic root stress tends to the quasi-static one with the speed",
          "[crosscheck][slow][dynamics][stress]") {
  // The setting and the argument of the load-sharing test "quasi-static limit" (dynamics_model):
  // FE compliance without the local term, friction off, planet 1 with 20 µm run-out, sun fixed,
  // one planet revolution relative to the carrier (24 mesh cycles, 2 outputs each), rtol 1e-8.
  // The root stress is linear in the contact forces (with their damping), so what separates the
  // dynamic from the quasi-static stress are the same velocity and inertial terms: halving the
  // speed must at least halve the gap (ratio ≥ 2/1.25), down to the tolerances' floor (relative
  // 1e-6 of the stresses).
  double gap[2], largest = 0;
  const double speeds[2] = {120.0, 60.0};
  for (int k = 0; k < 2; ++k) {
    const auto rig = test::LowSpeedRunoutRig(speeds[k], "[model]\nstresses = true\n");
    REQUIRE(rig.compliance->has_root_stress());
    dynamics::SimulationOptions so;
    so.rtol = 1e-8;
    const auto r = test::Run(rig, test::Times(*rig.model, *rig.stage, 24, 2), so);
    REQUIRE(r.completed());
    const int bodies = transmission::PlanetBody(rig.stage->planets());
    gap[k] = 0;
    for (const dynamics::DynamicSample& s : r.samples) {
      REQUIRE_FALSE(s.fillet_stress.empty());
      const auto q = transmission::SolvePosition(*rig.stage_model, s.carrier_angle, rig.scene.loads,
                                                 transmission::QuasiStaticOptions{});
      REQUIRE(q.converged);
      const auto dyn = transmission::SummariseRootStress(s.fillet_stress, bodies);
      const auto qs = transmission::SummariseRootStress(q.fillet_stress, bodies);
      for (int b = 0; b < bodies; ++b) {
        gap[k] = std::max({gap[k], std::abs(dyn[b].tension - qs[b].tension),
                           std::abs(dyn[b].compression - qs[b].compression)});
        largest = std::max(largest, qs[b].tension);
      }
    }
    test::Figure("root stress, quasi-static limit at " + std::to_string(speeds[k]) +
                 " rpm: largest |sigma - sigma_qs| " + test::Sci(gap[k] / 1e6) + " MPa");
  }
  CHECK(largest > 1e8);  // the run-out case's planet 1 carries ~350 MPa
  const double floor = 1e-6 * largest;
  const bool pass = gap[1] <= gap[0] / 2 * 1.25 + floor;
  test::VerifyRow("dynamic root stress -> quasi-static linearly in speed (120, 60 rpm; run-out)",
                  "quasi-static solver at the same carrier angles",
                  "largest gap " + test::Sci(gap[0] / 1e6) + " MPa at 120 rpm, " +
                      test::Sci(gap[1] / 1e6) + " MPa at 60 rpm",
                  "ratio " + test::Sci(gap[0] / gap[1], 2), "ratio >= 2/1.25 (1e-6 floor)", pass);
  CHECK(pass);
}
