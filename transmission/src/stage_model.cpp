#include "epicycle/transmission/stage_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/load_sharing.hpp"

namespace epicycle::transmission {

using geometry::PotentialContact;
using geometry::Vec2;

void StageSetup::Validate() const {
  auto check = [](const char* field, double v) {
    if (!std::isfinite(v) || v < 0)
      throw std::invalid_argument(std::string("supports: ") + field + " = " + std::to_string(v) +
                                  " N/m: must be finite and >= 0");
  };
  check("sun_stiffness", sun_stiffness);
  check("planet_stiffness", planet_stiffness);
  if (sun == SunSupport::kElastic && !(sun_stiffness > 0))
    throw std::invalid_argument("supports: an elastic sun needs sun_stiffness > 0 N/m");
  if (!(gap_window > 0) || !std::isfinite(gap_window))
    throw std::invalid_argument("contact: gap_window_um = " + std::to_string(gap_window * 1e6) +
                                ": must be finite and > 0");
}

StageSetup SetupFromScene(const Scene& scene) {
  StageSetup s;
  s.name = scene.name;
  s.sun = scene.supports.sun;
  s.sun_stiffness = scene.supports.sun_stiffness;
  s.planet_stiffness = scene.supports.planet_stiffness;
  s.gap_window = scene.gap_window;
  s.damage = scene.damage;
  s.face_width = scene.face_width;
  s.wind_up_sun_torque = scene.loads.sun_torque;
  return s;
}

StageModel::StageModel(const geometry::Stage& stage, const StageCompliance& compliance,
                       const StageSetup& setup)
    : stage_(stage),
      compliance_(compliance),
      setup_(setup),
      damage_(setup.damage, BodyNames(PlanetBody(stage.planets()))) {
  setup_.Validate();
  helical_ = IsHelicalStage(stage_);
  if (helical_ && !setup_.face_width.active())
    throw std::invalid_argument(
        "face_width.slices = " + std::to_string(setup_.face_width.slices) +
        ": a helical stage needs slices >= 2 (its contact lines cross the face width; "
        "docs/model.md §10)");
  if (setup_.face_width.active()) {
    // A fixed ring: the carrier's torque balances the sun's and the ring's, T_c = −T_s (1 + z_r/z_s).
    const double ratio = static_cast<double>(stage_.ring().spec().teeth) / stage_.sun().spec().teeth;
    faces_ = FaceWidthModel(setup_.face_width, stage_, -setup_.wind_up_sun_torque * (1 + ratio));
  }
  // DOFs and their support stiffness (0: an equality; k: an elastic bearing, G F + k λ = W).
  dofs_.push_back({StageDof::kSunRotation, 0});
  support_.push_back(0.0);
  if (setup_.sun != SunSupport::kFixed) {
    const double s_sun = setup_.sun == SunSupport::kElastic ? setup_.sun_stiffness : 0.0;
    dofs_.push_back({StageDof::kSunX, 0});
    dofs_.push_back({StageDof::kSunY, 0});
    support_.insert(support_.end(), {s_sun, s_sun});
  }
  for (int i = 0; i < stage_.planets(); ++i) {
    dofs_.push_back({StageDof::kPlanetRotation, i});
    support_.push_back(0.0);
    if (setup_.planet_stiffness > 0) {
      dofs_.push_back({StageDof::kPlanetX, i});
      dofs_.push_back({StageDof::kPlanetY, i});
      support_.insert(support_.end(), {setup_.planet_stiffness, setup_.planet_stiffness});
    }
  }
}

const geometry::Gear& StageModel::BodyGear(int body) const {
  if (body == kSunBody) return stage_.sun();
  if (body == kRingBody) return stage_.ring();
  return stage_.planet(body - 2);
}

ContactTerms StageModel::Terms(const geometry::StagePoses& poses) const {
  ContactTerms t;
  const StageOutcome o = Terms(poses, &t);
  if (!o.ok()) throw std::runtime_error(setup_.name + ": " + o.message);
  return t;
}

StageOutcome StageModel::Terms(const geometry::StagePoses& poses, ContactTerms* terms,
                               std::vector<geometry::TipRoundReuse>* reuse) const {
  if (helical_) return HelicalTerms(poses, terms);
  ContactTerms& t = *terms;
  // With slices, the search and the compliance fill the plane buffers that Expand splits.
  const bool sliced = faces_.active();
  std::vector<StageContact>& found = sliced ? t.plane_contacts : t.contacts;
  if (StageOutcome o = SearchStage(stage_, poses, setup_.gap_window, &found, reuse); !o.ok())
    return o;
  const int n = static_cast<int>(found.size());
  t.local.clear();
  if (n == 0) {
    t.compliance_terms.clear();
    t.contacts.clear();
    t.overlap.resize(0);
    t.compliance.resize(0, 0);
    return {};
  }
  if (StageOutcome o = compliance_.TryMatrix(stage_, poses, found,
                                             sliced ? &t.plane_compliance : &t.compliance);
      !o.ok())
    return o;
  if (sliced) {
    faces_.Expand(poses, damage_, &t);
  } else {
    t.compliance_terms.clear();
    t.overlap.resize(n);
    for (int j = 0; j < n; ++j) t.overlap(j) = t.contacts[j].contact.overlap;
    if (!damage_.empty()) SplitDamaged(&t);
  }
  return LocalTerms(&t);
}

StageOutcome StageModel::HelicalTerms(const geometry::StagePoses& poses,
                                      ContactTerms* terms) const {
  // Each slice at its own section reads its own flank points: no Kronecker structure.
  terms->compliance_terms.clear();
  if (StageOutcome o = HelicalSliceTerms(stage_, compliance_, faces_, damage_, poses,
                                         setup_.gap_window, terms);
      !o.ok())
    return o;
  if (terms->size() == 0) return {};
  return LocalTerms(terms);
}

StageOutcome StageModel::LocalTerms(ContactTerms* terms) const {
  ContactTerms& t = *terms;
  if (setup_.local_terms) {
    t.local.resize(static_cast<std::size_t>(t.size()));
    for (int j = 0; j < t.size(); ++j) {
      const StageContact& s = t.contacts[j];
      StageOutcome o = ContactLocalTerm(s, BodyGear(s.body_a), BodyGear(s.body_b),
                                        compliance_.material(), compliance_.plane(),
                                        compliance_.JoiningDepth(s.body_a),
                                        compliance_.JoiningDepth(s.body_b), &t.local[j]);
      if (!o.ok()) return o;
      // A helical slice's term per unit length of contact line (helical_slices.hpp).
      if (helical_) t.local[j].face_width *= LocalWidthFactor(BodyGear(s.body_a), BodyGear(s.body_b));
    }
  }
  return {};
}

void StageModel::SplitDamaged(ContactTerms* terms) const {
  ContactTerms& t = *terms;
  const int n = t.size();
  std::vector<int> body_a(n), body_b(n), source;
  std::vector<PotentialContact> found(n);
  std::vector<ContactStrip> strips;
  for (int j = 0; j < n; ++j) {
    body_a[j] = t.contacts[j].body_a;
    body_b[j] = t.contacts[j].body_b;
    found[j] = t.contacts[j].contact;
  }
  if (!SplitContacts(damage_, body_a, body_b, found, setup_.gap_window, setup_.local_terms,
                     &source, &strips))
    return;
  // The compliance was built for the searched contacts: each strip takes its contact's rows
  // (built again for a repeated point, the diagonal's joining-depth term would differ).
  std::vector<StageContact> parts;
  parts.reserve(source.size());
  for (std::size_t s = 0; s < source.size(); ++s) {
    StageContact c = t.contacts[static_cast<std::size_t>(source[s])];
    c.width_fraction = strips[s].width_fraction;
    c.pit_depth = strips[s].depth;
    c.part = strips[s].part;
    c.contact.overlap -= strips[s].depth;
    parts.push_back(c);
  }
  t.compliance = ExpandCompliance(t.compliance, source);
  t.contacts = std::move(parts);
  t.overlap.resize(t.size());
  for (int j = 0; j < t.size(); ++j) t.overlap(j) = t.contacts[j].contact.overlap;
}

namespace {

// ∂δ/∂q for one contact and one DOF: translating A along e changes the overlap by n·e, B by
// −n·e; turning a body about its rotation centre by dθ changes it by −(moment of the unit force
// on that body)·dθ.
double Sensitivity(const StageContact& s, const StageDof& d) {
  const PotentialContact& c = s.contact;
  auto on_body = [&](int body, double on_a, double on_b) {
    if (s.body_a == body) return on_a;
    if (s.body_b == body) return on_b;
    return 0.0;
  };
  switch (d.kind) {
    case StageDof::kSunRotation:
      return on_body(kSunBody, -c.lever_a, -c.lever_b);
    case StageDof::kSunX:
      return on_body(kSunBody, c.normal.x(), -c.normal.x());
    case StageDof::kSunY:
      return on_body(kSunBody, c.normal.y(), -c.normal.y());
    case StageDof::kPlanetRotation:
      return on_body(PlanetBody(d.planet), -c.lever_a, -c.lever_b);
    case StageDof::kPlanetX:
      return on_body(PlanetBody(d.planet), c.normal.x(), -c.normal.x());
    case StageDof::kPlanetY:
      return on_body(PlanetBody(d.planet), c.normal.y(), -c.normal.y());
    case StageDof::kRingRotation:
      return on_body(kRingBody, -c.lever_a, -c.lever_b);
    case StageDof::kRingX:
      return on_body(kRingBody, c.normal.x(), -c.normal.x());
    case StageDof::kRingY:
      return on_body(kRingBody, c.normal.y(), -c.normal.y());
  }
  return 0.0;
}

}  // namespace

Eigen::MatrixXd StageModel::Sensitivity(const ContactTerms& terms,
                                        const std::vector<StageDof>& dofs) const {
  const int n = terms.size(), m = static_cast<int>(dofs.size());
  Eigen::MatrixXd g(m, n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < m; ++k) g(k, j) = transmission::Sensitivity(terms.contacts[j], dofs[k]);
  return g;
}

void StageModel::CheckLoads(const StageLoads& loads) const {
  const double t = loads.sun_torque;
  if (!(t != 0) || !std::isfinite(t))
    throw std::invalid_argument("load: sun_torque_Nm = " + std::to_string(t) +
                                ": must be finite and non-zero (its sign selects the loaded "
                                "flanks)");
  if ((t > 0 ? 1 : -1) != stage_.sun_mesh_side())
    throw std::invalid_argument(
        "load: sun_torque_Nm = " + std::to_string(t) +
        ": the stage's loaded flanks were built for a torque of the other sign (the scene's "
        "sun_torque_Nm selects them; a changed torque must keep its sign)");
}

Eigen::VectorXd StageModel::LoadVector(const std::vector<StageDof>& dofs,
                                       const StageLoads& loads) const {
  CheckLoads(loads);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs.size()));
  for (std::size_t k = 0; k < dofs.size(); ++k)
    if (dofs[k].kind == StageDof::kSunRotation) w(static_cast<Eigen::Index>(k)) = loads.sun_torque;
  return w;
}

