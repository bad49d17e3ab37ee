// The quasi-static driver with friction at rest (docs/model.md §9, docs/quasistatic.md
// "Friction at rest") against hand computations that use none of its friction code: the sliding
// from the stage's kinematic ratios in the carrier frame, the constant law written out, the sun's
// torque balance and the stage's efficiency from the ring's reaction and from the power balance.
// And friction off: the frictionless results, bit for bit, whatever the friction settings hold.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "epicycle/io/units.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/contact_kinematics.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "helical_fixtures.hpp"

using namespace epicycle;
using test::Sci;
using test::VerifyRow;
using transmission::PositionResult;
using transmission::StageContact;
using Vec2 = Eigen::Vector2d;

namespace {

double Cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 Perp(const Vec2& a) { return {-a.y(), a.x()}; }

struct Rig {
  transmission::Scene scene;
  geometry::Stage stage;
  std::unique_ptr<transmission::StageModel> model;
  explicit Rig(const char* file)
      : scene(transmission::ParseScene(test::SceneText(file), file)), stage(scene.stage) {
    model = std::make_unique<transmission::StageModel>(stage,
                                                       transmission::IsHelical(scene)
                                                           ? test::HelicalCompliance(scene, stage)
                                                           : test::Compliance(file),
                                                       transmission::SetupFromScene(scene));
  }
};

bool BitIdentical(const PositionResult& a, const PositionResult& b) {
  return a.converged == b.converged && a.geometric_iterations == b.geometric_iterations &&
         a.contact_iterations == b.contact_iterations && a.load_sharing == b.load_sharing &&
         a.transmission_error == b.transmission_error && a.solution.force == b.solution.force &&
         a.solution.multiplier == b.solution.multiplier && a.displacements == b.displacements &&
         a.problem.data.equality_rhs == b.problem.data.equality_rhs && !a.friction && !b.friction &&
         a.friction_force.size() == 0 && b.friction_force.size() == 0;
}

}  // namespace

TEST_CASE("friction at rest off: the frictionless results bit for bit, the friction settings unread",
          "[crosscheck][transmission][quasistatic][friction]") {
  // Off must run no friction code: options whose friction fields would fail validation or give
  // NaN if any of it ran (a NaN speed, an out-of-range coefficient under the off law) must give
  // the default options' results exactly, on the run-out case (fixed and floating sun).
  for (auto sun : {transmission::SunSupport::kFixed, transmission::SunSupport::kFloating}) {
    Rig rig("paper_stage_runout.toml");
    transmission::StageSetup setup = transmission::SetupFromScene(rig.scene);
    setup.sun = sun;
    const transmission::StageModel model(rig.stage, test::Compliance("paper_stage_runout.toml"),
                                         setup);
    transmission::QuasiStaticOptions plain, unread;
    unread.friction.law = transmission::FrictionLaw::kOff;
    unread.friction.coefficient = 7.0;
    unread.friction.lubricant.dynamic_viscosity = -1.0;
    unread.sun_speed = std::numeric_limits<double>::quiet_NaN();
    for (double deg : {0.0, 1.7, 3.1, 30.0}) {
      const auto a = transmission::SolvePosition(model, geometry::Rad(deg), rig.scene.loads, plain);
      const auto b = transmission::SolvePosition(model, geometry::Rad(deg), rig.scene.loads, unread);
      CHECK(a.converged);
      CHECK(BitIdentical(a, b));
    }
  }
}

