#include "epicycle/dynamics/dynamic_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "epicycle/io/number_format.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace epicycle::dynamics {

using transmission::kRingBody;
using transmission::kSunBody;
using transmission::StageContact;
using transmission::StageDof;
using transmission::SurfaceVelocity;
using Vec2 = Eigen::Vector2d;

namespace {

double Cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The gear body a coordinate moves (kSunBody, kRingBody, PlanetBody(i)), or −1 (the carrier).
int GearBody(const MotionDof& f) {
  switch (f.member) {
    case MotionDof::kSun:
      return kSunBody;
    case MotionDof::kRing:
      return kRingBody;
    case MotionDof::kPlanet:
      return transmission::PlanetBody(f.planet);
    case MotionDof::kCarrier:
      break;
  }
  return -1;
}

Vec2 Perp(const Vec2& a) { return {-a.y(), a.x()}; }  // ẑ × a

}  // namespace

std::string MotionDof::Label() const {
  const std::string name = member == kSun       ? "sun"
                           : member == kRing    ? "ring"
                           : member == kCarrier ? "carrier"
                                                : "planet" + std::to_string(planet + 1);
  return name + (axis == kX ? " x [m]" : axis == kY ? " y [m]" : " rotation [rad]");
}

DynamicModel::DynamicModel(const transmission::StageModel& model,
                           const transmission::DynamicSettings& settings,
                           const transmission::StageInertias& inertias,
                           const transmission::StageLoads& loads)
    : model_(model),
      settings_(settings),
      sun_(inertias.sun),
      planet_(inertias.planet),
      ring_(inertias.ring),
      carrier_(inertias.carrier),
      loads_(loads),
      friction_(settings_.friction) {
  settings_.Validate();
  model_.CheckLoads(loads);
  const geometry::Stage& stage = model_.stage();
  const transmission::StageSetup& setup = model_.setup();
  auto need = [&](const std::string& key, double value, const std::string& why) {
    if (!(value > 0) || !std::isfinite(value))
      throw std::invalid_argument(model_.name() + ": " + key + " = " + io::Num(value) + ": " + why +
                                  " needs it > 0 in the dynamic model");
  };
  // The sun turns the way its input torque drives it; ω_c = ω_s z_s/(z_s + z_r).
  carrier_speed_ = transmission::RigidCarrierSpeed(stage, settings_.sun_speed, loads_.sun_torque);
  carrier_torque_ = -loads_.sun_torque * stage.sun_ratio();
  auto add = [&](MotionDof::Member member, MotionDof::Axis axis, int planet, double mass,
                 StageDof::Kind kind, bool gear) {
    dofs_.push_back({member, axis, planet});
    mass_.conservativeResize(mass_.size() + 1);
    mass_(mass_.size() - 1) = mass;
    if (gear) {
      stage_dof_.push_back(static_cast<int>(stage_dofs_.size()));
      stage_dofs_.push_back({kind, planet});
    } else {
      stage_dof_.push_back(-1);
    }
  };
  need("[sun] inertia_kgm2", sun_.inertia, "the sun's rotation");
  if (!settings_.sun_speed_driven)
    add(MotionDof::kSun, MotionDof::kRotation, 0, sun_.inertia, StageDof::kSunRotation, true);
  if (setup.sun != transmission::SunSupport::kFixed) {
    need("[sun] mass_kg", sun_.mass, "a floating or elastic sun");
    add(MotionDof::kSun, MotionDof::kX, 0, sun_.mass, StageDof::kSunX, true);
    add(MotionDof::kSun, MotionDof::kY, 0, sun_.mass, StageDof::kSunY, true);
  }
  if (settings_.ring_elastic) {
    need("[ring] mass_kg", ring_.mass, "an elastic ring");
    need("[ring] inertia_kgm2", ring_.inertia, "an elastic ring");
    add(MotionDof::kRing, MotionDof::kRotation, 0, ring_.inertia, StageDof::kRingRotation, true);
    add(MotionDof::kRing, MotionDof::kX, 0, ring_.mass, StageDof::kRingX, true);
    add(MotionDof::kRing, MotionDof::kY, 0, ring_.mass, StageDof::kRingY, true);
  }
  if (settings_.carrier_free) {
    need("[carrier] inertia_kgm2", carrier_.inertia + settings_.carrier_load_inertia,
         "a carrier free in rotation");
    if (!(setup.planet_stiffness > 0))
      throw std::invalid_argument(
          "[dynamics] carrier = \"torque\": a free carrier needs elastic planet pins ([supports] "
          "planet_stiffness_N_per_um > 0); rigid pins tie the planets' centres to the carrier");
    add(MotionDof::kCarrier, MotionDof::kRotation, 0,
        carrier_.inertia + settings_.carrier_load_inertia, StageDof::kSunRotation, false);
  }
  if (settings_.carrier_stiffness > 0) {
    need("[carrier] mass_kg", carrier_.mass, "a carrier on an elastic bearing");
    if (!(setup.planet_stiffness > 0))
      throw std::invalid_argument(
          "[dynamics] carrier_stiffness_N_per_um > 0: an elastic carrier needs elastic planet pins "
          "([supports] planet_stiffness_N_per_um > 0)");
    add(MotionDof::kCarrier, MotionDof::kX, 0, carrier_.mass, StageDof::kSunRotation, false);
    add(MotionDof::kCarrier, MotionDof::kY, 0, carrier_.mass, StageDof::kSunRotation, false);
  }
  need("[planet] inertia_kgm2", planet_.inertia, "each planet's rotation");
  for (int i = 0; i < stage.planets(); ++i) {
    add(MotionDof::kPlanet, MotionDof::kRotation, i, planet_.inertia, StageDof::kPlanetRotation,
        true);
    if (setup.planet_stiffness > 0) {
      need("[planet] mass_kg", planet_.mass, "elastic planet pins");
      add(MotionDof::kPlanet, MotionDof::kX, i, planet_.mass, StageDof::kPlanetX, true);
      add(MotionDof::kPlanet, MotionDof::kY, i, planet_.mass, StageDof::kPlanetY, true);
    }
  }
  contact_modulus_ = transmission::ContactModulus(model_.material());
  // Find's table: −1 where a member has no such DOF.
  dof_index_.assign(static_cast<std::size_t>(3 * (3 + stage.planets())), -1);
  for (int k = size() - 1; k >= 0; --k) dof_index_[DofSlot(dofs_[k])] = k;
}

