// The helical paper stage with a pin error (scenes/paper_stage_helical_pin_error.toml: planet 1's
// pin hole 20 µm off tangentially, straddle pins; docs/face_width.md, "Helical meshes"): over a
// mesh cycle, each planet's tilting moment against the hand calculation from its own sun- and
// ring-mesh axial forces and the levers of the scene's geometry; the sun's axial force against
// the sun torque whatever the sharing; K_γ against the spur paper stage's with the same pin error;
// K_Hβ with the tilt's feedback (straddle pins) and without it (pins rigid in tilt), the feedback
// moving the load along the face the way the tilt's kinematics says.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "fe_fixtures.hpp"
#include "helical_fixtures.hpp"

using namespace epicycle;
using transmission::PositionResult;

namespace {

// 12 positions over one mesh cycle (as `epicycle quasistatic --positions 12`): 1.3 s of solving
// per run on the helical stage.
constexpr int kPositions = 12;

const char* const kPinError =
    "\n[[errors.pin]]\ngear = \"planet1\"\nradial_um = 0.0\ntangential_um = 20.0\n";

// The scene without its [[face_width.pin]] table: the pins rigid in tilt (`--rigid-pins`).
std::string WithoutPins(const std::string& text) {
  const std::size_t pin = text.find("\n[[face_width.pin]]");
  const std::size_t error = text.find("\n[[errors.pin]]");  // tables at a line's start
  REQUIRE(pin < error);
  return text.substr(0, pin) + text.substr(error);
}

struct Sweep {
  transmission::Scene scene;
  geometry::Stage stage;
  std::vector<PositionResult> results;
  transmission::SweepSummary summary;
  Sweep(const std::string& text, const std::string& name, bool helical)
      : scene(transmission::ParseScene(text, name)), stage(scene.stage) {
    const transmission::FeStageCompliance& c =
        helical ? test::HelicalCompliance(scene, stage) : test::Compliance("paper_stage.toml");
    const transmission::StageModel model(stage, c, transmission::SetupFromScene(scene));
    const double span = transmission::CarrierSpan(stage, transmission::RunRange::kMeshCycle);
    for (int k = 0; k < kPositions; ++k) {
      results.push_back(transmission::SolvePosition(model, k * span / kPositions, scene.loads,
                                                    transmission::QuasiStaticOptions{}));
      INFO(name << " position " << k << ": " << results.back().message);
      REQUIRE(results.back().converged);
    }
    summary = transmission::SummariseSweep(results, 3);
  }
};

}  // namespace

