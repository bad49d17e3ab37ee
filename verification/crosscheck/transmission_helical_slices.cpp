// Helical meshes in slices (docs/model.md §10; helical_slices.hpp): the helical search at β = 0
// is the spur face-width model's expansion; on the helical paper stage, the axial forces that the
// sun and the ring take against the sun torque, and each planet's tilting moment against a hand
// calculation from its sun-mesh load.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/transmission/helical_scene.hpp"
#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/helical_study.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "fe_fixtures.hpp"
#include "helical_fixtures.hpp"

using namespace epicycle;
using transmission::ContactTerms;
using transmission::PositionResult;
using transmission::StageContact;

namespace {

// The helical paper stage (scenes/paper_stage_helical.toml) and its stage model.
struct HelicalPaperStage {
  transmission::Scene scene = transmission::ParseScene(test::SceneText("paper_stage_helical.toml"),
                                                       "paper_stage_helical.toml");
  geometry::Stage stage{scene.stage};
  transmission::StageModel model{stage, test::HelicalCompliance(scene, stage),
                                 transmission::SetupFromScene(scene)};
};

}  // namespace

TEST_CASE("helical slices at beta = 0 are the spur face-width model's slices",
          "[crosscheck][transmission][helical]") {
  // The spur paper stage with a tilted pin (paper_stage_pin_tilt.toml): at β = 0 every section
  // is the one the poses describe, so the helical search must find the contacts the spur model
  // expands, with the same gaps (tilt and lead terms) and the same compliance C_jk W_st. The
  // reference is FaceWidthModel::Expand, a separate code path (one search, rows repeated).
  const transmission::Scene scene = transmission::ParseScene(
      test::SceneText("paper_stage_pin_tilt.toml"), "paper_stage_pin_tilt.toml");
  const geometry::Stage stage(scene.stage);
  const transmission::StageModel model(stage, test::Compliance("paper_stage.toml"),
                                       transmission::SetupFromScene(scene));
  REQUIRE(model.face_width().active());
  const geometry::StagePoses poses = model.KinematicPoses(0.01);
  const ContactTerms spur = model.Terms(poses);
  ContactTerms helical;
  const transmission::DamageModel damage(scene.damage, transmission::BodyNames(5));
  REQUIRE(transmission::HelicalSliceTerms(stage, model.compliance(), model.face_width(), damage,
                                          poses, model.setup().gap_window, &helical)
              .ok());
  REQUIRE(helical.size() == spur.size());
  std::vector<int> match(static_cast<std::size_t>(spur.size()), -1);
  for (int j = 0; j < spur.size(); ++j)
    for (int k = 0; k < helical.size(); ++k)
      if (helical.contacts[k].SameAs(spur.contacts[j])) match[j] = k;
  for (int j = 0; j < spur.size(); ++j) {
    REQUIRE(match[j] >= 0);
    // The same arithmetic on the same searched contact: equal to rounding of the gap terms'
    // sums (1e-15 m on overlaps of 1e-4 m).
    CHECK(helical.overlap(match[j]) == Approx(spur.overlap(j)).margin(1e-15));
    CHECK(helical.contacts[match[j]].width_fraction == spur.contacts[j].width_fraction);
    for (int k = 0; k < spur.size(); ++k)
      CHECK(helical.compliance(match[j], match[k]) ==
            Approx(spur.compliance(j, k)).epsilon(1e-12).margin(1e-20));
  }
}