std::size_t DynamicModel::DofSlot(const MotionDof& f) {
  const int member = f.member == MotionDof::kPlanet ? 3 + f.planet : static_cast<int>(f.member);
  return static_cast<std::size_t>(3 * member + static_cast<int>(f.axis));
}

int DynamicModel::Find(MotionDof::Member member, MotionDof::Axis axis, int planet) const {
  MotionDof f;
  f.member = member;
  f.axis = axis;
  f.planet = member == MotionDof::kPlanet ? planet : 0;
  if (member == MotionDof::kPlanet && (planet < 0 || planet >= model_.planets())) return -1;
  return dof_index_[DofSlot(f)];
}

std::vector<MemberDofs> DynamicModel::ModeLayout() const {
  std::vector<MemberDofs> layout;
  auto member = [&](const std::string& name, bool central, MotionDof::Member m, int planet) {
    layout.push_back({name, central, Find(m, MotionDof::kX, planet), Find(m, MotionDof::kY, planet),
                      Find(m, MotionDof::kRotation, planet)});
  };
  member("sun", true, MotionDof::kSun, 0);
  member("ring", true, MotionDof::kRing, 0);
  member("carrier", true, MotionDof::kCarrier, 0);
  for (int i = 0; i < model_.planets(); ++i)
    member("planet " + std::to_string(i + 1), false, MotionDof::kPlanet, i);
  return layout;
}

void DynamicModel::SetMeshStiffness(double sun_mesh, double ring_mesh) {
  k_sun_ = sun_mesh;
  k_ring_ = ring_mesh;
  const geometry::Stage& st = model_.stage();
  auto coefficient = [&](double k, double ja, double rba, double jb, double rbb) {
    if (settings_.mesh_damping > 0) return settings_.mesh_damping;
    // m_eq = J_A J_B/(J_A r_bB² + J_B r_bA²); a held member (ring) counts as infinite inertia.
    const double m_eq =
        std::isinf(jb) ? ja / (rba * rba) : ja * jb / (ja * rbb * rbb + jb * rba * rba);
    return 2.0 * settings_.mesh_damping_ratio * std::sqrt(std::max(k, 0.0) * m_eq);
  };
  const double j_ring = settings_.ring_elastic ? ring_.inertia : INFINITY;
  damping_sun_ = coefficient(k_sun_, sun_.inertia, st.sun().base_radius(), planet_.inertia,
                             st.planet(0).base_radius());
  damping_ring_ = coefficient(k_ring_, planet_.inertia, st.planet(0).base_radius(), j_ring,
                              st.ring().base_radius());
}

Vec2 DynamicModel::PinReference(int planet, double t) const {
  return model_.stage().Pin(planet, CarrierAngle(t));
}

Vec2 DynamicModel::CarrierCentre(const Eigen::VectorXd& d) const {
  const int kx = Find(MotionDof::kCarrier, MotionDof::kX);
  return kx >= 0 ? Vec2(d(kx), d(kx + 1)) : Vec2::Zero();
}

Vec2 DynamicModel::Pin(int planet, double t, const Eigen::VectorXd& d) const {
  const int kc = Find(MotionDof::kCarrier, MotionDof::kRotation);
  const double turn = kc >= 0 ? d(kc) : 0.0;
  return CarrierCentre(d) + model_.stage().Pin(planet, CarrierAngle(t) + turn);
}

Vec2 DynamicModel::PinVelocity(int planet, double t, const Eigen::VectorXd& d,
                               const Eigen::VectorXd& v) const {
  const int kc = Find(MotionDof::kCarrier, MotionDof::kRotation);
  const double omega = carrier_speed_ + (kc >= 0 ? v(kc) : 0.0);
  return CarrierCentre(v) + omega * Perp(Pin(planet, t, d) - CarrierCentre(d));
}

double DynamicModel::ReferenceVelocity(int k, double t) const {
  const MotionDof& f = dofs_[k];
  const geometry::Stage& st = model_.stage();
  switch (f.member) {
    case MotionDof::kSun:
      return f.axis == MotionDof::kRotation ? carrier_speed_ * st.sun_ratio() : 0.0;
    case MotionDof::kRing:
      return 0.0;
    case MotionDof::kCarrier:
      return f.axis == MotionDof::kRotation ? carrier_speed_ : 0.0;
    case MotionDof::kPlanet: {
      if (f.axis == MotionDof::kRotation) return carrier_speed_ * st.planet_ratio();
      const Vec2 vp = carrier_speed_ * Perp(PinReference(f.planet, t));
      return f.axis == MotionDof::kX ? vp.x() : vp.y();
    }
  }
  return 0.0;
}

geometry::StagePoses DynamicModel::Poses(double t, const Eigen::VectorXd& d) const {
  geometry::StagePoses poses;
  Eigen::VectorXd q;
  Poses(t, d, &q, &poses);
  return poses;
}

void DynamicModel::Poses(double t, const Eigen::VectorXd& d, Eigen::VectorXd* q,
                         geometry::StagePoses* poses) const {
  model_.KinematicPoses(CarrierAngle(t), poses);
  q->resize(static_cast<Eigen::Index>(stage_dofs_.size()));
  for (int k = 0; k < size(); ++k)
    if (stage_dof_[k] >= 0) (*q)(stage_dof_[k]) = d(k);
  transmission::StageModel::Displace(stage_dofs_, *q, poses);
}

void DynamicModel::BodyVelocities(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                                  std::vector<BodyMotion>* out) const {
  const int n = model_.planets();
  std::vector<BodyMotion>& b = *out;
  b.assign(2 + n, BodyMotion{});
  const geometry::Stage& st = model_.stage();
  b[kSunBody].angular_velocity = carrier_speed_ * st.sun_ratio();
  for (int i = 0; i < n; ++i) {
    b[transmission::PlanetBody(i)].angular_velocity = carrier_speed_ * st.planet_ratio();
    b[transmission::PlanetBody(i)].centre_velocity = PinVelocity(i, t, d, v);
  }
  for (int k = 0; k < size(); ++k) {
    const MotionDof& f = dofs_[k];
    const int body = GearBody(f);
    if (body < 0) continue;
    BodyMotion& m = b[body];
    if (f.axis == MotionDof::kRotation) m.angular_velocity += v(k);
    // An elastic pin: the centre's velocity is the reference pin's plus the deviation's.
    if (f.axis != MotionDof::kRotation && f.member == MotionDof::kPlanet && f.axis == MotionDof::kX)
      m.centre_velocity = carrier_speed_ * Perp(PinReference(f.planet, t));
    if (f.axis == MotionDof::kX) m.centre_velocity.x() += v(k);
    if (f.axis == MotionDof::kY) m.centre_velocity.y() += v(k);
  }
}