StageOutcome StageModel::Problem(const geometry::StagePoses& poses, const StageLoads& loads,
                                 StageProblem* problem) const {
  ContactTerms t;
  if (StageOutcome o = Terms(poses, &t); !o.ok()) return o;
  if (t.contacts.empty()) {
    return {StageStatus::kNoContact, "no potential contact within the gap window of " +
                                         std::to_string(setup_.gap_window * 1e6) + " um"};
  }
  StageProblem& p = *problem;
  p = {};
  p.dofs = dofs_;
  solvers::ContactProblemData& d = p.data;
  d.name = setup_.name + " @ carrier " + std::to_string(geometry::Deg(poses.carrier_angle)) + " deg";
  d.equality_matrix = Sensitivity(t, dofs_);  // G F = W: Σ −lever_sun F = T_sun
  d.equality_rhs = LoadVector(dofs_, loads);
  d.compliance = std::move(t.compliance);
  d.compliance_terms = std::move(t.compliance_terms);
  d.overlap = std::move(t.overlap);
  d.local = std::move(t.local);
  for (const StageContact& s : t.contacts) d.contact_labels.push_back(s.Label());
  for (const StageDof& dof : dofs_) d.multiplier_labels.push_back(dof.Label());
  if (std::any_of(support_.begin(), support_.end(), [](double v) { return v > 0; })) {
    d.support_stiffness =
        Eigen::VectorXd::Map(support_.data(), static_cast<Eigen::Index>(support_.size()))
            .asDiagonal();
  }
  p.contacts = std::move(t.contacts);
  return {};
}