TEST_CASE("helical paper stage: the sun's and the ring's axial forces balance the sun torque, "
          "each planet's tilting moment is the hand calculation's",
          "[crosscheck][transmission][helical]") {
  const HelicalPaperStage paper;
  const transmission::Scene& scene = paper.scene;
  const geometry::Stage& stage = paper.stage;
  const transmission::StageModel& model = paper.model;
  const PositionResult r =
      transmission::SolvePosition(model, 0.0, scene.loads, transmission::QuasiStaticOptions{});
  REQUIRE(r.converged);
  const transmission::HelicalLoads& h = r.helical;
  REQUIRE(h.planets.size() == 3);

  // Hand calculation (ISO 21771, docs/model.md §10): the planets' sun meshes carry the sun
  // torque, Σ F_bt,i r_b,sun = |T_s|, each with the axial part F_bt,i tan β_b; so the sun takes
  // |F_a| = |T_s| tan β_b / r_b,sun. That holds for contacts on the line of action (lever r_b);
  // a tip-round contact's lever ℓ lies in [0, r_b], so the forces it carries move Σ F by at most
  // their sum F_tip. Relative to the sun meshes' Σ F (half of all contacts' forces, the other
  // half the ring meshes'): 2 F_tip/ΣF_all, plus the equilibrium residual (1e-9).
  const double share = test::TipRoundShare(r);
  INFO("share of the load on tip-round contacts " << (share - 1e-9) / 2);
  const double tan_bb = std::tan(stage.sun().spec().helix.angle) *
                        std::cos(stage.sun().spec().pressure_angle);
  const double torque = std::abs(scene.loads.sun_torque);
  const double sun_axial = torque * tan_bb / stage.sun().base_radius();
  CHECK(std::abs(h.sun_axial_force) == Approx(sun_axial).epsilon(share));
  // Its sign: the rule of geometry::AxialLoads (the flank carrying the load, the hand).
  const geometry::StageAxialLoads ref = geometry::AxialLoads(stage, scene.loads.sun_torque);
  CHECK((h.sun_axial_force > 0) == (ref.sun_axial_force > 0));
  CHECK((h.ring_axial_force > 0) == (ref.ring_axial_force > 0));
  // Newton's third law over the stage: the carrier takes nothing, the ring the sun's opposite.
  CHECK(h.ring_axial_force == Approx(-h.sun_axial_force).epsilon(share));
  CHECK(std::abs(h.carrier_axial_force) <= share * sun_axial);

  const double r_b_sun = stage.sun().base_radius();
  for (int i = 0; i < 3; ++i) {
    const transmission::PlanetHelicalLoad& p = h.planets[static_cast<std::size_t>(i)];
    // The planet's rotation balances its meshes: equal transverse base forces, equal and
    // opposite axial forces, to the tip-round contacts' forces again (relative to this planet's
    // load, LSR_i of the whole: share / LSR_i).
    const double f_bt = r.load_sharing[static_cast<std::size_t>(i)] * torque / r_b_sun;
    const double f_a = f_bt * tan_bb;
    const double own = share / r.load_sharing[static_cast<std::size_t>(i)];
    CHECK(std::abs(p.sun_mesh_axial) == Approx(f_a).epsilon(own));
    CHECK(std::abs(p.axial_force) <= own * f_a);
    // Hand calculation of the tilting moment: the two axial forces at the operating pitch
    // points, a diameter apart, M_t = F_a (r_w,p|s + r_w,p|r), sign as geometry::AxialLoads.
    const auto& m = ref.meshes;
    const double arm = m[static_cast<std::size_t>(2 * i)].planet_arm +
                       m[static_cast<std::size_t>(2 * i + 1)].planet_arm;
    const double hand = f_a * arm * (ref.planets[static_cast<std::size_t>(i)].tilting_moment > 0 ? 1 : -1);
    // Tolerance: each mesh's contacts lie on its line of action, at a distance u from the pitch
    // point of at most the path of contact's length g_α = ε_α p_bt, i.e. radially u sin α_wt from
    // the pitch point: |M − M_hand| ≤ F_a Σ_meshes g_α sin α_wt.
    double bound = 0;
    for (int k : {2 * i, 2 * i + 1}) {
      const geometry::MeshSummary& s = stage.meshes()[static_cast<std::size_t>(k)];
      const double p_bt = 2 * std::numbers::pi * stage.sun().base_radius() / stage.sun().spec().teeth;
      bound += s.contact_ratio_iso * p_bt * std::sin(s.pressure_angle);
    }
    INFO("planet " << i + 1 << ": M_t " << p.axial_moment_tangential << " N m, hand " << hand
                   << " N m, bound " << f_a * bound << " N m; whole moment (radial, tangential) "
                   << p.moment_radial << ", " << p.moment_tangential);
    CHECK(std::abs(p.axial_moment_tangential - hand) <= f_a * bound);
  }
}

TEST_CASE("helical paper stage with one planet: the transmission error's ripple is smallest at a "
          "whole overlap ratio",
          "[crosscheck][transmission][helical]") {
  // The theory (docs/model.md §10, ISO 21771 / Velex): the total contact-line length of a mesh
  // is constant when ε_β is whole, so the stiffness fluctuation and the TE ripple of unmodified
  // gears are smallest there. The paper stage's transverse section with one planet (no planet
  // phasing) and β from 25° to 30° (ε_β 0.88 … 1.09; helical_te_overlap maps 0 … 30°:
  // docs/face_width.md, "Helical meshes").
  const transmission::Scene scene =
      transmission::ParseScene(test::SceneText("paper_stage.toml"), "paper_stage.toml");
  geometry::StageSpec spur = scene.stage;
  spur.planets = 1;
  constexpr int kSlices = 20, kPositions = 24;
  transmission::StageSetup setup = transmission::SetupFromScene(scene);
  setup.face_width.slices = kSlices;
  double best = 1e9, best_eps = 0, step = 0, eps_prev = 0;
  for (int deg = 25; deg <= 30; ++deg) {
    const geometry::Stage stage(transmission::WithHelix(spur, deg * std::numbers::pi / 180,
                                                        geometry::Hand::kRight));
    const transmission::StageModel model(stage, test::Compliance("paper_stage.toml"), setup);
    const double eps = transmission::StageOverlapRatio(stage);
    const double pp = transmission::TransmissionErrorRipple(model, scene.loads, kPositions);
    if (deg > 25) step = std::max(step, eps - eps_prev);
    eps_prev = eps;
    INFO("beta " << deg << " deg, eps_beta " << eps << ": TE ripple " << pp * 1e6 << " urad");
    CHECK(pp > 0);
    if (pp < best) {
      best = pp;
      best_eps = eps;
    }
  }
  // Tolerance: the β grid finds the minimum to half its step in ε_β; the slices sample each
  // contact line at S points, so the model's contact length is constant when ε_β S (not ε_β) is
  // whole: its minimum may sit up to 1/S from the whole ε_β.
  INFO("smallest ripple " << best * 1e6 << " urad at eps_beta " << best_eps);
  CHECK(std::abs(best_eps - 1.0) <= 0.5 * step + 1.0 / kSlices);
}