transmission::FrictionContact DynamicModel::FrictionState(const transmission::ContactTerms& terms,
                                                          int j) const {
  return transmission::ContactFrictionState(model_, terms.contacts[j],
                                            terms.local.empty() ? nullptr : &terms.local[j],
                                            contact_modulus_);
}

void DynamicModel::AddPairForce(const StageContact& s, const geometry::StagePoses& poses,
                                const Vec2& f, Eigen::Ref<Eigen::VectorXd> q) const {
  Eigen::VectorXd on_stage = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(stage_dofs_.size()));
  transmission::AddPairLoad(s, poses, f, stage_dofs_, on_stage);
  for (int k = 0; k < size(); ++k)
    if (stage_dof_[k] >= 0) q(k) += on_stage(stage_dof_[k]);
}

void DynamicModel::BearingForces(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                                 Eigen::VectorXd* q, Evaluation* out) const {
  const transmission::StageSetup& setup = model_.setup();
  const int ks = Find(MotionDof::kSun, MotionDof::kX);
  if (ks >= 0 && setup.sun == transmission::SunSupport::kElastic) {
    for (int a = 0; a < 2; ++a) {
      const double f = -setup.sun_stiffness * d(ks + a) - settings_.sun_bearing_damping * v(ks + a);
      (*q)(ks + a) += f;
      if (out) out->sun_bearing_force(a) = f;
    }
  }
  const int kr = Find(MotionDof::kRing, MotionDof::kRotation);
  if (kr >= 0) {
    (*q)(kr) -=
        settings_.ring_torsional_stiffness * d(kr) + settings_.ring_torsional_damping * v(kr);
    for (int a = 1; a <= 2; ++a)
      (*q)(kr + a) -= settings_.ring_stiffness * d(kr + a) + settings_.ring_damping * v(kr + a);
  }
  const int kc = Find(MotionDof::kCarrier, MotionDof::kRotation);
  for (int i = 0; i < model_.planets(); ++i) {
    const int kx = Find(MotionDof::kPlanet, MotionDof::kX, i);
    if (kx < 0) continue;
    // Elastic pin: spring and damper between the planet's centre and its pin.
    const Vec2 centre = PinReference(i, t) + Vec2(d(kx), d(kx + 1));
    const Vec2 centre_velocity = carrier_speed_ * Perp(PinReference(i, t)) + Vec2(v(kx), v(kx + 1));
    const Vec2 pin = Pin(i, t, d);
    const Vec2 f = -setup.planet_stiffness * (centre - pin) -
                   settings_.planet_bearing_damping * (centre_velocity - PinVelocity(i, t, d, v));
    (*q)(kx) += f.x();
    (*q)(kx + 1) += f.y();
    // The reaction on the carrier, about its centre.
    if (kc >= 0) (*q)(kc) += Cross(pin - CarrierCentre(d), -f);
    const int kcx = Find(MotionDof::kCarrier, MotionDof::kX);
    if (kcx >= 0) {
      (*q)(kcx) -= f.x();
      (*q)(kcx + 1) -= f.y();
    }
    if (out) out->planet_bearing_force[i] = f;
  }
  const int kcx = Find(MotionDof::kCarrier, MotionDof::kX);
  for (int a = 0; a < 2 && kcx >= 0; ++a)
    (*q)(kcx + a) -=
        settings_.carrier_stiffness * d(kcx + a) + settings_.carrier_damping * v(kcx + a);
  // External loads: the input torque on a torque-driven sun, the output torque on a free carrier.
  const int ks_rot = Find(MotionDof::kSun, MotionDof::kRotation);
  if (ks_rot >= 0) (*q)(ks_rot) += loads_.sun_torque;
  if (kc >= 0) (*q)(kc) += carrier_torque_;
}

void DynamicModel::Evaluate(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                            solvers::ContactSolver& solver, const solvers::ContactOptions& contact,
                            const Evaluation* warm, Evaluation* out, bool energies) const {
  if (!SolveContacts(t, d, solver, contact, warm, out)) return;
  out->ok = true;
  ContactForces(t, d, v, out);
  Accelerations(t, d, v, out);
  PowersAndEnergies(t, d, v, energies, out);
}

bool DynamicModel::SolveContacts(double t, const Eigen::VectorXd& d,
                                 solvers::ContactSolver& solver,
                                 const solvers::ContactOptions& contact, const Evaluation* warm,
                                 Evaluation* out) const {
  Evaluation& e = *out;
  EvaluationWorkspace& w = e.work;
  e.ok = false;
  e.message.clear();
  Poses(t, d, &w.stage_displacement, &e.poses);
  {
    // A fresh report that keeps its message's storage (SolveInto writes into it).
    std::string kept = std::move(e.report.message);
    kept.clear();
    e.report = {};
    e.report.message = std::move(kept);
  }
  e.geometry = model_.Terms(e.poses, &e.terms, &w.tip_rounds);
  if (!e.geometry.ok()) {
    // A pose the stage cannot be evaluated at (a trial step that swung a member past where its
    // meshes have a line of action or its contacts lie on the tables' flank grids): recoverable,
    // as a failed contact solve is; the integrator retries with a smaller step.
    e.message = "geometry: " + transmission::StatusName(e.geometry.status) + " (" +
                e.geometry.message + ")";
    return false;
  }
  const transmission::ContactTerms& terms = e.terms;
  const int n = terms.size();
  e.force.setZero(n);
  if (n > 0) {
    // The problem's buffers are the work space's: copied into (same sizes, no allocation), moved
    // into the problem, released after the solve. C is lent, not copied (O(N²) with face-width
    // slices): swapped into the problem's data and back after the solve, as the problem stores
    // it (its symmetric part, which the FE compliance and the face-width expansion already
    // are, bit for bit). A problem that refuses its data (it throws) takes the lent C with it;
    // the run then stops with that error, and an evaluation builds its terms anew in any case.
    solvers::ContactProblemData& data = w.problem;
    data.compliance.swap(e.terms.compliance);
    data.compliance_terms = terms.compliance_terms;
    data.overlap = terms.overlap;
    data.local = terms.local;
    data.equality_matrix.resize(0, n);
    data.equality_rhs.resize(0);
    solvers::ContactProblem problem(std::move(data));
    solvers::ContactOptions opt = contact;
    solvers::ContactSolution& solution = w.solution;
    if (warm != nullptr && warm->ok && warm->terms.size() > 0) {
      // Forces of the same potential contacts (those Label() names alike) from the last accepted
      // step.
      opt.warm_start = transmission::CarryForces(warm->terms.contacts, warm->force, terms.contacts,
                                                 &solution.force) > 0;
    } else {
      solution.force.resize(0);
    }
    solution.multiplier.resize(0);
    solver.SolveInto(problem, opt, &solution, &e.report);
    data = std::move(problem).Release();
    e.terms.compliance.swap(data.compliance);
    if (e.report.status != solvers::ContactStatus::kConverged) {
      e.message =
          "contact solve: " + solvers::StatusName(e.report.status) + " (" + e.report.message + ")";
      return false;
    }
    e.force = solution.force.cwiseMax(0.0);
  }
  return true;
}

