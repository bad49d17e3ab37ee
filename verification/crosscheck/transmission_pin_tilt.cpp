// The planet's tilt on its pin as per-position state (pin.hpp; docs/model.md §10, "The planet's
// pin"): on the helical paper stage with straddle pins, each planet's tilt against the hand
// calculation F_a (r_w,p|s + r_w,p|r)/k_tilt; the fixed point's face loads against those of the
// same tilt given as a fixed pin tilt (the validated path of issue 40); a rigid pin is the model
// without pins, bit for bit; on the spur paper stage with cantilever pins, each planet's slope in
// the plane of its force against the beam formula with the planet's force.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/pin.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "fe_fixtures.hpp"
#include "helical_fixtures.hpp"

using namespace epicycle;
using transmission::MeshFaceLoad;
using transmission::PositionResult;

namespace {

struct Helical {
  transmission::Scene scene;
  geometry::Stage stage;
  std::unique_ptr<transmission::StageModel> model;
  explicit Helical(const std::string& text)
      : scene(transmission::ParseScene(text, "paper_stage_helical_pin.toml")), stage(scene.stage) {
    model = std::make_unique<transmission::StageModel>(stage, test::HelicalCompliance(scene, stage),
                                                      transmission::SetupFromScene(scene));
  }
  PositionResult Solve(double angle = 0) const {
    PositionResult r = transmission::SolvePosition(*model, angle, scene.loads,
                                                   transmission::QuasiStaticOptions{});
    INFO(r.message);
    REQUIRE(r.converged);
    return r;
  }
};

const MeshFaceLoad& Mesh(const PositionResult& r, int planet, bool ring) {
  return test::MeshLoad(r, planet, ring);
}

// F_m |z̄_m| of a mesh: its force times its load centroid's distance from the mid-plane [N·m].
double LoadShiftMoment(const MeshFaceLoad& f) { return std::abs(test::FaceFirstMoment(f)); }

// The scene without its [[face_width.pin]] table (the last table of the file).
std::string WithoutPins(const std::string& text) {
  return text.substr(0, text.find("[[face_width.pin]]"));
}

}  // namespace

