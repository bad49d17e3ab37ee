#include "epicycle/dynamics/stage_periodic.hpp"

#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "epicycle/io/units.hpp"

namespace epicycle::dynamics {

namespace {

// The most models kept at other parameter values: λ and λ ± h of the parameter derivative.
constexpr std::size_t kCachedModels = 4;

}  // namespace

StagePeriod StagePeriodMeshCycles(const geometry::Stage& stage,
                                  const transmission::Damage& damage) {
  const geometry::StageSpec& spec = stage.spec();
  StagePeriod out;
  auto need = [&](const std::string& what, long teeth) {
    out.mesh_cycles = std::lcm(out.mesh_cycles, teeth);
    out.reasons.push_back(what + ": " + std::to_string(teeth) + " mesh cycles");
  };
  const long zs = spec.sun.teeth, zp = spec.planet.teeth, zr = spec.ring.teeth;
  if (spec.sun_runout.amplitude > 0) need("sun run-out", zs);
  if (spec.ring_runout.amplitude > 0) need("ring run-out", zr);
  for (std::size_t i = 0; i < spec.planet_runouts.size(); ++i)
    if (spec.planet_runouts[i].amplitude > 0)
      need("planet" + std::to_string(i + 1) + " run-out", zp);
  auto damaged = [&](const std::string& gear) {
    const std::string what = gear + " damage";
    if (gear == "sun") need(what, zs);
    else if (gear == "ring") need(what, zr);
    else need(what, zp);
  };
  for (const transmission::Pit& p : damage.pits) damaged(p.gear);
  for (const transmission::Crack& c : damage.cracks) damaged(c.gear);
  return out;
}

StagePeriodicSystem::StagePeriodicSystem(const DynamicModel& model, solvers::Backend backend,
                                         solvers::ContactOptions contact, long mesh_cycles)
    : base_(model),
      contact_(std::move(contact)),
      mesh_cycles_(mesh_cycles),
      solver_(solvers::MakeContactSolver(backend)) {
  if (mesh_cycles < 1)
    throw std::invalid_argument("stage period: mesh_cycles = " + std::to_string(mesh_cycles) +
                                ": must be >= 1");
  defaults_ = DefaultParameters();
}

std::vector<PeriodicParameter> StagePeriodicSystem::parameters() const {
  return {{kSunSpeed, "rpm", io::RadPerSecondToRpm(base_.settings().sun_speed)},
          {kSunTorque, "N·m", base_.loads().sun_torque},
          {kMeshDampingRatio, "-", base_.settings().mesh_damping_ratio}};
}

const DynamicModel& StagePeriodicSystem::ModelAt(const Eigen::VectorXd& p) const {
  if (p.size() == 0 || p == defaults_) return base_;
  for (std::size_t k = 0; k < models_.size(); ++k)
    if (models_[k].p == p) {
      if (k > 0) std::swap(models_[0], models_[k]);
      return *models_[0].model;
    }
  transmission::DynamicSettings s = base_.settings();
  s.sun_speed = io::RpmToRadPerSecond(p(0));
  s.mesh_damping_ratio = p(2);
  transmission::StageLoads loads = base_.loads();
  loads.sun_torque = p(1);
  auto m = std::make_unique<DynamicModel>(base_.stage_model(), s, base_.inertias(), loads);
  m->SetMeshStiffness(base_.sun_mesh_stiffness(), base_.ring_mesh_stiffness());
  m->SetStartAngle(base_.CarrierAngle(0));
  if (models_.size() == kCachedModels) models_.pop_back();
  models_.insert(models_.begin(), Cached{p, std::move(m)});
  return *models_[0].model;
}

double StagePeriodicSystem::Period(const Eigen::VectorXd& p) const {
  return static_cast<double>(mesh_cycles_) * base_.stage_model().stage().mesh_cycle() /
         std::abs(ModelAt(p).carrier_speed());
}

Eigen::MatrixXd StagePeriodicSystem::PeriodMap(const Eigen::VectorXd& p) const {
  const DynamicModel& m = ModelAt(p);
  const double advance = std::remainder(
      std::copysign(static_cast<double>(mesh_cycles_) * m.stage_model().stage().mesh_cycle(),
                    m.carrier_speed()),
      2 * std::numbers::pi);
  if (advance == 0) return {};
  const int n = m.size();
  // S turns the deviations of the end state back by the carrier's advance: R(−Δφ_c) per pair.
  const double c = std::cos(advance), s = std::sin(advance);
  Eigen::MatrixXd map = Eigen::MatrixXd::Identity(2 * n, 2 * n);
  bool any = false;
  for (int i = 0; i < n; ++i) {
    const MotionDof& f = m.dofs()[static_cast<std::size_t>(i)];
    if (f.axis != MotionDof::kX) continue;
    const int j = m.Find(f.member, MotionDof::kY, f.planet);
    if (j < 0) continue;
    any = true;
    for (const int off : {0, n}) {
      map(off + i, off + i) = c;
      map(off + i, off + j) = s;
      map(off + j, off + i) = -s;
      map(off + j, off + j) = c;
    }
  }
  if (!any) return {};
  return map;
}

bool StagePeriodicSystem::EvaluateAt(const DynamicModel& model, double t, const Eigen::VectorXd& y,
                                     Evaluation* at) const {
  const int n = model.size();
  model.Evaluate(t, y.head(n), y.tail(n), *solver_, contact_, warm_valid_ ? &warm_ : nullptr, at,
                 /*energies=*/false);
  ++evaluations_;
  return at->ok;
}

bool StagePeriodicSystem::IsWarm(double t, const Eigen::VectorXd& y,
                                 const Eigen::VectorXd& p) const {
  return warm_valid_ && t == warm_t_ && y == warm_y_ && p.size() == warm_p_.size() &&
         p == warm_p_;
}

bool StagePeriodicSystem::Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                              Eigen::VectorXd* f) const {
  const DynamicModel& model = ModelAt(p);
  if (!EvaluateAt(model, t, y, &scratch_)) return false;
  const int n = model.size();
  f->head(n) = y.tail(n);
  f->tail(n) = scratch_.acceleration;
  std::swap(warm_, scratch_);
  warm_valid_ = true;
  warm_t_ = t;
  warm_y_ = y;
  warm_p_ = p;
  return true;
}

bool StagePeriodicSystem::Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                                   Eigen::MatrixXd* jac) const {
  const DynamicModel& model = ModelAt(p);
  if (!IsWarm(t, y, p)) {
    if (!EvaluateAt(model, t, y, &scratch_)) return false;
    std::swap(warm_, scratch_);
    warm_valid_ = true;
    warm_t_ = t;
    warm_y_ = y;
    warm_p_ = p;
  }
  const int n = model.size();
  Eigen::MatrixXd dd, dv;
  model.Jacobian(t, y.head(n), y.tail(n), warm_, &dd, &dv);
  jac->setZero(2 * n, 2 * n);
  jac->topRightCorner(n, n).setIdentity();
  jac->bottomLeftCorner(n, n) = dd;
  jac->bottomRightCorner(n, n) = dv;
  return jac->allFinite();
}

}  // namespace epicycle::dynamics