// The contacts' total forces (F with the mesh damping, clipped at 0) and friction at the bodies'
// velocities, summed per body into w.body_force and w.body_moment, with the powers they carry.
void DynamicModel::ContactForces(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                                 Evaluation* out) const {
  Evaluation& e = *out;
  EvaluationWorkspace& w = e.work;
  const int np = model_.planets();
  const transmission::ContactTerms& terms = e.terms;
  const int n = terms.size();
  // Velocities of the gear bodies, the overlap rates and the mesh damping.
  BodyVelocities(t, d, v, &w.body);
  const std::vector<BodyMotion>& body = w.body;
  auto body_pose = [&](int b) -> const geometry::GearPose& {
    return transmission::BodyPose(e.poses, b);
  };
  e.overlap_rate.resize(n);
  e.total_force = e.force;
  e.friction.setZero(n);
  std::vector<double>& mesh_load = w.mesh_load;
  mesh_load.assign(2 * np, 0.0);
  auto mesh_index = [](const StageContact& s) { return geometry::MeshIndex(s.planet, s.mesh); };
  for (int j = 0; j < n; ++j) mesh_load[mesh_index(terms.contacts[j])] += e.force(j);
  e.dissipated_power = 0;
  e.friction_power = 0;
  e.contact_power = 0;
  const bool friction = settings_.friction.law != transmission::FrictionLaw::kOff;
  if (friction) e.friction_tangent.assign(static_cast<std::size_t>(n), Vec2::Zero());
  std::vector<Vec2>& body_force = w.body_force;
  body_force.assign(2 + np, Vec2::Zero());
  std::vector<double>& body_moment = w.body_moment;
  body_moment.assign(2 + np, 0.0);
  e.sun_mesh_torque.assign(np, 0.0);
  for (int j = 0; j < n; ++j) {
    const StageContact& s = terms.contacts[j];
    const geometry::PotentialContact& c = s.contact;
    const Vec2 p = c.point;
    const Vec2 va = transmission::MaterialVelocity(s.body_a, p, e.poses, body),
               vb = transmission::MaterialVelocity(s.body_b, p, e.poses, body);
    e.overlap_rate(j) = c.normal.dot(va - vb);
    if (!(e.force(j) > 0)) continue;
    e.contact_power += e.force(j) * e.overlap_rate(j);
    const double cm = s.mesh == geometry::MeshKind::kSunPlanet ? damping_sun_ : damping_ring_;
    const double cj = cm * e.force(j) / mesh_load[mesh_index(s)];
    e.total_force(j) = std::max(0.0, e.force(j) + cj * e.overlap_rate(j));
    // Power of the non-elastic part of the normal force (damping, and the clip).
    e.dissipated_power += (e.total_force(j) - e.force(j)) * e.overlap_rate(j);
    Vec2 f = e.total_force(j) * c.normal;  // on B
    if (friction && e.total_force(j) > 0) {
      const SurfaceVelocity u = transmission::ContactSurfaceVelocity(model_, s, e.poses, body);
      e.friction(j) = transmission::FrictionForce(friction_, FrictionState(terms, j), e.total_force(j), u.ua, u.ub);
      f += e.friction(j) * u.tangent;
      e.friction_tangent[static_cast<std::size_t>(j)] = u.tangent;
      const double p_friction = e.friction(j) * (u.ua - u.ub);  // μ_s F v_s ≥ 0
      e.friction_power += p_friction;
      e.dissipated_power += p_friction;
    }
    body_force[s.body_b] += f;
    body_force[s.body_a] -= f;
    body_moment[s.body_b] += Cross(p - body_pose(s.body_b).rotation_centre, f);
    const double moment_a = Cross(p - body_pose(s.body_a).rotation_centre, -f);
    body_moment[s.body_a] += moment_a;
    if (s.body_a == kSunBody) e.sun_mesh_torque[s.planet] += moment_a;
  }
}

// Q per DOF (the bodies' mesh forces and moments, the bearings, the external loads) and d̈ = Q/m
// with the elastic pins' reference acceleration.
void DynamicModel::Accelerations(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                                 Evaluation* out) const {
  Evaluation& e = *out;
  const EvaluationWorkspace& w = e.work;
  const int nd = size();
  const int np = model_.planets();
  const std::vector<Vec2>& body_force = w.body_force;
  const std::vector<double>& body_moment = w.body_moment;
  Eigen::VectorXd& qf = e.generalised_force;
  qf.setZero(nd);
  for (int k = 0; k < nd; ++k) {
    const MotionDof& f = dofs_[k];
    const int b = GearBody(f);
    if (b < 0) continue;
    qf(k) += f.axis == MotionDof::kX   ? body_force[b].x()
             : f.axis == MotionDof::kY ? body_force[b].y()
                                       : body_moment[b];
  }
  e.sun_mesh_force = body_force[kSunBody];
  e.ring_mesh_force = body_force[kRingBody];
  e.ring_mesh_torque = body_moment[kRingBody];
  e.planet_bearing_force.assign(np, Vec2::Zero());
  e.sun_bearing_force.setZero();
  BearingForces(t, d, v, &qf, &e);
  e.acceleration = qf.cwiseQuotient(mass_);
  // Elastic planet pins follow a reference that accelerates (the pin's circle).
  const double w2 = carrier_speed_ * carrier_speed_;
  for (int k = 0; k < nd; ++k) {
    const MotionDof& f = dofs_[k];
    if (f.member != MotionDof::kPlanet || f.axis == MotionDof::kRotation) continue;
    const Vec2 a = -w2 * PinReference(f.planet, t);
    e.acceleration(k) -= f.axis == MotionDof::kX ? a.x() : a.y();
  }
}