namespace {

// A stage at its scene's loads (the paper's: no errors, fixed sun, −600 N·m), constant μ = 0.05
// with v_ε = 1e-5 m/s
// (tanh written out below, so the smoothing is part of the law, not an error), the sun at 1500
// rpm; 12 positions over a mesh cycle. By hand, from each contact's point p, normal n (A into B),
// force F_j of the driver's result and the members' centres, with the kinematics of the ring-fixed
// stage in the carrier frame (docs/model.md §7): ω_s' = ω_s − ω_c, ω_p' = −ω_s' z_s/z_p, ω_r' =
// −ω_c,
//   t = ẑ × n,   v_s = (ω_A' ẑ × (p − c_A) − ω_B' ẑ × (p − c_B))·t  (frame-free: the carrier's
//   own velocity at p cancels),   φ = μ tanh(v_s/v_ε) F  (on B along t, on A opposite), with
//   F = F_t/cos β_b on a helical slice (its transverse force F_t on a flank inclined by β_b).
// Checks, per position:
//  (a) the sun: T_s + Σ_j (p − c_s) × (−F_j n_j − φ_j t_j) = 0, to what the driver guarantees:
//      the contact solve's equilibrium residual on the sun's row (ε r_sun F*, ε the contact
//      tolerance, r_sun, F* its scales), plus the fixed point's: friction of forces within
//      ε‖F‖∞ of the final ones, μ ε ‖F‖∞ Σ_j |(p_j − c_s)·n_j|, plus round-off 1e-12 |T_s|;
//  (b) η from the ring's reaction: the load on the carrier balances the stage, T_c = M_r − T_s
//      (M_r the contacts' moment on the ring), η = (T_s − M_r) ω_c/(T_s ω_s), against the
//      driver's P_out/P_in (the planets' forces at their pins): the same bound scaled by ω_c/P_in
//      on both members' rows;
//  (c) the power balance of the rigid kinematics: η = 1 − (Σ φ_j v_s,j + Σ F_j n_j·(v_A −
//  v_B))/P_in
//      (friction's loss, and the normal forces' power at contacts whose rigid motion is not
//      along their normal: off the line of action), against (b).
// The checks on the stage of `file`, named `label` in the report.
void ConstantLawByHand(const char* file, const char* label) {
  Rig rig(file);
  const geometry::Stage& st = rig.stage;
  const double mu = 0.05, v_eps = 1e-5;
  transmission::QuasiStaticOptions opt;
  opt.friction.law = transmission::FrictionLaw::kConstant;
  opt.friction.coefficient = mu;
  opt.friction.smoothing_velocity = v_eps;
  opt.sun_speed = io::RpmToRadPerSecond(1500.0);
  const double t_s = rig.scene.loads.sun_torque;
  const double z_s = st.sun().teeth(), z_r = st.ring().teeth(), z_p = st.planet(0).teeth();
  const double w_s = (t_s > 0 ? 1.0 : -1.0) * opt.sun_speed;  // the sun turns as T_s drives it
  const double w_c = w_s * z_s / (z_s + z_r);
  const double w_sr = w_s - w_c, w_pr = -w_sr * z_s / z_p, w_rr = -w_c;
  // A helical slice's force is transverse, F_t; Coulomb's law acts on the flank's normal force
  // F_n = F_t/cos β_b, tan β_b = tan β cos α_t (ISO 21771), from the scene's β and α_t here.
  const geometry::GearSpec& sun = st.sun().spec();
  const double cos_beta_b =
      std::cos(std::atan(std::tan(sun.helix.angle) * std::cos(sun.pressure_angle)));
  double worst_a = 0, worst_b = 0, worst_c = 0, eta_min = 1, eta_max = 0;
  int positions = 0;
  for (int k = 0; k < 12; ++k) {
    const double angle = st.mesh_cycle() * k / 12.0;
    const PositionResult r = transmission::SolvePosition(*rig.model, angle, rig.scene.loads, opt);
    INFO(label << ", position " << k << ": " << r.message);
    REQUIRE(r.converged);
    REQUIRE(r.friction);
    ++positions;
    const geometry::StagePoses& poses = r.poses;
    auto centre = [&](int body) -> Vec2 {
      return body == transmission::kSunBody    ? poses.sun.rotation_centre
             : body == transmission::kRingBody ? poses.ring.rotation_centre
                                               : poses.planets[body - 2].rotation_centre;
    };
    auto spin = [&](int body) {  // in the carrier frame
      return body == transmission::kSunBody ? w_sr : body == transmission::kRingBody ? w_rr : w_pr;
    };
    double sun_moment = t_s, ring_moment = 0, loss = 0, normal_power = 0, lever_sum = 0;
    const double f_max = r.solution.force.cwiseAbs().maxCoeff();
    for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
      const StageContact& s = r.problem.contacts[j];
      const double f = std::max(r.solution.force(static_cast<Eigen::Index>(j)), 0.0);
      if (!(f > 0)) continue;
      const Vec2 p = s.contact.point, n = s.contact.normal, t = Perp(n);
      const Vec2 ca = centre(s.body_a), cb = centre(s.body_b);
      const Vec2 va = spin(s.body_a) * Perp(p - ca), vb = spin(s.body_b) * Perp(p - cb);
      const double v_s = (va - vb).dot(t);
      const double phi = mu * std::tanh(v_s / v_eps) * f / cos_beta_b;
      const Vec2 on_b = f * n + phi * t;
      loss += phi * v_s;
      normal_power += f * n.dot(va - vb);  // the carrier's own velocity at p cancels here too
      if (s.body_a == transmission::kSunBody) {
        sun_moment += Cross(p - ca, -on_b);
        lever_sum += std::abs((p - ca).dot(n));
      }
      if (s.body_b == transmission::kRingBody) ring_moment += Cross(p - cb, on_b);
    }
    const double p_in = t_s * w_s;
    const double eta_ring = (t_s - ring_moment) * w_c / p_in;
    const double eta_power = 1.0 - (loss + normal_power) / p_in;
    // (a)'s bound from the driver's guarantees on this position's problem.
    const solvers::ContactProblem problem(r.problem.data);
    const solvers::ContactScales sc = solvers::ComputeContactScales(problem);
    int sun_row = 0;
    for (std::size_t q = 0; q < r.problem.dofs.size(); ++q)
      if (r.problem.dofs[q].kind == transmission::StageDof::kSunRotation) sun_row = static_cast<int>(q);
    const double eps = opt.contact.tolerance;
    const double bound_a =
        eps * sc.row(sun_row) * sc.force + mu * eps * f_max * lever_sum + 1e-12 * std::abs(t_s);
    worst_a = std::max(worst_a, std::abs(sun_moment) / bound_a);
    // (b), (c): each side carries the residual of the sun's and of the planets' and ring's
    // balances, of the same size on the power scale: 2·bound_a·|ω_c|/P_in per member row, for the
    // three members in the balance (sun, planets, ring) — 6 bound_a |ω_c|/|P_in| in all.
    const double bound_b = 6 * bound_a * std::abs(w_c) / std::abs(p_in);
    worst_b = std::max(worst_b, std::abs(eta_ring - r.Efficiency()) / bound_b);
    worst_c = std::max(worst_c, std::abs(eta_power - eta_ring) / bound_b);
    eta_min = std::min(eta_min, r.Efficiency());
    eta_max = std::max(eta_max, r.Efficiency());
    CHECK(std::abs(loss - r.friction_power) <= 1e-9 * loss + bound_b * std::abs(p_in));
  }
  test::Figure(std::string("constant mu = 0.05, ") + label + ", 1500 rpm: efficiency " +
               Sci(eta_min, 6) + " .. " + Sci(eta_max, 6) + " over a mesh cycle");
  VerifyRow(std::string("sun torque balance with friction at rest, constant mu 0.05 (") + label +
                ", 12 positions)",
            "hand: contact forces, normals, tangents, mu, carrier-frame kinematics",
            std::to_string(positions) + " positions", "largest share of the bound " + Sci(worst_a),
            "eps r_sun F* + mu eps |F| sum|rho| + 1e-12 |T_s|", worst_a <= 1.0);
  VerifyRow(std::string("stage efficiency with friction at rest, constant mu 0.05 (") + label + ")",
            "hand: ring reaction; power balance of the rigid kinematics",
            "eta " + Sci(eta_min, 6) + " .. " + Sci(eta_max, 6),
            "largest share of the bound " + Sci(std::max(worst_b, worst_c)),
            "6 (a)-bound |w_c|/P_in", worst_b <= 1.0 && worst_c <= 1.0);
  CHECK(worst_a <= 1.0);
  CHECK(worst_b <= 1.0);
  CHECK(worst_c <= 1.0);
}

}  // namespace