TEST_CASE("pins on the helical paper stage: each planet's tilt is its tilting moment over "
          "k_tilt, the hand calculation's within its bound, and the fixed point is the given "
          "tilt's state",
          "[crosscheck][transmission][pin][helical]") {
  const std::string text = test::SceneText("paper_stage_helical_pin.toml");
  const Helical rig(text);
  const transmission::PinModel& pins = rig.model->face_width().pins();
  REQUIRE(pins.active());
  const PositionResult r = rig.Solve();
  REQUIRE(r.pin_tilts_carrier.size() == 3);
  const transmission::QuasiStaticOptions options;
  const double b = 25e-3, k_tilt = 1 / pins.compliance(0).moment;
  // A straddle pin of 30 mm between plates 45 mm apart: 16 E I / L (E = 207 GPa).
  CHECK(k_tilt == Approx(16 * 207e9 * std::numbers::pi * std::pow(30e-3, 4) / 64 / 45e-3)
                      .epsilon(1e-12));

  // The fixed point: the last update moved the tilt's gap across the face by at most the
  // geometric tolerance, so the reported tilt is the pin's answer to the final forces within
  // tolerance/b (+ round-off of the sums, 1e-12 relative).
  const std::vector<transmission::PinLoad> loads =
      transmission::PinLoadsOf(rig.stage, r.poses, r.problem.contacts, r.solution.force);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d t = pins.Tilt(i, loads[static_cast<std::size_t>(i)]);
    CHECK((t - r.pin_tilts[static_cast<std::size_t>(i)]).norm() <=
          options.geometric_tolerance / b + 1e-12 * t.norm());
  }

  // The hand calculation: the two axial forces F_a = F_bt tan β_b at the operating pitch points,
  // M_t = F_a (r_w,p|s + r_w,p|r) about the tangential axis; a moment about e_t turns the axis
  // radially, t_r = M_t/k_tilt (pin.hpp: t = c_M (M_y, −M_x)). Bound: the contacts' positions
  // along the paths of contact move M_t by at most F_a Σ g_α sin α_wt (as the moment's own test,
  // transmission_helical_slices.cpp), and the transverse forces at their slices' z add
  // Σ_meshes F_m |z̄_m| at most (each mesh's force F_m at its load centroid z̄_m, from its line
  // loads; the radial share of a force ≤ 1).
  const geometry::StageAxialLoads ref = geometry::AxialLoads(rig.stage, rig.scene.loads.sun_torque);
  const double tan_bb = std::tan(rig.stage.sun().spec().helix.angle) *
                        std::cos(rig.stage.sun().spec().pressure_angle);
  const double torque = std::abs(rig.scene.loads.sun_torque);
  const double p_bt = 2 * std::numbers::pi * rig.stage.sun().base_radius() / rig.stage.sun().spec().teeth;
  for (int i = 0; i < 3; ++i) {
    const double f_a = r.load_sharing[static_cast<std::size_t>(i)] * torque /
                       rig.stage.sun().base_radius() * tan_bb;
    const auto& m = ref.meshes;
    const double arm = m[static_cast<std::size_t>(2 * i)].planet_arm +
                       m[static_cast<std::size_t>(2 * i + 1)].planet_arm;
    const double hand_moment =
        f_a * arm * (ref.planets[static_cast<std::size_t>(i)].tilting_moment > 0 ? 1 : -1);
    double path = 0, shift = 0;
    for (int k : {2 * i, 2 * i + 1}) {
      const geometry::MeshSummary& s = rig.stage.meshes()[static_cast<std::size_t>(k)];
      path += s.contact_ratio_iso * p_bt * std::sin(s.pressure_angle);
    }
    for (const bool ring : {false, true}) shift += LoadShiftMoment(Mesh(r, i, ring));
    const double hand = hand_moment / k_tilt;
    const double bound = (f_a * path + shift) / k_tilt;
    const Eigen::Vector2d& t = r.pin_tilts_carrier[static_cast<std::size_t>(i)];
    INFO("planet " << i + 1 << ": tilt radial " << t.x() * 1e6 << " urad, tangential "
                   << t.y() * 1e6 << " urad; hand " << hand * 1e6 << " urad, bound "
                   << bound * 1e6 << " urad (paths " << f_a * path / k_tilt * 1e6
                   << ", load shift " << shift / k_tilt * 1e6 << ")");
    CHECK(std::abs(t.x() - hand) <= bound);
    // The tangential tilt comes from the load's shift along the face alone.
    CHECK(std::abs(t.y()) <= shift / k_tilt);
  }

  // The same tilts given as fixed pin tilts ([[face_width.pin_tilt]], no pins): the same state.
  // The given tilts are written with 17 digits (exact) and differ from the fixed point's settled
  // ones by at most tolerance/b; a gap change δg moves a mesh's K_Hβ by at most c b δg/F_m
  // (c ≤ 25 N/(mm·µm) the stiffness per unit width, F_m ≥ 5 kN the mesh's force here: 1.25e5 per
  // metre), and both runs settle their displacements to the same tolerance: 2 × 1.25e5 × 1e-11.
  std::string given = WithoutPins(text);
  char line[200];
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d& t = r.pin_tilts_carrier[static_cast<std::size_t>(i)];
    std::snprintf(line, sizeof line,
                  "[[face_width.pin_tilt]]\nplanet = %d\nover_mm = 25.0\nradial_um = %.17g\n"
                  "tangential_um = %.17g\n",
                  i + 1, t.x() * b * 1e6, t.y() * b * 1e6);
    given += line;
  }
  const Helical fixed(given);
  REQUIRE_FALSE(fixed.model->face_width().pins().active());
  const PositionResult q = fixed.Solve();
  const double tol = 2 * 1.25e5 * options.geometric_tolerance;
  for (int i = 0; i < 3; ++i)
    for (const bool ring : {false, true}) {
      INFO("planet " << i + 1 << (ring ? " ring" : " sun") << " mesh: K_Hbeta with feedback "
                     << Mesh(r, i, ring).k_h_beta << ", given tilt " << Mesh(q, i, ring).k_h_beta);
      CHECK(std::abs(Mesh(r, i, ring).k_h_beta - Mesh(q, i, ring).k_h_beta) <= tol);
    }

  // Without the pins (rigid in tilt) the radial tilt's feedback is gone: the sun meshes' K_Hβ
  // differs from the feedback's (the tilt loads one end of the sun mesh and the other of the
  // ring mesh, docs/model.md §10).
  const Helical rigid(WithoutPins(text));
  const PositionResult o = rigid.Solve();
  for (int i = 0; i < 3; ++i) {
    INFO("planet " << i + 1 << ": sun mesh K_Hbeta off " << Mesh(o, i, false).k_h_beta << " on "
                   << Mesh(r, i, false).k_h_beta << "; ring mesh off " << Mesh(o, i, true).k_h_beta
                   << " on " << Mesh(r, i, true).k_h_beta);
    CHECK(Mesh(o, i, false).k_h_beta != Approx(Mesh(r, i, false).k_h_beta).epsilon(1e-3));
  }
}