// The input torque, the external and the bearings' dissipated powers, the rigid pins' forces on
// the planets, and with `energies` the kinetic and stored energies (the energy balance of
// docs/dynamic.md).
void DynamicModel::PowersAndEnergies(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                                     bool energies, Evaluation* out) const {
  Evaluation& e = *out;
  const EvaluationWorkspace& w = e.work;
  const int np = model_.planets();
  const transmission::ContactTerms& terms = e.terms;
  const int n = terms.size();
  const std::vector<BodyMotion>& body = w.body;
  const std::vector<Vec2>& body_force = w.body_force;
  const std::vector<double>& body_moment = w.body_moment;
  const double w2 = carrier_speed_ * carrier_speed_;
  const geometry::Stage& st = model_.stage();
  const int ksun = Find(MotionDof::kSun, MotionDof::kRotation);
  const double omega_s = carrier_speed_ * st.sun_ratio() + (ksun >= 0 ? v(ksun) : 0.0);
  // A speed-driven sun is held at its speed by the torque that balances the mesh moments.
  e.input_torque = ksun >= 0 ? loads_.sun_torque : -body_moment[kSunBody];
  e.external_power = e.input_torque * omega_s;
  const int kc = Find(MotionDof::kCarrier, MotionDof::kRotation);
  double kinetic = 0.5 * sun_.inertia * omega_s * omega_s;
  kinetic += 0.5 * carrier_.inertia * std::pow(carrier_speed_ + (kc >= 0 ? v(kc) : 0.0), 2);
  if (kc >= 0) {
    kinetic += 0.5 * settings_.carrier_load_inertia * std::pow(carrier_speed_ + v(kc), 2);
    e.external_power += carrier_torque_ * (carrier_speed_ + v(kc));
  }
  kinetic += 0.5 * carrier_.mass * CarrierCentre(v).squaredNorm();
  kinetic += 0.5 * sun_.mass * body[kSunBody].centre_velocity.squaredNorm();
  if (settings_.ring_elastic) {
    kinetic += 0.5 * ring_.mass * body[kRingBody].centre_velocity.squaredNorm() +
               0.5 * ring_.inertia * std::pow(body[kRingBody].angular_velocity, 2);
  }
  for (int i = 0; i < np; ++i) {
    const BodyMotion& m = body[transmission::PlanetBody(i)];
    kinetic += 0.5 * planet_.mass * m.centre_velocity.squaredNorm() +
               0.5 * planet_.inertia * m.angular_velocity * m.angular_velocity;
    const Vec2 vpin = PinVelocity(i, t, d, v);
    if (Find(MotionDof::kPlanet, MotionDof::kX, i) < 0) {
      // Rigid pin: the pin's force on the planet is what moves its centre around the circle.
      e.planet_bearing_force[i] =
          planet_.mass * (-w2 * PinReference(i, t)) - body_force[transmission::PlanetBody(i)];
    }
    // A carrier driven at its speed does work on the planets through their pins.
    if (kc < 0) e.external_power += e.planet_bearing_force[i].dot(vpin);
  }
  e.kinetic_energy = energies ? kinetic : 0.0;
  double elastic = 0;
  if (n > 0 && energies) {
    elastic = 0.5 * e.force.dot(terms.compliance * e.force);
    for (int j = 0; j < n && !terms.local.empty(); ++j) {
      const double fj = e.force(j);
      elastic += fj * solvers::LocalApproach(terms.local[j], fj) -
                 solvers::LocalApproachIntegral(terms.local[j], fj);
    }
  }
  e.contact_energy = energies ? elastic : 0.0;
  const transmission::StageSetup& setup = model_.setup();
  const int ks = Find(MotionDof::kSun, MotionDof::kX);
  if (ks >= 0 && setup.sun == transmission::SunSupport::kElastic) {
    elastic += 0.5 * setup.sun_stiffness * (d(ks) * d(ks) + d(ks + 1) * d(ks + 1));
    e.dissipated_power += settings_.sun_bearing_damping * (v(ks) * v(ks) + v(ks + 1) * v(ks + 1));
  }
  const int kr = Find(MotionDof::kRing, MotionDof::kRotation);
  if (kr >= 0) {
    elastic += 0.5 * settings_.ring_torsional_stiffness * d(kr) * d(kr) +
               0.5 * settings_.ring_stiffness * (d(kr + 1) * d(kr + 1) + d(kr + 2) * d(kr + 2));
    e.dissipated_power += settings_.ring_torsional_damping * v(kr) * v(kr) +
                          settings_.ring_damping * (v(kr + 1) * v(kr + 1) + v(kr + 2) * v(kr + 2));
  }
  const int kcx = Find(MotionDof::kCarrier, MotionDof::kX);
  if (kcx >= 0) {
    elastic += 0.5 * settings_.carrier_stiffness * CarrierCentre(d).squaredNorm();
    e.dissipated_power += settings_.carrier_damping * CarrierCentre(v).squaredNorm();
  }
  for (int i = 0; i < np; ++i) {
    const int kx = Find(MotionDof::kPlanet, MotionDof::kX, i);
    if (kx < 0) continue;
    const Vec2 defl = PinReference(i, t) + Vec2(d(kx), d(kx + 1)) - Pin(i, t, d);
    const Vec2 rate = carrier_speed_ * Perp(PinReference(i, t)) + Vec2(v(kx), v(kx + 1)) -
                      PinVelocity(i, t, d, v);
    elastic += 0.5 * setup.planet_stiffness * defl.squaredNorm();
    e.dissipated_power += settings_.planet_bearing_damping * rate.squaredNorm();
  }
  e.elastic_energy = energies ? elastic : 0.0;
}

