#include "epicycle/transmission/stage_problem.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace epicycle::transmission {

using geometry::MeshKind;
using geometry::PotentialContact;
using geometry::Vec2;

std::string StageContact::Label() const {
  const std::string mesh_name = mesh == MeshKind::kSunPlanet
                                    ? "sun-planet" + std::to_string(planet + 1)
                                    : "planet" + std::to_string(planet + 1) + "-ring";
  return mesh_name + " " + geometry::KindName(contact.kind) + " " + (loaded ? "drive" : "coast") +
         " teeth " + std::to_string(contact.tooth_a) + "/" + std::to_string(contact.tooth_b);
}

std::string StageDof::Label() const {
  switch (kind) {
    case kSunRotation:
      return "sun rotation [rad]";
    case kSunX:
      return "sun x [m]";
    case kSunY:
      return "sun y [m]";
    case kPlanetRotation:
      return "planet" + std::to_string(planet + 1) + " rotation [rad]";
    case kPlanetX:
      return "planet" + std::to_string(planet + 1) + " x [m]";
    case kPlanetY:
      return "planet" + std::to_string(planet + 1) + " y [m]";
  }
  return "?";
}

std::vector<StageContact> SearchStage(const geometry::Stage& stage,
                                      const geometry::StagePoses& poses, double gap_window) {
  std::vector<StageContact> out;
  geometry::ContactSearchOptions opt;
  opt.gap_window = gap_window;
  for (int i = 0; i < stage.planets(); ++i) {
    for (MeshKind kind : {MeshKind::kSunPlanet, MeshKind::kPlanetRing}) {
      const int loaded_side =
          kind == MeshKind::kSunPlanet ? stage.sun_mesh_side() : stage.ring_mesh_planet_side();
      for (const PotentialContact& c : stage.Contacts(poses, i, kind, opt)) {
        StageContact s;
        s.contact = c;
        s.planet = i;
        s.mesh = kind;
        s.body_a = kind == MeshKind::kSunPlanet ? kSunBody : PlanetBody(i);
        s.body_b = kind == MeshKind::kSunPlanet ? PlanetBody(i) : kRingBody;
        s.loaded = c.side_a == loaded_side;
        out.push_back(s);
      }
    }
  }
  return out;
}

namespace {

const geometry::Gear& BodyGear(const geometry::Stage& st, int body) {
  if (body == kSunBody) return st.sun();
  if (body == kRingBody) return st.ring();
  return st.planet(body - 2);
}

// ∂δ/∂q for one contact and one DOF: translating A along e changes the overlap by n·e, B by
// −n·e; turning a body about its rotation centre by dθ changes it by −(moment of the unit force
// on that body)·dθ.
double Sensitivity(const StageContact& s, const StageDof& d) {
  const PotentialContact& c = s.contact;
  switch (d.kind) {
    case StageDof::kSunRotation:
      return s.body_a == kSunBody ? -c.lever_a : 0.0;
    case StageDof::kSunX:
      return s.body_a == kSunBody ? c.normal.x() : 0.0;
    case StageDof::kSunY:
      return s.body_a == kSunBody ? c.normal.y() : 0.0;
    case StageDof::kPlanetRotation: {
      const int body = PlanetBody(d.planet);
      if (s.body_a == body) return -c.lever_a;
      if (s.body_b == body) return -c.lever_b;
      return 0.0;
    }
    case StageDof::kPlanetX:
    case StageDof::kPlanetY: {
      const int body = PlanetBody(d.planet);
      const double nc = d.kind == StageDof::kPlanetX ? c.normal.x() : c.normal.y();
      if (s.body_a == body) return nc;
      if (s.body_b == body) return -nc;
      return 0.0;
    }
  }
  return 0.0;
}

}  // namespace

solvers::LocalTermParameters ContactLocalTerm(const geometry::PotentialContact& contact,
                                              const geometry::Gear& a, const geometry::Gear& b,
                                              const Material& material,
                                              solvers::PlaneAssumption plane, double depth_a,
                                              double depth_b, const std::string& label) {
  solvers::LocalTermParameters l;
  l.face_width = std::min(a.spec().face_width, b.spec().face_width);
  l.plane = plane;
  const double curvature = 1.0 / contact.curvature_radius_a + 1.0 / contact.curvature_radius_b;
  if (!(curvature > 0) || !std::isfinite(curvature)) {
    throw std::invalid_argument("contact " + label + ": curvature radii " +
                                std::to_string(contact.curvature_radius_a) + " m and " +
                                std::to_string(contact.curvature_radius_b) +
                                " m give no positive reduced radius");
  }
  l.reduced_radius = 1.0 / curvature;
  l.body[0] = {material.youngs_modulus, material.poisson_ratio, depth_a};
  l.body[1] = {material.youngs_modulus, material.poisson_ratio, depth_b};
  return l;
}