TEST_CASE("a helical stage without slices is refused naming face_width.slices",
          "[crosscheck][transmission][helical]") {
  const transmission::Scene grc = transmission::ParseScene(
      test::SceneText("grc_helical_stage.toml"), "grc_helical_stage.toml");
  CHECK_THROWS_WITH(transmission::RequireHelicalSlices(grc, "`epicycle quasistatic`"),
                    Catch::Matchers::Contains("grc_helical_stage.toml:") &&
                        Catch::Matchers::Contains("face_width.slices = 1") &&
                        Catch::Matchers::Contains("needs slices >= 2"));
  const transmission::Scene sliced = transmission::ParseScene(
      test::SceneText("paper_stage_helical.toml"), "paper_stage_helical.toml");
  CHECK_NOTHROW(transmission::RequireHelicalSlices(sliced, "`epicycle quasistatic`"));
}

TEST_CASE(
    "helical paper stage: the sun's axial force departs from |T_s| tan beta_b / r_b by its "
    "contacts' levers off the base circle",
    "[crosscheck][transmission][helical]") {
  // docs/face_width.md, "Helical meshes": the model sums the sun contacts' axial parts,
  // F_a = tan β_b Σ f_j, and the sun's moment balance is Σ f_j ℓ_j = |T_s| (ℓ_j the lever of
  // contact j's normal about the sun's axis). So, exactly,
  //     F_a / (|T_s| tan β_b / r_b) − 1 = Σ_j f_j (r_b − ℓ_j) / |T_s| + ε_M,
  // ε_M the moment balance's relative residual. An involute contact's normal is tangent to the
  // base circle (ℓ = r_b); a tip-round contact (kTipRound*) pushes along the mating flank's normal,
  // whose lever about the sun's axis is shorter. The claim pinned here: the whole gap is the
  // tip-round contacts' term, at every position of the cycle sampled, and it is not small (it is
  // what the speed sweep's closed-form comparison reports).
  const HelicalPaperStage paper;
  const transmission::Scene& scene = paper.scene;
  const geometry::Stage& stage = paper.stage;
  const transmission::StageModel& model = paper.model;
  const double r_b = stage.sun().base_radius();
  const double torque = std::abs(scene.loads.sun_torque);
  const double tan_bb =
      std::tan(stage.sun().spec().helix.angle) * std::cos(stage.sun().spec().pressure_angle);
  const double closed = torque * tan_bb / r_b;
  constexpr int kPositions = 12;
  for (int k = 0; k < kPositions; ++k) {
    const double phi = stage.mesh_cycle() * k / kPositions;
    const PositionResult r =
        transmission::SolvePosition(model, phi, scene.loads, transmission::QuasiStaticOptions{});
    REQUIRE(r.converged);
    const geometry::Vec2 c = r.poses.sun.rotation_centre;
    double moment = 0, force = 0, tips = 0, tip_force = 0, worst_lever = 0;
    for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
      const StageContact& sc = r.problem.contacts[j];
      if (sc.body_a != transmission::kSunBody && sc.body_b != transmission::kSunBody) continue;
      const double f = r.solution.force(static_cast<Eigen::Index>(j));
      const geometry::PotentialContact& p = sc.contact;
      const geometry::Vec2 d = p.point - c;
      const double lever = std::abs(d.x() * p.normal.y() - d.y() * p.normal.x());
      moment += f * lever;
      force += f;
      if (p.kind == geometry::ContactKind::kInvolute) {
        worst_lever = std::max(worst_lever, std::abs(lever - r_b) / r_b);
      } else {
        tips += f * (r_b - lever) / torque;
        tip_force += f;
      }
    }
    const double gap = std::abs(r.helical.sun_axial_force) / closed - 1;
    const double residual = std::abs(moment / torque - 1);
    INFO("carrier angle " << phi << " rad: gap " << gap << ", tip-round term " << tips
                          << " (their share of the sun's contact force " << tip_force / force
                          << "), moment residual " << residual << ", worst involute lever "
                          << worst_lever);
    // An involute contact's lever is r_b to the rounding of the search's point and normal
    // (a few ε = 2.2e-16 of r_b): 1e-14 = 45 ε.
    CHECK(worst_lever <= 1e-14);
    // The identity above, to ε_M, the involute levers' rounding (worst_lever × Σ f r_b / |T_s|
    // = worst_lever (1 + gap)) and the sums' rounding (< 1e-13: a few hundred terms of ε each).
    CHECK(std::abs(gap - tips) <= residual + worst_lever * (1 + gap) + 1e-13);
    // And that term is what the gap is made of: positive, far above those roundings.
    CHECK(tips > 1e-5);
  }
}
