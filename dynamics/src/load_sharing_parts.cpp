#include "epicycle/dynamics/load_sharing_parts.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "epicycle/transmission/contact_kinematics.hpp"

namespace epicycle::dynamics {

using Vec2 = Eigen::Vector2d;

namespace {

double Cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 Perp(const Vec2& a) { return {-a.y(), a.x()}; }

}  // namespace

const std::vector<double>& Part(const LoadSharingParts& p, int k) {
  // In the order of kLoadSharingPartNames.
  static constexpr std::vector<double> LoadSharingParts::*kMembers[kLoadSharingPartCount] = {
      &LoadSharingParts::sun_rotation, &LoadSharingParts::sun_translation,
      &LoadSharingParts::bearing,      &LoadSharingParts::friction,
      &LoadSharingParts::off_line,     &LoadSharingParts::geometry,
      &LoadSharingParts::residual};
  if (k < 0 || k >= kLoadSharingPartCount)
    throw std::invalid_argument("load-sharing part " + std::to_string(k) + ": must lie in 0.." +
                                std::to_string(kLoadSharingPartCount - 1));
  return p.*kMembers[k];
}

LoadSharingParts DecomposeLoadSharing(const DynamicModel& model, const DynamicSample& sample) {
  const int n = model.stage_model().planets();
  const Evaluation& e = sample.evaluation;
  if (static_cast<int>(sample.load_sharing.size()) != n ||
      static_cast<int>(e.sun_mesh_torque.size()) != n || sample.d.size() != model.size())
    throw std::invalid_argument("DecomposeLoadSharing: the sample has " +
                                std::to_string(sample.load_sharing.size()) +
                                " planets' ratios, the model " + std::to_string(n));
  const std::size_t un = static_cast<std::size_t>(n);
  LoadSharingParts out;
  for (std::vector<double>* v : {&out.deviation, &out.sun_rotation, &out.sun_translation,
                                 &out.bearing, &out.friction, &out.off_line, &out.geometry,
                                 &out.residual})
    v->assign(un, 0.0);
  const double tau = -e.input_torque;
  if (!(std::abs(tau) > 0) || n == 0) return out;
  for (int i = 0; i < n; ++i) out.deviation[i] = sample.load_sharing[i] - 1.0 / n;

  const geometry::Stage& stage = model.stage_model().stage();
  const geometry::GearPose& sun = transmission::BodyPose(e.poses, transmission::kSunBody);
  // Per planet: normal forces, their moment and resultant on the sun.
  std::vector<double> force(un, 0.0), normal_moment(un, 0.0);
  std::vector<Vec2> normal_resultant(un, Vec2::Zero());
  for (int j = 0; j < e.terms.size(); ++j) {
    const transmission::StageContact& s = e.terms.contacts[j];
    if (s.mesh != geometry::MeshKind::kSunPlanet) continue;
    const double f = e.total_force(j);
    if (!(f > 0)) continue;
    const double sign = s.body_a == transmission::kSunBody ? -1.0 : 1.0;  // +F n acts on B
    const Vec2 on_sun = sign * f * s.contact.normal;
    const std::size_t i = static_cast<std::size_t>(s.planet);
    force[i] += f;
    normal_resultant[i] += on_sun;
    normal_moment[i] += Cross(s.contact.point - sun.rotation_centre, on_sun);
  }
  // Each mesh's line of action: the crossed tangents of the base circles (a·D = r_s + r_p, a the
  // unit vector from the sun's centre to its tangent point), both orientations; the one the
  // normal forces load (largest Σ F_j n_j·u). An unloaded mesh takes a loaded one's, turned with
  // the planet's position.
  const double rs = stage.sun().base_radius();
  std::vector<Vec2> dir(un, Vec2::Zero()), tangent_point(un, Vec2::Zero());
  std::vector<bool> found(un, false);
  std::vector<Vec2> centre_dir(un);
  for (int i = 0; i < n; ++i) {
    const geometry::GearPose& p = transmission::BodyPose(e.poses, transmission::PlanetBody(i));
    const Vec2 dvec = p.geometric_centre - sun.geometric_centre;
    const double dist = dvec.norm();
    centre_dir[i] = dvec / dist;
    if (!(force[i] > 0)) continue;
    const double c = std::min(1.0, (rs + stage.planet(i).base_radius()) / dist);
    const double sn = std::sqrt(1 - c * c);
    double best = -INFINITY;
    for (double side : {1.0, -1.0}) {
      const Vec2 a = c * centre_dir[i] + side * sn * Perp(centre_dir[i]);
      for (double orient : {1.0, -1.0}) {
        const Vec2 u = orient * Perp(a);
        const double load = normal_resultant[i].dot(u);
        if (load > best) {
          best = load;
          dir[i] = u;
          tangent_point[i] = sun.geometric_centre + rs * a;
        }
      }
    }
    found[i] = true;
  }
  int loaded = -1;
  for (int i = 0; i < n && loaded < 0; ++i)
    if (found[i]) loaded = i;
  if (loaded < 0) return out;
  for (int i = 0; i < n; ++i) {
    if (found[i]) continue;
    // Turned from the loaded planet's line by the angle between the planets' centres.
    const double turn = std::atan2(Cross(centre_dir[loaded], centre_dir[i]),
                                   centre_dir[loaded].dot(centre_dir[i]));
    dir[i] = geometry::Rotate(dir[loaded], turn);
    tangent_point[i] =
        sun.geometric_centre + geometry::Rotate(tangent_point[loaded] - sun.geometric_centre, turn);
  }
  std::vector<double> lever(un);
  double lever_mean = 0, force_mean = 0;
  Vec2 off_force = Vec2::Zero(), on_line = Vec2::Zero();
  for (int i = 0; i < n; ++i) {
    lever[i] = Cross(tangent_point[i] - sun.rotation_centre, dir[i]);
    lever_mean += lever[i] / n;
    force_mean += force[i] / n;
    off_force += normal_resultant[i] - force[i] * dir[i];
    on_line += force[i] * dir[i];
  }
  // Moments per planet: off-line normal and friction (the mesh's moment less its normal forces').
  const bool friction = model.settings().friction.law != transmission::FrictionLaw::kOff;
  std::vector<double> m_off(un), m_fric(un, 0.0);
  double m_off_mean = 0, m_fric_mean = 0, lever_term_mean = 0;
  for (int i = 0; i < n; ++i) {
    m_off[i] = normal_moment[i] - lever[i] * force[i];
    if (friction) m_fric[i] = e.sun_mesh_torque[i] - normal_moment[i];
    m_off_mean += m_off[i] / n;
    m_fric_mean += m_fric[i] / n;
    lever_term_mean += (lever[i] - lever_mean) * force[i] / n;
  }
  // The sun's translational balance: inertia (equation of motion), bearing, friction, off-line.
  const int kx = model.Find(MotionDof::kSun, MotionDof::kX);
  Vec2 inertia = Vec2::Zero(), bearing = Vec2::Zero();
  Vec2 mesh_force = e.sun_mesh_force;
  if (kx >= 0) {
    inertia = model.mass()(kx) * Vec2(e.acceleration(kx), e.acceleration(kx + 1));
    bearing = e.sun_bearing_force;
  } else {
    bearing = -mesh_force;  // a fixed sun: the bearing takes the net mesh force
  }
  const Vec2 fric_force = friction ? Vec2(mesh_force - on_line - off_force) : Vec2::Zero();
  Eigen::MatrixXd a(3, n);
  for (int i = 0; i < n; ++i) a.col(i) << dir[i], 1.0;
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> split(a);
  auto share = [&](const Vec2& b) -> Eigen::VectorXd {
    return split.solve(Eigen::Vector3d(b.x(), b.y(), 0.0));
  };
  // A part without a source is exactly 0 (a floating sun's bearing, friction off).
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd df_inertia = kx >= 0 ? share(inertia) : zero,
                        df_bearing = bearing.isZero(0) ? zero : share(-bearing),
                        df_fric = friction ? share(-fric_force) : zero, df_off = share(-off_force);
  const int ks = model.Find(MotionDof::kSun, MotionDof::kRotation);
  const double j_theta = ks >= 0 ? model.mass()(ks) * sample.sun_acceleration : 0.0;
  for (int i = 0; i < n; ++i) {
    out.sun_rotation[i] = j_theta / (n * tau);
    out.sun_translation[i] = lever_mean * df_inertia(i) / tau;
    out.bearing[i] = lever_mean * df_bearing(i) / tau;
    out.friction[i] = ((m_fric[i] - m_fric_mean) + lever_mean * df_fric(i)) / tau;
    out.off_line[i] = ((m_off[i] - m_off_mean) + lever_mean * df_off(i)) / tau;
    const double rest = force[i] - force_mean - df_inertia(i) - df_bearing(i) - df_fric(i) - df_off(i);
    out.geometry[i] =
        (lever_mean * rest + (lever[i] - lever_mean) * force[i] - lever_term_mean) / tau;
    double sum = 0;
    for (int k = 0; k + 1 < kLoadSharingPartCount; ++k) sum += Part(out, k)[i];
    out.residual[i] = out.deviation[i] - sum;
  }
  return out;
}

}  // namespace epicycle::dynamics