void DynamicModel::Jacobian(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                            const Evaluation& at, Eigen::MatrixXd* dd, Eigen::MatrixXd* dv) const {
  const int nd = size();
  dd->setZero(nd, nd);
  dv->setZero(nd, nd);
  const transmission::ContactTerms& terms = at.terms;
  const int n = terms.size();
  if (n > 0 && at.ok) {
    const Eigen::MatrixXd gs = model_.Sensitivity(terms, stage_dofs_);
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(nd, n);
    for (int k = 0; k < nd; ++k)
      if (stage_dof_[k] >= 0) g.row(k) = gs.row(stage_dof_[k]);
    std::vector<int> active;
    for (int j = 0; j < n; ++j)
      if (at.force(j) > 0) active.push_back(j);
    const int na = static_cast<int>(active.size());
    if (na > 0) {
      // ∂F_A/∂δ0_A = (C_AA + diag u'(F_A))⁻¹, δ0 changes by Gᵀ dq.
      Eigen::MatrixXd caa(na, na);
      Eigen::MatrixXd ga(nd, na);
      Eigen::VectorXd c_damp(na);
      std::vector<double> mesh_load(2 * model_.planets(), 0.0);
      for (int j = 0; j < n; ++j) {
        const StageContact& s = terms.contacts[j];
        mesh_load[2 * s.planet + (s.mesh == geometry::MeshKind::kSunPlanet ? 0 : 1)] += at.force(j);
      }
      for (int a = 0; a < na; ++a) {
        const int j = active[a];
        ga.col(a) = g.col(j);
        for (int b = 0; b < na; ++b) caa(a, b) = terms.compliance(j, active[b]);
        if (!terms.local.empty())
          caa(a, a) += solvers::LocalApproachDerivative(terms.local[j], at.force(j));
        const StageContact& s = terms.contacts[j];
        const double cm = s.mesh == geometry::MeshKind::kSunPlanet ? damping_sun_ : damping_ring_;
        const int mi = 2 * s.planet + (s.mesh == geometry::MeshKind::kSunPlanet ? 0 : 1);
        c_damp(a) = at.total_force(j) > 0 ? cm * at.force(j) / mesh_load[mi] : 0.0;
      }
      const Eigen::MatrixXd s_aa = caa.ldlt().solve(Eigen::MatrixXd::Identity(na, na));
      *dd -= ga * s_aa * ga.transpose();
      *dv -= ga * c_damp.asDiagonal() * ga.transpose();
      if (settings_.friction.law != transmission::FrictionLaw::kOff)
        AddFrictionJacobian(t, d, v, at, active, s_aa * ga.transpose(), c_damp, dd, dv);
    }
  }
  // Bearings and external loads: central differences of the cheap part.
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(nd);
  for (int k = 0; k < nd; ++k) {
    const double hd = 1e-9 * (dofs_[k].axis == MotionDof::kRotation ? 1.0 : 0.1);
    const double hv = 1e-6;
    Eigen::VectorXd dp = d, dm = d, vp = v, vm = v;
    dp(k) += hd;
    dm(k) -= hd;
    vp(k) += hv;
    vm(k) -= hv;
    Eigen::VectorXd qp = Eigen::VectorXd::Zero(nd), qm = Eigen::VectorXd::Zero(nd);
    BearingForces(t, dp, v, &qp, nullptr);
    BearingForces(t, dm, v, &qm, nullptr);
    dd->col(k) += (qp - qm) / (2 * hd);
    qp.setZero();
    qm.setZero();
    BearingForces(t, d, vp, &qp, nullptr);
    BearingForces(t, d, vm, &qm, nullptr);
    dv->col(k) += (qp - qm) / (2 * hv);
  }
  for (int k = 0; k < nd; ++k) {
    dd->row(k) /= mass_(k);
    dv->row(k) /= mass_(k);
  }
}

// Friction's part of the Jacobian (docs/model.md §7), with the contact geometry frozen as in the
// normal part. Contact j pushes B by φ_j t_j and A by −φ_j t_j, φ_j = μ_s(F_j, u_A, u_B)·F_j
// (F_j the normal force with its damping), so with h_j the generalised force of that unit pair:
//
//   ∂Q/∂d += Σ_j h_j ∂φ_j/∂F · ∂F_j/∂d,                     ∂F_A/∂d = (C_AA + diag u')⁻¹ G_Aᵀ,
//   ∂Q/∂ḋ += Σ_j h_j (∂φ_j/∂F c_j ∂δ̇_j/∂ḋ + ∂φ_j/∂u_A ∂u_A/∂ḋ + ∂φ_j/∂u_B ∂u_B/∂ḋ).
//
// The surface and overlap velocities are linear in ḋ, so their derivatives are the exact
// differences for unit changes of each velocity; the law's partial derivatives are central
// differences of the law itself (any law, its guards included), with steps 1e-6·F and 1e-3·v_ε:
// far below the scale on which any law bends (v_ε for the smoothed ones, V_e otherwise).
void DynamicModel::AddFrictionJacobian(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                                       const Evaluation& at, const std::vector<int>& active,
                                       const Eigen::MatrixXd& force_by_d,
                                       const Eigen::VectorXd& damping, Eigen::MatrixXd* dd,
                                       Eigen::MatrixXd* dv) const {
  const int nd = size();
  const transmission::ContactTerms& terms = at.terms;
  std::vector<BodyMotion> body;
  BodyVelocities(t, d, v, &body);
  std::vector<std::vector<BodyMotion>> moved(nd);  // body velocities with ḋ_k + 1
  for (int k = 0; k < nd; ++k) {
    Eigen::VectorXd vk = v;
    vk(k) += 1.0;
    BodyVelocities(t, d, vk, &moved[k]);
  }
  const double hu = 1e-3 * settings_.friction.smoothing_velocity;
  Eigen::VectorXd h(nd), rate_by_v(nd), ua_by_v(nd), ub_by_v(nd);
  for (int a = 0; a < static_cast<int>(active.size()); ++a) {
    const int j = active[a];
    const double f = at.total_force(j);
    if (!(f > 0)) continue;
    const StageContact& s = terms.contacts[j];
    const geometry::PotentialContact& c = s.contact;
    const SurfaceVelocity u = transmission::ContactSurfaceVelocity(model_, s, at.poses, body);
    auto overlap_rate = [&](const std::vector<BodyMotion>& b) {
      return c.normal.dot(transmission::MaterialVelocity(s.body_a, c.point, at.poses, b) -
                          transmission::MaterialVelocity(s.body_b, c.point, at.poses, b));
    };
    const double rate = overlap_rate(body);
    for (int k = 0; k < nd; ++k) {
      const SurfaceVelocity uk = transmission::ContactSurfaceVelocity(model_, s, at.poses, moved[k], &u.tangent);
      ua_by_v(k) = uk.ua - u.ua;
      ub_by_v(k) = uk.ub - u.ub;
      rate_by_v(k) = overlap_rate(moved[k]) - rate;
    }
    const transmission::FrictionContact fc = FrictionState(terms, j);
    const double hf = 1e-6 * f;
    const double phi_f =
        (transmission::FrictionForce(friction_, fc, f + hf, u.ua, u.ub) - transmission::FrictionForce(friction_, fc, f - hf, u.ua, u.ub)) / (2 * hf);
    const double phi_ua =
        (transmission::FrictionForce(friction_, fc, f, u.ua + hu, u.ub) - transmission::FrictionForce(friction_, fc, f, u.ua - hu, u.ub)) / (2 * hu);
    const double phi_ub =
        (transmission::FrictionForce(friction_, fc, f, u.ua, u.ub + hu) - transmission::FrictionForce(friction_, fc, f, u.ua, u.ub - hu)) / (2 * hu);
    h.setZero();
    AddPairForce(s, at.poses, u.tangent, h);
    *dd += h * (phi_f * force_by_d.row(a));
    *dv += h * (phi_f * damping(a) * rate_by_v + phi_ua * ua_by_v + phi_ub * ub_by_v).transpose();
  }
}