TEST_CASE(
    "friction at rest, constant law: the sun's torque balance and the stage's efficiency by hand "
    "from the contact forces, normals, tangents and mu",
    "[crosscheck][transmission][quasistatic][friction]") {
  ConstantLawByHand("paper_stage.toml", "paper stage, fixed sun");
}

TEST_CASE(
    "friction at rest on sliced stages: each slice's friction balances by hand (a tilted pin, a "
    "helix), the fixed point settles",
    "[crosscheck][transmission][quasistatic][friction][helical]") {
  // The same hand checks on stages whose slices carry different loads: the spur paper stage with
  // planet 1's pin tilted (20 slices; its slices' loads fall across the face) and the helical one
  // (β = 15°, 20 slices; each slice at its own phase of the mesh cycle, so a tooth pair's slices
  // range from unloaded to the most loaded, and the sliding reverses at each slice's own pitch
  // point). Every slice is a contact of its own in the sums: its point, transverse normal and
  // tangent (a helical mesh slides in the transverse plane, along the profile's tangent: both
  // gears turn about parallel axes, so the relative velocity has no axial part), its force and
  // its φ = μ F_t/cos β_b (cos β_b = 0.9718 here: a φ of μ F_t misses (a) by 2.6e6 times the
  // bound, measured). The bounds are the plane stage's, per contact. The friction fixed point
  // must settle at each of the 12 positions (REQUIRE(converged)): a friction load computed from
  // another slice's force leaves the relative force change at the spread between the slices
  // (0.4-0.5).
  ConstantLawByHand("paper_stage_pin_tilt.toml", "spur paper stage, pin 1 tilted, 20 slices");
  ConstantLawByHand("paper_stage_helical.toml", "helical paper stage, beta 15 deg, 20 slices");
}

