// The kinematics of a tooth contact that friction needs (docs/model.md §7 and §9), shared by the
// dynamic model (at its current velocities) and the quasi-static driver (at the rigid kinematics
// of the scene's speed): the velocity of each gear body, the material velocity of a body at a
// point, the surface velocities u_A, u_B of the two flanks along the contact's tangent, the
// contact's friction state (face width, reduced radius, contact modulus) and the generalised
// load of a force pair on the stage's rigid DOFs.
//
// Surface velocities (docs/model.md §7): with v_A, v_B the material velocities of the two bodies
// at the contact point p and v_p the contact point's own velocity,
//
//   u_A = (v_A − v_p)·t,   u_B = (v_B − v_p)·t,   t = ẑ × n (or −ẑ × n, so that u_A + u_B ≥ 0),
//
// v_p = v_l + (n·((v_A + v_B)/2 − v_l)) n on the line of action, v_l the velocity at p of the
// frame of the line through the two gears' geometric centres g_A, g_B (it moves with them: a
// planet's lines of action turn with the carrier), v_l = v_gA + ω_l ẑ × (p − g_A),
// ω_l = ((g_B − g_A) × (v_gB − v_gA))/|g_B − g_A|²; the point slides along the line with the
// bodies' common normal motion. A tip round's contact point moves with the round's centre. Slide-to-roll ratio SR = |u_A − u_B|/V_e and
// entrainment V_e = (u_A + u_B)/2 follow (friction.hpp).
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "epicycle/geometry/contact.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/friction.hpp"
#include "epicycle/transmission/stage_model.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::transmission {

/// Velocity state of a gear body in the inertial frame.
struct BodyMotion {
  Eigen::Vector2d centre_velocity = Eigen::Vector2d::Zero();  ///< of its rotation centre [m/s]
  double angular_velocity = 0;                                ///< [rad/s]
};

/// ω_c [rad/s] (signed) of the rigid kinematics for a sun turning at |ω_s| = `sun_speed` [rad/s]
/// the way its input torque `sun_torque` [N·m] drives it, ring fixed: ω_c = ±|ω_s| z_s/(z_s + z_r).
double RigidCarrierSpeed(const geometry::Stage& stage, double sun_speed, double sun_torque);

/// The body velocities (kSunBody, kRingBody, PlanetBody(i)) of the rigid kinematics at carrier
/// angle φ_c [rad] and carrier speed ω_c [rad/s], ring fixed: the sun turns at ω_c (1 + z_r/z_s)
/// about a centre at rest, each planet at ω_c (1 − z_r/z_p) about a centre moving with its pin,
/// ω_c ẑ × Pin(i, φ_c). The dynamic model's velocities at zero deviation velocity.
void RigidBodyMotion(const geometry::Stage& stage, double carrier_angle, double carrier_speed,
                     std::vector<BodyMotion>* out);

/// The pose of body b (kSunBody, kRingBody, PlanetBody(i)).
const geometry::GearPose& BodyPose(const geometry::StagePoses& poses, int body);

/// The material velocity of body b at point p [m/s]: v_c + ω ẑ × (p − c), c its rotation centre.
Eigen::Vector2d MaterialVelocity(int body, const Eigen::Vector2d& p,
                                 const geometry::StagePoses& poses,
                                 const std::vector<BodyMotion>& motion);

/// The surface velocities of one contact (equations above).
struct SurfaceVelocity {
  Eigen::Vector2d tangent = Eigen::Vector2d::Zero();  ///< t, unit
  double ua = 0;  ///< u_A [m/s]
  double ub = 0;  ///< u_B [m/s]
};
/// Along `*tangent`, or (nullptr) along ẑ × n oriented so that the entrainment is ≥ 0.
SurfaceVelocity ContactSurfaceVelocity(const StageModel& model, const StageContact& contact,
                                       const geometry::StagePoses& poses,
                                       const std::vector<BodyMotion>& motion,
                                       const Eigen::Vector2d* tangent = nullptr);

/// E* [Pa] of two bodies of `material`: 1/E* = 2(1 − ν²)/E.
double ContactModulus(const Material& material);

/// The friction state of a contact but its load and velocities (FrictionContact's face width b,
/// reduced radius R and contact modulus E*): b the narrower face, R that of its local term if
/// `local` is given, else 1/(1/ρ_A + 1/ρ_B) of the search. On a helical slice those of its
/// flank's normal section (docs/model.md §10): b/cos β_b, R/cos β_b, and the normal force
/// F_n = F_t/cos β_b per unit of the slice's transverse force (normal_per_contact_force).
FrictionContact ContactFrictionState(const StageModel& model, const StageContact& contact,
                                     const solvers::LocalTermParameters* local,
                                     double contact_modulus);

/// The friction force μ_s(F, u_A, u_B)·F [N] of a contact with state `fc` (on B along t; on A
/// the opposite), 0 for F ≤ 0, with F = fc.normal_per_contact_force × `force` (the flank's
/// normal force of a helical slice's transverse force).
double FrictionForce(const FrictionModel& law, FrictionContact fc, double force, double ua,
                     double ub);

/// q_k += the generalised force on DOF k of `dofs` of a force f [N] on body B at the contact
/// point and −f on body A: f_x, f_y on a translation, (p − c) × f on a rotation about the body's
/// rotation centre c.
void AddPairLoad(const StageContact& contact, const geometry::StagePoses& poses,
                 const Eigen::Vector2d& f, const std::vector<StageDof>& dofs,
                 Eigen::Ref<Eigen::VectorXd> q);

}  // namespace epicycle::transmission