TEST_CASE("pins: a rigid pin (k_tilt = +inf) is the model without pins, bit for bit",
          "[crosscheck][transmission][pin]") {
  const std::string text = WithoutPins(test::SceneText("paper_stage_helical_pin.toml"));
  const Helical none(text);
  transmission::Scene scene = none.scene;
  transmission::PinSpec rigid;
  rigid.tilting_stiffness = std::numeric_limits<double>::infinity();
  scene.face_width.pins.push_back(rigid);
  const transmission::StageModel model(none.stage, test::HelicalCompliance(none.scene, none.stage),
                                       transmission::SetupFromScene(scene));
  const PositionResult a = none.Solve(0.1);
  const PositionResult b = transmission::SolvePosition(model, 0.1, scene.loads,
                                                       transmission::QuasiStaticOptions{});
  REQUIRE(b.converged);
  CHECK(b.pin_tilts.empty());
  REQUIRE(a.solution.force.size() == b.solution.force.size());
  for (Eigen::Index j = 0; j < a.solution.force.size(); ++j)
    CHECK(a.solution.force(j) == b.solution.force(j));
  CHECK(a.transmission_error == b.transmission_error);
}

TEST_CASE("pin bending on the spur paper stage: a cantilever pin's slope lies in the plane of "
          "the planet's force, P a^2/(2EI) and the load shift's moment over EI/a",
          "[crosscheck][transmission][pin][face_width]") {
  const transmission::Scene scene = transmission::ParseScene(
      test::SceneText("paper_stage_pin_bending.toml"), "paper_stage_pin_bending.toml");
  const geometry::Stage stage(scene.stage);
  const transmission::StageModel model(stage, test::Compliance("paper_stage.toml"),
                                       transmission::SetupFromScene(scene));
  const PositionResult r =
      transmission::SolvePosition(model, 0.0, scene.loads, transmission::QuasiStaticOptions{});
  INFO(r.message);
  REQUIRE(r.converged);
  REQUIRE(r.pin_tilts.size() == 3);
  // Beam table (cantilever, load at the distance a from the clamp): slope P a²/(2 E I), and a
  // moment M there turns it by M a/(E I). E = 207 GPa, D = 30 mm, a = 20 mm, clamped at −z.
  const double ei = 207e9 * std::numbers::pi * std::pow(30e-3, 4) / 64, a = 20e-3;
  // Hand calculation of the planet's force: its two meshes' forces along their lines of action,
  // the sun mesh's carrying the planet's share of the sun torque, F_s = LSR_i |T_s|/r_b,sun, the
  // ring mesh's balancing the planet's rotation, F_r = F_s (equal base radii on the planet). Both
  // push the planet the same way tangentially, the sun's outward by sin α_w,s and the ring's
  // inward by sin α_w,r: their sum's magnitude is 2 F_s cos((α_w,s + α_w,r)/2).
  const double torque = std::abs(scene.loads.sun_torque);
  const double alpha_s = stage.meshes()[0].pressure_angle, alpha_r = stage.meshes()[1].pressure_angle;
  for (int i = 0; i < 3; ++i) {
    const double f_s = r.load_sharing[static_cast<std::size_t>(i)] * torque / stage.sun().base_radius();
    const double p_hand = 2 * f_s * std::cos(0.5 * (alpha_s + alpha_r));
    const Eigen::Vector2d& t = r.pin_tilts[static_cast<std::size_t>(i)];
    // The moment part: the transverse forces at their slices' z, Σ_meshes F_m |z̄_m| at most,
    // turns the axis by at most that × a/(EI); the tip-round contacts' forces (off the lines of
    // action) move P by at most their sum.
    double shift = 0, off_line = 0;
    for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
      const auto& c = r.problem.contacts[j];
      if (c.planet != i) continue;
      const double f = r.solution.force(static_cast<Eigen::Index>(j));
      if (c.contact.kind != geometry::ContactKind::kInvolute) off_line += f;
    }
    for (const bool ring : {false, true}) shift += LoadShiftMoment(Mesh(r, i, ring));
    const double hand = p_hand * a * a / (2 * ei);
    const double bound = shift * a / ei + 2 * off_line * a * a / (2 * ei) + 1e-9 * hand;
    // In the plane of the force: the planet's net force from its contacts.
    const std::vector<transmission::PinLoad> loads =
        transmission::PinLoadsOf(stage, r.poses, r.problem.contacts, r.solution.force);
    const Eigen::Vector2d along = loads[static_cast<std::size_t>(i)].force.normalized();
    INFO("planet " << i + 1 << ": slope along the force " << t.dot(along) * 1e6 << " urad, across "
                   << (t - t.dot(along) * along).norm() * 1e6 << " urad; hand " << hand * 1e6
                   << " urad, bound " << bound * 1e6 << " urad");
    CHECK(std::abs(t.dot(along) - hand) <= bound);
    CHECK((t - t.dot(along) * along).norm() <= shift * a / ei);
    // Clamped at −z, the free end +z follows the force: the slope points along it.
    CHECK(t.dot(along) > 0);
  }
}