geometry::StagePoses StageModel::Displace(const geometry::StagePoses& poses,
                                          const std::vector<StageDof>& dofs,
                                          const Eigen::VectorXd& q) {
  geometry::StagePoses out = poses;
  Displace(dofs, q, &out);
  return out;
}

void StageModel::Displace(const std::vector<StageDof>& dofs, const Eigen::VectorXd& q,
                          geometry::StagePoses* poses) {
  geometry::StagePoses& out = *poses;
  auto turn = [](geometry::GearPose& g, double angle) {
    g.rotation += angle;
    g.geometric_centre =
        g.rotation_centre + geometry::Rotate(g.geometric_centre - g.rotation_centre, angle);
  };
  auto move = [](geometry::GearPose& g, const Vec2& e) {
    g.rotation_centre += e;
    g.geometric_centre += e;
  };
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const double v = q(static_cast<Eigen::Index>(k));
    switch (dofs[k].kind) {
      case StageDof::kSunRotation:
        turn(out.sun, v);
        break;
      case StageDof::kSunX:
        move(out.sun, Vec2(v, 0.0));
        break;
      case StageDof::kSunY:
        move(out.sun, Vec2(0.0, v));
        break;
      case StageDof::kPlanetRotation:
        turn(out.planets.at(dofs[k].planet), v);
        break;
      case StageDof::kPlanetX:
        move(out.planets.at(dofs[k].planet), Vec2(v, 0.0));
        break;
      case StageDof::kPlanetY:
        move(out.planets.at(dofs[k].planet), Vec2(0.0, v));
        break;
      case StageDof::kRingRotation:
        turn(out.ring, v);
        break;
      case StageDof::kRingX:
        move(out.ring, Vec2(v, 0.0));
        break;
      case StageDof::kRingY:
        move(out.ring, Vec2(0.0, v));
        break;
    }
  }
}

