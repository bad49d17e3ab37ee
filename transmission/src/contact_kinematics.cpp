// Contact kinematics for friction (equations in contact_kinematics.hpp).
#include "epicycle/transmission/contact_kinematics.hpp"

#include "epicycle/transmission/helical_slices.hpp"

namespace epicycle::transmission {

using Vec2 = Eigen::Vector2d;

namespace {

double Cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 Perp(const Vec2& a) { return {-a.y(), a.x()}; }  // ẑ × a

// The body a stage DOF moves and its axis (0 x, 1 y, 2 rotation).
int DofBody(const StageDof& d) {
  switch (d.kind) {
    case StageDof::kSunRotation:
    case StageDof::kSunX:
    case StageDof::kSunY:
      return kSunBody;
    case StageDof::kPlanetRotation:
    case StageDof::kPlanetX:
    case StageDof::kPlanetY:
      return PlanetBody(d.planet);
    case StageDof::kRingRotation:
    case StageDof::kRingX:
    case StageDof::kRingY:
      return kRingBody;
  }
  return -1;
}

int DofAxis(const StageDof& d) {
  switch (d.kind) {
    case StageDof::kSunX:
    case StageDof::kPlanetX:
    case StageDof::kRingX:
      return 0;
    case StageDof::kSunY:
    case StageDof::kPlanetY:
    case StageDof::kRingY:
      return 1;
    default:
      return 2;
  }
}

}  // namespace

double RigidCarrierSpeed(const geometry::Stage& stage, double sun_speed, double sun_torque) {
  return (sun_torque > 0 ? 1.0 : -1.0) * sun_speed / stage.sun_ratio();
}

void RigidBodyMotion(const geometry::Stage& stage, double carrier_angle, double carrier_speed,
                     std::vector<BodyMotion>* out) {
  const int n = stage.planets();
  out->assign(static_cast<std::size_t>(2 + n), BodyMotion{});
  (*out)[kSunBody].angular_velocity = carrier_speed * stage.sun_ratio();
  for (int i = 0; i < n; ++i) {
    BodyMotion& m = (*out)[static_cast<std::size_t>(PlanetBody(i))];
    m.angular_velocity = carrier_speed * stage.planet_ratio();
    m.centre_velocity = carrier_speed * Perp(stage.Pin(i, carrier_angle));
  }
}

const geometry::GearPose& BodyPose(const geometry::StagePoses& poses, int body) {
  return body == kSunBody    ? poses.sun
         : body == kRingBody ? poses.ring
                             : poses.planets[static_cast<std::size_t>(body - 2)];
}

Vec2 MaterialVelocity(int body, const Vec2& p, const geometry::StagePoses& poses,
                      const std::vector<BodyMotion>& motion) {
  const BodyMotion& m = motion[static_cast<std::size_t>(body)];
  return m.centre_velocity + m.angular_velocity * Perp(p - BodyPose(poses, body).rotation_centre);
}

SurfaceVelocity ContactSurfaceVelocity(const StageModel& model, const StageContact& s,
                                       const geometry::StagePoses& poses,
                                       const std::vector<BodyMotion>& motion,
                                       const Vec2* tangent) {
  const geometry::PotentialContact& c = s.contact;
  const Vec2 va = MaterialVelocity(s.body_a, c.point, poses, motion),
             vb = MaterialVelocity(s.body_b, c.point, poses, motion);
  // The contact point's own velocity: a tip round's contact point stays at the round, moving
  // with its centre.
  Vec2 v_contact = Vec2::Zero();
  if (c.kind == geometry::ContactKind::kTipRoundA) {
    const double rt = model.BodyGear(s.body_a).spec().tip_round_radius;
    v_contact = MaterialVelocity(s.body_a, c.point_a - rt * c.normal, poses, motion);
  } else if (c.kind == geometry::ContactKind::kTipRoundB) {
    const double rt = model.BodyGear(s.body_b).spec().tip_round_radius;
    v_contact = MaterialVelocity(s.body_b, c.point_b + rt * c.normal, poses, motion);
  } else {
    // On the line of action: it moves with the line through the two gears' geometric centres
    // (a planet's meshes turn with the carrier), and the point slides along it with the bodies'
    // common normal motion. The frame velocity at p: the centre line's translation and rotation,
    // ω_l = ((g_B − g_A) × (v_gB − v_gA))/|g_B − g_A|² (0 for gears on fixed axes).
    const Vec2 ga = BodyPose(poses, s.body_a).geometric_centre,
               gb = BodyPose(poses, s.body_b).geometric_centre;
    const Vec2 vga = MaterialVelocity(s.body_a, ga, poses, motion),
               vgb = MaterialVelocity(s.body_b, gb, poses, motion);
    const Vec2 d = gb - ga;
    const double w_line = Cross(d, vgb - vga) / d.squaredNorm();
    const Vec2 v_frame = vga + w_line * Perp(c.point - ga);
    v_contact = v_frame + c.normal.dot(0.5 * (va + vb) - v_frame) * c.normal;
  }
  SurfaceVelocity u;
  u.tangent = tangent != nullptr ? *tangent : Vec2(Perp(c.normal));
  u.ua = (va - v_contact).dot(u.tangent);
  u.ub = (vb - v_contact).dot(u.tangent);
  if (tangent == nullptr && u.ua + u.ub < 0) {  // orient t so that the entrainment is ≥ 0
    u.tangent = -u.tangent;
    u.ua = -u.ua;
    u.ub = -u.ub;
  }
  return u;
}

double ContactModulus(const Material& material) {
  const double k = (1 - material.poisson_ratio * material.poisson_ratio) / material.youngs_modulus;
  return 1.0 / (2 * k);
}

FrictionContact ContactFrictionState(const StageModel& model, const StageContact& s,
                                     const solvers::LocalTermParameters* local,
                                     double contact_modulus) {
  const geometry::PotentialContact& c = s.contact;
  FrictionContact fc;
  fc.face_width = geometry::ContactFaceWidth(model.BodyGear(s.body_a), model.BodyGear(s.body_b)) *
                  s.width_fraction;  // a pitted contact's strip (× 1 exactly when whole)
  fc.reduced_radius = local == nullptr
                          ? 1.0 / (1.0 / c.curvature_radius_a + 1.0 / c.curvature_radius_b)
                          : local->reduced_radius;
  fc.contact_modulus = contact_modulus;
  // A helical slice (docs/model.md §10, "Helical meshes in slices") solves for the transverse
  // force F_t; its flank carries F_n = F_t/cos β_b along a contact line Δz/cos β_b long with the
  // normal section's radius R/cos β_b, and the law takes those. The sliding has no axial part
  // (both gears turn about parallel axes), so μ F_n lies in the transverse plane along t.
  if (model.BodyGear(s.body_a).spec().helix.helical()) {
    const double cos_beta_b = LocalWidthFactor(model.BodyGear(s.body_a), model.BodyGear(s.body_b));
    fc.face_width /= cos_beta_b;
    fc.reduced_radius /= cos_beta_b;
    fc.normal_per_contact_force = 1.0 / cos_beta_b;
  }
  return fc;
}

double FrictionForce(const FrictionModel& law, FrictionContact fc, double force, double ua,
                     double ub) {
  fc.normal_force = force * fc.normal_per_contact_force;
  fc.velocity_a = ua;
  fc.velocity_b = ub;
  return law.SignedCoefficient(fc) * fc.normal_force;
}

void AddPairLoad(const StageContact& s, const geometry::StagePoses& poses, const Vec2& f,
                 const std::vector<StageDof>& dofs, Eigen::Ref<Eigen::VectorXd> q) {
  const Vec2& p = s.contact.point;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const int b = DofBody(dofs[k]);
    if (b != s.body_a && b != s.body_b) continue;
    const double sign = b == s.body_b ? 1.0 : -1.0;
    const int axis = DofAxis(dofs[k]);
    q(static_cast<Eigen::Index>(k)) +=
        sign * (axis == 0   ? f.x()
                : axis == 1 ? f.y()
                            : Cross(p - BodyPose(poses, b).rotation_centre, f));
  }
}

}  // namespace epicycle::transmission