TEST_CASE(
    "helical paper stage with a pin error: tilting moments from the axial forces, K_gamma "
    "against the spur stage's, K_Hbeta with and without the tilt's feedback",
    "[crosscheck][transmission][helical][pin]") {
  const std::string text = test::SceneText("paper_stage_helical_pin_error.toml");
  const Sweep on(text, "paper_stage_helical_pin_error.toml", true);
  const Sweep off(WithoutPins(text), "paper_stage_helical_pin_error.toml", true);
  const Sweep spur(test::SceneText("paper_stage.toml") + kPinError, "paper_stage.toml", false);

  // The levers from the scene's numbers alone: both meshes' centre distance is the carrier radius
  // a (the ring's fixed), so the planet's operating pitch radii are r_w,p|s = a z_p/(z_s + z_p)
  // in the sun mesh and r_w,p|r = a z_p/(z_r − z_p) in the ring mesh: 52.029 and 50.760 mm.
  const geometry::StageSpec& spec = on.scene.stage;
  const double a = spec.carrier_radius;
  const double z_s = spec.sun.teeth, z_p = spec.planet.teeth, z_r = spec.ring.teeth;
  const double arm_sun = a * z_p / (z_s + z_p), arm_ring = a * z_p / (z_r - z_p);
  CHECK(arm_sun + arm_ring == Approx(102.789e-3).epsilon(1e-5));
  // Base helix: tan β_b = tan β cos α_t (ISO 21771), the sun's base radius r_b = r cos α_t.
  const double tan_bb =
      std::tan(on.stage.sun().spec().helix.angle) * std::cos(on.stage.sun().spec().pressure_angle);
  const double r_b_sun = on.stage.sun().base_radius();
  const double torque = std::abs(on.scene.loads.sun_torque);
  const double p_bt = 2 * std::numbers::pi * r_b_sun / z_s;

  for (const Sweep* run : {&on, &off}) {
    for (std::size_t k = 0; k < run->results.size(); ++k) {
      const PositionResult& r = run->results[k];
      const transmission::HelicalLoads& h = r.helical;
      REQUIRE(h.planets.size() == 3);
      // The planets' sun meshes carry the sun torque however they share it: Σ_i F_a,i = the
      // sun's |T_s| tan β_b / r_b,sun. A tip-round contact's lever lies in [0, r_b]: the forces on
      // such contacts move the sum by at most their share of the sun meshes' load (2 F_tip/ΣF,
      // half of all forces being the ring meshes'), and the equilibrium residual 1e-9.
      const double share = test::TipRoundShare(r);
      double sun_meshes = 0;
      for (const transmission::PlanetHelicalLoad& p : h.planets) sun_meshes += p.sun_mesh_axial;
      CHECK(std::abs(sun_meshes) == Approx(torque * tan_bb / r_b_sun).epsilon(share));

      for (int i = 0; i < 3; ++i) {
        const transmission::PlanetHelicalLoad& p = h.planets[static_cast<std::size_t>(i)];
        // Hand calculation: the sun mesh's axial force F_a,s acts at the sun-side pitch point,
        // r_w,p|s inward of the planet's centre, the ring mesh's F_a,r at the ring-side one,
        // r_w,p|r outward, both on the line of centres. With (e_r, e_t, e_z) right-handed, a force
        // F e_z at ρ e_r has the moment −ρ F e_t: M_t = r_w,p|s F_a,s − r_w,p|r F_a,r.
        const double hand = arm_sun * p.sun_mesh_axial - arm_ring * p.ring_mesh_axial;
        // Tolerance: each mesh's contacts lie on its line of action within the path of contact
        // g_α = ε_α p_bt of the pitch point, radially g_α sin α_wt: the moment differs from the
        // pitch points' by at most Σ_meshes |F_a| g_α sin α_wt; the solver's equilibrium
        // residual (1e-9 relative) adds 1e-9 |M|.
        double bound = 1e-9 * std::abs(hand);
        for (const int m : {2 * i, 2 * i + 1}) {
          const geometry::MeshSummary& s = on.stage.meshes()[static_cast<std::size_t>(m)];
          const double f_a = m % 2 == 0 ? p.sun_mesh_axial : p.ring_mesh_axial;
          bound += std::abs(f_a) * s.contact_ratio_iso * p_bt * std::sin(s.pressure_angle);
        }
        INFO((run == &on ? "pins" : "rigid")
             << ", position " << k << ", planet " << i + 1 << ": axial forces " << p.sun_mesh_axial
             << " / " << p.ring_mesh_axial << " N, M_t " << p.axial_moment_tangential
             << " N m, hand " << hand << " N m, bound " << bound << " N m");
        CHECK(std::abs(p.axial_moment_tangential - hand) <= bound);
        // No moment about the radial axis: the axial forces act on the line of centres (the
        // contact points off it by at most their path's tangential extent g_α cos α_wt).
        double radial_bound = 1e-9 * std::abs(hand);
        for (const int m : {2 * i, 2 * i + 1}) {
          const geometry::MeshSummary& s = on.stage.meshes()[static_cast<std::size_t>(m)];
          const double f_a = m % 2 == 0 ? p.sun_mesh_axial : p.ring_mesh_axial;
          radial_bound += std::abs(f_a) * s.contact_ratio_iso * p_bt * std::cos(s.pressure_angle);
        }
        CHECK(std::abs(p.axial_moment_radial) <= radial_bound);
      }
    }
  }
  // The pin error loads planet 1 most: its moment is the largest.
  const transmission::HelicalLoads& mean = on.summary.helical_mean;
  INFO("mean M_t " << mean.planets[0].axial_moment_tangential << ", "
                   << mean.planets[1].axial_moment_tangential << ", "
                   << mean.planets[2].axial_moment_tangential << " N m");
  CHECK(std::abs(mean.planets[0].axial_moment_tangential) >
        1.5 * std::abs(mean.planets[1].axial_moment_tangential));

  // K_γ against the spur stage with the same pin error. The helical stage's slices are the spur
  // stage's transverse sections (docs/model.md §10, "Helical meshes in slices": the same teeth,
  // the same plane compliance), each at its own phase of the mesh cycle, so its mesh stiffness
  // is the spur mesh's averaged over the phases across ε_β = 0.5 of an axial pitch: about the
  // same mean, a far smaller fluctuation (the spur mesh alternates one and two tooth pairs,
  // ε_α = 1.30 / 1.52). The pin error's share follows the stiffness position by position, so
  // planet 1's LSR swings less over the cycle, and K_γ, its largest L_i, is smaller.
  const auto swing = [](const transmission::SweepSummary& s) {
    return s.lsr_max[0] - s.lsr_min[0];
  };
  INFO("K_gamma helical " << off.summary.k_gamma << " (mean " << off.summary.k_gamma_mean
                          << ", planet 1 LSR swing " << swing(off.summary) << "), with pins "
                          << on.summary.k_gamma << "; spur " << spur.summary.k_gamma << " (mean "
                          << spur.summary.k_gamma_mean << ", swing " << swing(spur.summary) << ")");
  CHECK(swing(off.summary) < swing(spur.summary));
  CHECK(off.summary.k_gamma < spur.summary.k_gamma);
  // The comparison holds where the share follows the stiffness linearly: every planet in contact
  // at every position, in both stages.
  for (const Sweep* run : {&off, &spur})
    for (const double lsr : run->summary.lsr_min) CHECK(lsr > 0);

  // The tilt's feedback. A moment M_t about e_t turns the planet's axis by M_t/k_tilt about e_t:
  // e_z → e_z + φ e_r, so for M_t > 0 the planet's +z end moves outward. That opens the sun mesh
  // at +z and closes it at −z, and closes the ring mesh at +z: the sun mesh's load moves towards
  // −z, the ring mesh's towards +z (the other way for M_t < 0). Uncoupled slices on the rigid
  // planet: a gap change linear in z adds k_s κ (z_s − z̄_k) to slice s (z̄_k the slices'
  // stiffness centroid), so the load's first moment moves with the closing end.
  for (std::size_t k = 0; k < on.results.size(); ++k) {
    const PositionResult& r = on.results[k];
    const PositionResult& o = off.results[k];
    for (int i = 0; i < 3; ++i) {
      const double m_t = r.helical.planets[static_cast<std::size_t>(i)].axial_moment_tangential;
      const double outward = m_t > 0 ? 1 : -1;  // the sign of the +z end's radial motion
      // The pin's tilt is the moment's (pin.hpp: straddle, no slope from the planet's force).
      CHECK(r.pin_tilts_carrier[static_cast<std::size_t>(i)].x() * outward > 0);
      for (const bool ring : {false, true}) {
        const double shift = test::FaceFirstMoment(test::MeshLoad(r, i, ring)) -
                             test::FaceFirstMoment(test::MeshLoad(o, i, ring));
        INFO("position " << k << ", planet " << i + 1 << (ring ? " ring" : " sun")
                         << " mesh: first moment with feedback - without " << shift
                         << " N m; K_Hbeta " << test::MeshLoad(o, i, ring).k_h_beta << " -> "
                         << test::MeshLoad(r, i, ring).k_h_beta);
        CHECK(shift * outward * (ring ? 1 : -1) > 0);
      }
    }
  }
  // K_Hβ (largest over the cycle) of planet 1, whose tilt is the largest: without the feedback its
  // sun mesh's peak sits in the edge slice at −z, the end the tilt closes. There the feedback adds
  // k_s κ (z_s − z̄_k) > 0 (the edge is beyond the stiffness centroid) while the mesh's force, and
  // so the mean load, stays put (the tilt's gap change is zero at mid-face), so K_Hβ at that
  // position, and the largest over the cycle with it, rises.
  const auto k_h_beta = [](const transmission::SweepSummary& s, bool ring) {
    for (const transmission::MeshFaceSummary& f : s.face_width)
      if (f.planet == 0 && f.ring_mesh == ring) return f;
    FAIL("no face summary");
    return s.face_width.front();
  };
  const transmission::MeshFaceSummary sun_off = k_h_beta(off.summary, false),
                                      sun_on = k_h_beta(on.summary, false);
  INFO("planet 1 sun mesh K_Hbeta max "
       << sun_off.k_h_beta_max << " at z " << sun_off.largest_z << " -> " << sun_on.k_h_beta_max
       << " at z " << sun_on.largest_z << "; ring mesh " << k_h_beta(off.summary, true).k_h_beta_max
       << " -> " << k_h_beta(on.summary, true).k_h_beta_max);
  REQUIRE(mean.planets[0].axial_moment_tangential > 0);
  const double b = 25e-3, slice = b / on.scene.face_width.slices;
  REQUIRE(sun_off.largest_z == Approx(-0.5 * b + 0.5 * slice).margin(1e-12));
  CHECK(sun_on.k_h_beta_max > sun_off.k_h_beta_max);
}