double StageModel::DisplacementSize(const std::vector<StageDof>& dofs,
                                    const Eigen::VectorXd& q) const {
  double worst = 0;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    double scale = 1.0;
    if (dofs[k].kind == StageDof::kSunRotation) scale = stage_.sun().base_radius();
    if (dofs[k].kind == StageDof::kPlanetRotation)
      scale = stage_.planet(dofs[k].planet).base_radius();
    if (dofs[k].kind == StageDof::kRingRotation) scale = stage_.ring().base_radius();
    worst = std::max(worst, std::abs(q(static_cast<Eigen::Index>(k))) * scale);
  }
  return worst;
}

namespace {

// Σ over planet i's sun-mesh contacts of the moment of the contact on the sun.
std::vector<double> SunMoments(int planets, const std::vector<StageContact>& contacts,
                               const Eigen::VectorXd& force) {
  std::vector<double> out(planets, 0.0);
  for (std::size_t j = 0; j < contacts.size() && force.size() > 0; ++j) {
    const StageContact& s = contacts[j];
    if (s.body_a != kSunBody) continue;
    out[s.planet] += s.contact.lever_a * force(static_cast<Eigen::Index>(j));
  }
  return out;
}

}  // namespace

std::vector<double> StageModel::SunMeshTorques(const std::vector<StageContact>& contacts,
                                               const Eigen::VectorXd& force) const {
  return SunMoments(stage_.planets(), contacts, force);
}

std::vector<double> StageModel::LoadSharing(const std::vector<StageContact>& contacts,
                                            const Eigen::VectorXd& force, double sun_torque) const {
  return LoadSharingRatios(SunMeshTorques(contacts, force), sun_torque);
}

}  // namespace epicycle::transmission