Eigen::VectorXd DynamicModel::QuasiStaticStart(const solvers::ContactOptions& contact,
                                               solvers::Backend backend) const {
  StartOutcome start = SolveQuasiStaticStart(contact, backend);
  if (start.status != transmission::RunStatus::kCompleted) throw std::runtime_error(start.message);
  return std::move(start.d);
}

StartOutcome DynamicModel::SolveQuasiStaticStart(const solvers::ContactOptions& contact,
                                                 solvers::Backend backend) const {
  StartOutcome out;
  transmission::QuasiStaticOptions opt;
  opt.backend = backend;
  opt.contact = contact;
  const transmission::PositionResult r =
      transmission::SolvePosition(model_, CarrierAngle(0.0), loads_, opt);
  // A planet whose flanks, drive and coast, all lie beyond the gap window in a mesh is separated
  // from that member: its motion would not be held by the contacts the model sees. A planet held
  // by its coast flanks only (errors beyond the backlash: jammed) is a state the model computes,
  // outside its validity; the run's warnings say so (DynamicWarnings).
  for (int i = 0; i < model_.planets(); ++i) {
    for (const geometry::MeshKind kind :
         {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
      const bool any =
          std::any_of(r.problem.contacts.begin(), r.problem.contacts.end(),
                      [&](const StageContact& s) { return s.planet == i && s.mesh == kind; });
      if (!any) {
        out.status = transmission::RunStatus::kGeometry;
        out.message = "the quasi-static start at carrier " +
                      io::Num(geometry::Deg(CarrierAngle(0.0))) + " deg: planet" +
                      std::to_string(i + 1) + " is separated from the " +
                      (kind == geometry::MeshKind::kSunPlanet ? "sun" : "ring") +
                      " (no flank within the gap window): the scene's errors or backlash "
                      "separate the gears";
        return out;
      }
    }
  }
  if (!r.converged) {
    out.status = transmission::RunStatus::kContactFailure;
    out.message = "the quasi-static start at carrier " + io::Num(geometry::Deg(CarrierAngle(0.0))) +
                  " deg failed: " + r.message;
    return out;
  }
  Eigen::VectorXd& d = out.d;
  d = Eigen::VectorXd::Zero(size());
  // A speed-driven sun cannot lag: the quasi-static lag λ_s goes to the carrier instead, by the
  // rigid kinematic motion that turns the sun back by −λ_s (carrier −λ_s/(1 + z_r/z_s), planets
  // with it), which leaves every mesh deflection as the quasi-static solution has it.
  const geometry::Stage& st = model_.stage();
  const bool shift = Find(MotionDof::kSun, MotionDof::kRotation) < 0;
  const double carrier_shift = shift ? -r.transmission_error / st.sun_ratio() : 0.0;
  for (int k = 0; k < size(); ++k) {
    const MotionDof& f = dofs_[k];
    if (f.member == MotionDof::kSun)
      d(k) = f.axis == MotionDof::kRotation ? r.transmission_error
             : f.axis == MotionDof::kX      ? r.sun_displacement.x()
                                            : r.sun_displacement.y();
    if (f.member == MotionDof::kCarrier && f.axis == MotionDof::kRotation) d(k) = carrier_shift;
    if (f.member == MotionDof::kPlanet) {
      if (f.axis == MotionDof::kRotation) {
        d(k) = r.planet_rotations[f.planet] + st.planet_ratio() * carrier_shift;
      } else {
        // The bearing deflection, turned with the carrier.
        const Vec2 defl = geometry::Rotate(r.planet_displacements[f.planet], carrier_shift);
        const Vec2 move = model_.stage().Pin(f.planet, CarrierAngle(0.0) + carrier_shift) -
                          model_.stage().Pin(f.planet, CarrierAngle(0.0));
        d(k) = f.axis == MotionDof::kX ? defl.x() + move.x() : defl.y() + move.y();
      }
    }
  }
  return out;
}

void DynamicModel::Linearise(double carrier_angle, Eigen::MatrixXd* m, Eigen::MatrixXd* k,
                             Eigen::MatrixXd* c) const {
  const int nd = size();
  *m = mass_.asDiagonal();
  k->setZero(nd, nd);
  Eigen::MatrixXd damping = Eigen::MatrixXd::Zero(nd, nd);
  // One involute contact on the loaded flanks of each mesh gives the mesh's line of action.
  const transmission::ContactTerms terms = model_.Terms(model_.KinematicPoses(carrier_angle));
  const Eigen::MatrixXd gs = model_.Sensitivity(terms, stage_dofs_);
  std::vector<int> chosen(2 * model_.planets(), -1);
  for (int j = 0; j < terms.size(); ++j) {
    const StageContact& s = terms.contacts[j];
    if (!s.loaded || s.contact.kind != geometry::ContactKind::kInvolute) continue;
    int& pick = chosen[2 * s.planet + (s.mesh == geometry::MeshKind::kSunPlanet ? 0 : 1)];
    if (pick < 0 || s.contact.overlap > terms.contacts[pick].contact.overlap) pick = j;
  }
  for (std::size_t mi = 0; mi < chosen.size(); ++mi) {
    if (chosen[mi] < 0)
      throw std::runtime_error("linearisation: no involute contact on the loaded flanks of mesh " +
                               std::to_string(mi) + " at carrier " +
                               io::Num(geometry::Deg(carrier_angle)) + " deg");
    Eigen::VectorXd g = Eigen::VectorXd::Zero(nd);
    for (int q = 0; q < nd; ++q)
      if (stage_dof_[q] >= 0) g(q) = gs(stage_dof_[q], chosen[mi]);
    const double km = mi % 2 == 0 ? k_sun_ : k_ring_;
    *k += km * g * g.transpose();
    // The mesh's damping c_m along the same line (the contacts share it in proportion to their
    // loads, so one loaded contact carries all of it).
    damping += (mi % 2 == 0 ? damping_sun_ : damping_ring_) * g * g.transpose();
  }
  // Bearings: the Hessian of their stored energy at the reference configuration, symmetric by
  // construction. Every bearing is a linear spring, so its energy is ½ k |J d|² for the map J from
  // the state to the spring's deflection; at d = 0 every spring is unstretched (a pin's centre is
  // its pin, as Pin and PinReference agree there), so the rotation of a pin with the carrier adds
  // no geometric term and the Hessian is k JᵀJ.
  // The bearings' dampers act on the same deflections, so their matrix is c JᵀJ alike.
  const transmission::StageSetup& setup = model_.setup();
  auto spring = [&](double stiffness, double damper, const std::vector<std::pair<int, double>>& j) {
    for (const auto& [a, ja] : j)
      for (const auto& [b, jb] : j) {
        (*k)(a, b) += stiffness * ja * jb;
        damping(a, b) += damper * ja * jb;
      }
  };
  const int ks = Find(MotionDof::kSun, MotionDof::kX);
  if (ks >= 0 && setup.sun == transmission::SunSupport::kElastic)
    for (int a = 0; a < 2; ++a)
      spring(setup.sun_stiffness, settings_.sun_bearing_damping, {{ks + a, 1.0}});
  const int kr = Find(MotionDof::kRing, MotionDof::kRotation);
  if (kr >= 0) {
    spring(settings_.ring_torsional_stiffness, settings_.ring_torsional_damping, {{kr, 1.0}});
    for (int a = 1; a <= 2; ++a)
      spring(settings_.ring_stiffness, settings_.ring_damping, {{kr + a, 1.0}});
  }
  const int kc = Find(MotionDof::kCarrier, MotionDof::kRotation);
  const int kcx = Find(MotionDof::kCarrier, MotionDof::kX);
  if (kcx >= 0)
    for (int a = 0; a < 2; ++a)
      spring(settings_.carrier_stiffness, settings_.carrier_damping, {{kcx + a, 1.0}});
  const double t = (carrier_angle - start_angle_) / carrier_speed_;
  for (int i = 0; i < model_.planets(); ++i) {
    const int kx = Find(MotionDof::kPlanet, MotionDof::kX, i);
    if (kx < 0) continue;
    // The pin spring's deflection: the planet's centre less its pin, which moves with the
    // carrier's centre and turns with its rotation φ by φ ẑ × (pin − carrier centre).
    const Vec2 arm = Perp(PinReference(i, t));
    for (int a = 0; a < 2; ++a) {
      std::vector<std::pair<int, double>> j = {{kx + a, 1.0}};
      if (kcx >= 0) j.push_back({kcx + a, -1.0});
      if (kc >= 0) j.push_back({kc, -arm(a)});
      spring(setup.planet_stiffness, settings_.planet_bearing_damping, j);
    }
  }
  if (c) *c = std::move(damping);
}

StageDynamics::StageDynamics(transmission::Scene s, const transmission::FeComplianceOptions& f)
    : scene(std::move(s)),
      rating(transmission::RatingInputsOf(scene)),
      stage(transmission::MakeStage(scene)),
      fe(f),
      compliance(scene, stage, fe),
      stage_model(stage, compliance, transmission::SetupFromScene(scene)),
      model(stage_model, scene.dynamics, scene.inertia, scene.loads) {
  // A helical mesh in turned slices: the stage's own quasi-static stiffness (docs/model.md §10).
  if (stage_model.helical())
    sliced_stiffness = transmission::ComputeStageMeshStiffness(stage_model, scene.loads);
  if (!stage_model.helical()) modal_pairs.emplace(scene, stage, compliance);
  const auto k = stage_model.helical() ? sliced_stiffness.secant
                                       : transmission::MeanMeshStiffness(*modal_pairs);
  model.SetMeshStiffness(k[0], k[1]);
}

std::array<double, 2> StageDynamics::TangentMeshStiffness() const {
  return modal_pairs ? MeanTangentMeshStiffness(*modal_pairs) : sliced_stiffness.tangent;
}

std::array<double, 2> MeanTangentMeshStiffness(const transmission::StageMeshPairs& pairs,
                                               int positions, double step) {
  if (!(step > 0 && step < 0.5))
    throw std::invalid_argument("tangent mesh stiffness: step = " + std::to_string(step) +
                                ": must lie in (0, 0.5)");
  if (positions < 2)
    throw std::invalid_argument("tangent mesh stiffness: positions = " + std::to_string(positions) +
                                ": must be >= 2");
  std::array<double, 2> k{};
  for (std::size_t m = 0; m < 2; ++m) {
    const transmission::StageMeshPairs::Mesh& mesh = *pairs.meshes()[m];
    transmission::MeshStiffnessOptions opt;
    opt.positions = positions;
    transmission::MeshPairSetup up = mesh.setup, down = mesh.setup;
    up.torque *= 1 + step;
    down.torque *= 1 - step;
    const auto ru = transmission::ComputeMeshStiffness(up, mesh.pair, mesh.compliance, opt);
    const auto rd = transmission::ComputeMeshStiffness(down, mesh.pair, mesh.compliance, opt);
    for (std::size_t i = 0; i < ru.samples.size(); ++i) {
      const transmission::MeshSample &a = ru.samples[i], &b = rd.samples[i];
      if (!a.converged || !b.converged || !(a.approach > b.approach))
        throw std::runtime_error(std::string("tangent mesh stiffness of ") + mesh.name +
                                 ": sample " + std::to_string(i) +
                                 " failed: " + (a.converged ? b.message : a.message));
      k[m] += (a.total_force - b.total_force) / (a.approach - b.approach) /
              static_cast<double>(ru.samples.size());
    }
  }
  return k;
}

OperatingPointModes StageModes(const StageDynamics& rig) {
  OperatingPointModes out;
  out.mesh_stiffness = rig.TangentMeshStiffness();
  DynamicModel model = rig.model;
  model.SetMeshStiffness(out.mesh_stiffness[0], out.mesh_stiffness[1]);
  Eigen::MatrixXd m, k;
  model.Linearise(0.0, &m, &k);
  out.modes = SolveModes(m, k, model.ModeLayout());
  return out;
}

}  // namespace epicycle::dynamics