TEST_CASE(
    "contact kinematics: the surface velocities are the carrier frame's, where the lines of "
    "action stand still",
    "[crosscheck][transmission][friction]") {
  // The paper's stage at its kinematic poses, ring fixed, the sun at 1500 rpm. A planet's lines of
  // action turn with the carrier, so the entrainment speed V_e = (u_A + u_B)/2 that the lubricated
  // laws take is the carrier frame's: u = ω' ẑ × (p − c)·t with ω_s' = ω_s − ω_c,
  // ω_p' = −ω_s' z_s/z_p, ω_r' = −ω_c (docs/model.md §7). At the ring mesh's pitch point a planet
  // rolling in the fixed ring has no velocity in the inertial frame, so an inertial V_e would
  // vanish there while the carrier frame's is ω_c r_b,ring (an inertial u is off by the carrier's
  // velocity at p along t, up to ω_c r ≈ 4 m/s here). Every involute contact within the gap
  // window over a mesh cycle, against transmission::ContactSurfaceVelocity with the rigid body
  // motion: the same to round-off (1e-12 of the speeds).
  Rig rig("paper_stage.toml");
  const geometry::Stage& st = rig.stage;
  const double z_s = st.sun().teeth(), z_r = st.ring().teeth(), z_p = st.planet(0).teeth();
  const double w_s = io::RpmToRadPerSecond(1500.0), w_c = w_s * z_s / (z_s + z_r);
  const double w_sr = w_s - w_c, w_pr = -w_sr * z_s / z_p, w_rr = -w_c;
  double worst = 0, scale = 0, ring_least = INFINITY;
  int compared = 0;
  for (int k = 0; k < 12; ++k) {
    const double angle = st.mesh_cycle() * k / 12.0;
    const geometry::StagePoses poses = rig.model->KinematicPoses(angle);
    const transmission::ContactTerms terms = rig.model->Terms(poses);
    std::vector<transmission::BodyMotion> motion;
    transmission::RigidBodyMotion(st, angle, w_c, &motion);
    for (const StageContact& s : terms.contacts) {
      if (s.contact.kind != geometry::ContactKind::kInvolute) continue;
      const transmission::SurfaceVelocity u =
          transmission::ContactSurfaceVelocity(*rig.model, s, poses, motion);
      auto frame = [&](int body) {
        const geometry::GearPose& g = transmission::BodyPose(poses, body);
        const double w = body == transmission::kSunBody    ? w_sr
                         : body == transmission::kRingBody ? w_rr
                                                           : w_pr;
        return (w * Perp(s.contact.point - g.rotation_centre)).dot(u.tangent);
      };
      const double ua = frame(s.body_a), ub = frame(s.body_b);
      worst = std::max({worst, std::abs(u.ua - ua), std::abs(u.ub - ub)});
      scale = std::max({scale, std::abs(ua), std::abs(ub)});
      if (s.mesh == geometry::MeshKind::kPlanetRing)
        ring_least = std::min(ring_least, 0.5 * (u.ua + u.ub));
      ++compared;
    }
  }
  REQUIRE(compared > 0);
  const bool pass = worst <= 1e-12 * scale;
  const double rolling = std::abs(w_c) * st.ring().base_radius();  // V_e at its pitch point
  VerifyRow("surface velocities of the stage's involute contacts (paper stage, 1500 rpm)",
            "carrier-frame kinematics (the lines of action at rest)",
            std::to_string(compared) + " contact sides over a mesh cycle; least ring-mesh V_e " +
                Sci(ring_least) + " m/s (w_c r_b,ring " + Sci(rolling) + ")",
            Sci(worst) + " m/s", "1e-12 of the speeds", pass);
  CHECK(pass);
}