StageProblem BuildStageProblem(const Scene& scene, const geometry::Stage& stage,
                               const geometry::StagePoses& poses, const StageCompliance& compliance,
                               const QuasiStaticSetup& setup) {
  StageProblem p;
  p.contacts = SearchStage(stage, poses, scene.gap_window);
  if (p.contacts.empty()) {
    throw std::invalid_argument("stage: no potential contact within the gap window of " +
                                std::to_string(scene.gap_window * 1e6) + " um");
  }
  // DOFs and their support stiffness (0: an equality; k: an elastic bearing, G F + k λ = W).
  std::vector<double> support;
  p.dofs.push_back({StageDof::kSunRotation, 0});
  support.push_back(0.0);
  if (setup.sun != SunSupport::kFixed) {
    const double s_sun = setup.sun == SunSupport::kElastic ? setup.sun_stiffness : 0.0;
    p.dofs.push_back({StageDof::kSunX, 0});
    p.dofs.push_back({StageDof::kSunY, 0});
    support.insert(support.end(), {s_sun, s_sun});
  }
  for (int i = 0; i < stage.planets(); ++i) {
    p.dofs.push_back({StageDof::kPlanetRotation, i});
    support.push_back(0.0);
    if (setup.planet_stiffness > 0) {
      p.dofs.push_back({StageDof::kPlanetX, i});
      p.dofs.push_back({StageDof::kPlanetY, i});
      support.insert(support.end(), {setup.planet_stiffness, setup.planet_stiffness});
    }
  }

  const int n = static_cast<int>(p.contacts.size()), m = static_cast<int>(p.dofs.size());
  solvers::ContactProblemData& d = p.data;
  d.name = scene.name + " @ carrier " + std::to_string(geometry::Deg(poses.carrier_angle)) + " deg";
  d.compliance = compliance.Matrix(stage, poses, p.contacts);
  d.overlap.resize(n);
  d.equality_matrix.resize(m, n);
  d.equality_rhs = Eigen::VectorXd::Zero(m);
  d.equality_rhs(0) = scene.sun_torque;  // G F = W: Σ −lever_sun F = T_sun
  for (int j = 0; j < n; ++j) {
    const StageContact& s = p.contacts[j];
    d.overlap(j) = s.contact.overlap;
    for (int k = 0; k < m; ++k) d.equality_matrix(k, j) = Sensitivity(s, p.dofs[k]);
    d.contact_labels.push_back(s.Label());
    if (!setup.local_terms) continue;
    d.local.push_back(ContactLocalTerm(s.contact, BodyGear(stage, s.body_a),
                                       BodyGear(stage, s.body_b), scene.material, setup.plane,
                                       compliance.JoiningDepth(s.body_a),
                                       compliance.JoiningDepth(s.body_b), s.Label()));
  }
  for (const StageDof& dof : p.dofs) d.multiplier_labels.push_back(dof.Label());
  if (std::any_of(support.begin(), support.end(), [](double v) { return v > 0; })) {
    d.support_stiffness = Eigen::VectorXd::Map(support.data(), m).asDiagonal();
  }
  return p;
}

QuasiStaticSetup SetupFromScene(const Scene& scene) {
  QuasiStaticSetup s;
  s.sun = scene.supports.sun;
  s.sun_stiffness = scene.supports.sun_stiffness;
  s.planet_stiffness = scene.supports.planet_stiffness;
  s.plane = scene.model.plane;
  return s;
}

geometry::StagePoses Displace(const geometry::StagePoses& poses, const std::vector<StageDof>& dofs,
                              const Eigen::VectorXd& lambda) {
  geometry::StagePoses out = poses;
  auto turn = [](geometry::GearPose& g, double angle) {
    g.rotation += angle;
    g.geometric_centre =
        g.rotation_centre + geometry::Rotate(g.geometric_centre - g.rotation_centre, angle);
  };
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const double v = lambda(static_cast<Eigen::Index>(k));
    switch (dofs[k].kind) {
      case StageDof::kSunRotation:
        turn(out.sun, v);
        break;
      case StageDof::kSunX:
        out.sun.rotation_centre.x() += v;
        out.sun.geometric_centre.x() += v;
        break;
      case StageDof::kSunY:
        out.sun.rotation_centre.y() += v;
        out.sun.geometric_centre.y() += v;
        break;
      case StageDof::kPlanetRotation:
        turn(out.planets.at(dofs[k].planet), v);
        break;
      case StageDof::kPlanetX:
      case StageDof::kPlanetY: {
        geometry::GearPose& g = out.planets.at(dofs[k].planet);
        const Vec2 e = dofs[k].kind == StageDof::kPlanetX ? Vec2(v, 0.0) : Vec2(0.0, v);
        g.rotation_centre += e;
        g.geometric_centre += e;
        break;
      }
    }
  }
  return out;
}

}  // namespace epicycle::transmission
