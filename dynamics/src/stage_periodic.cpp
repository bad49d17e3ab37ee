#include "epicycle/dynamics/stage_periodic.hpp"

#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

#include "epicycle/io/units.hpp"

namespace epicycle::dynamics {

namespace {

// The most models kept at other parameter values: λ and λ ± h of the parameter derivative.
constexpr std::size_t kCachedModels = 4;
constexpr double kUm = 1e-6;  // the error keys' unit [m]

}  // namespace

StagePeriod StagePeriodMeshCycles(const geometry::Stage& stage,
                                  const transmission::Damage& damage) {
  return StagePeriodMeshCycles(stage.spec(), damage);
}

StagePeriod StagePeriodMeshCycles(const geometry::StageSpec& spec,
                                  const transmission::Damage& damage) {
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

std::optional<StageErrorKey> ParseStageErrorKey(const std::string& name, int planets) {
  // The gear's index from its scene name: "sun" −1, "ring" −2, "planetK" K − 1; none otherwise.
  auto gear = [&](const std::string& g) -> std::optional<int> {
    if (g == "sun") return -1;
    if (g == "ring") return -2;
    if (g.rfind("planet", 0) != 0 || g.size() == 6) return std::nullopt;
    int k = 0;
    for (std::size_t c = 6; c < g.size(); ++c) {
      if (g[c] < '0' || g[c] > '9' || k > planets) return std::nullopt;
      k = 10 * k + (g[c] - '0');
    }
    if (k < 1 || k > planets || g[6] == '0') return std::nullopt;
    return k - 1;
  };
  std::vector<std::string> part;
  std::size_t at = 0;
  for (std::size_t c; (c = name.find('.', at)) != std::string::npos; at = c + 1)
    part.push_back(name.substr(at, c - at));
  part.push_back(name.substr(at));
  if (part.size() != 4 || part[0] != "errors") return std::nullopt;
  const std::optional<int> g = gear(part[2]);
  if (!g) return std::nullopt;
  StageErrorKey k{name, StageErrorKey::Kind::kPinTangential, *g};
  if (part[1] == "pin" && *g >= 0 && part[3] == "tangential_um") return k;
  if (part[1] == "pin" && *g >= 0 && part[3] == "radial_um") {
    k.kind = StageErrorKey::Kind::kPinRadial;
    return k;
  }
  if (part[1] == "runout" && part[3] == "amplitude_um") {
    k.kind = StageErrorKey::Kind::kRunout;
    return k;
  }
  return std::nullopt;
}

namespace {

// The run-out of gear g (−1 sun, −2 ring, else the planet) in `spec`, the planets' list sized.
geometry::Runout* RunoutOf(geometry::StageSpec* spec, int g) {
  if (g == -1) return &spec->sun_runout;
  if (g == -2) return &spec->ring_runout;
  if (spec->planet_runouts.empty()) spec->planet_runouts.assign(spec->planets, {});
  return &spec->planet_runouts[static_cast<std::size_t>(g)];
}

}  // namespace

double StageErrorKey::Value(const geometry::StageSpec& spec) const {
  geometry::StageSpec s = spec;  // RunoutOf and the pins' list may size an empty list
  if (kind == Kind::kRunout) return RunoutOf(&s, gear)->amplitude / kUm;
  if (s.pin_errors.empty()) return 0;
  const geometry::PinError& e = s.pin_errors[static_cast<std::size_t>(gear)];
  return (kind == Kind::kPinRadial ? e.radial : e.tangential) / kUm;
}

void StageErrorKey::Set(geometry::StageSpec* spec, double value_um) const {
  if (kind == Kind::kRunout) {
    RunoutOf(spec, gear)->amplitude = value_um * kUm;
    return;
  }
  if (spec->pin_errors.empty()) spec->pin_errors.assign(spec->planets, {});
  geometry::PinError& e = spec->pin_errors[static_cast<std::size_t>(gear)];
  (kind == Kind::kPinRadial ? e.radial : e.tangential) = value_um * kUm;
}

StagePeriodicSystem::StagePeriodicSystem(const DynamicModel& model, solvers::Backend backend,
                                         solvers::ContactOptions contact, long mesh_cycles,
                                         std::optional<StageErrorKey> error)
    : base_(model),
      contact_(std::move(contact)),
      mesh_cycles_(mesh_cycles),
      error_(std::move(error)),
      solver_(solvers::MakeContactSolver(backend)) {
  if (mesh_cycles < 1)
    throw std::invalid_argument("stage period: mesh_cycles = " + std::to_string(mesh_cycles) +
                                ": must be >= 1");
  defaults_ = DefaultParameters();
}

std::vector<PeriodicParameter> StagePeriodicSystem::parameters() const {
  std::vector<PeriodicParameter> out{
      {kSunSpeed, "rpm", io::RadPerSecondToRpm(base_.settings().sun_speed)},
      {kSunTorque, "N·m", base_.loads().sun_torque},
      {kMeshDampingRatio, "-", base_.settings().mesh_damping_ratio}};
  if (error_)
    out.push_back({error_->key, "µm", error_->Value(base_.stage_model().stage().spec())});
  return out;
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
  Cached c{p, nullptr, nullptr, nullptr};
  if (error_ && p(3) != defaults_(3)) {
    // The error's value moves the pins or the gears' centres, read by geometry::Stage from its
    // spec: the stage rebuilt with it (its gears generated anew) under the same compliance and
    // setup, which depend on the gears' shapes only.
    const transmission::StageModel& sm = base_.stage_model();
    geometry::StageSpec spec = sm.stage().spec();
    error_->Set(&spec, p(3));
    c.stage = std::make_unique<geometry::Stage>(std::move(spec));
    c.stage_model =
        std::make_unique<transmission::StageModel>(*c.stage, sm.compliance(), sm.setup());
    ++rebuilds_;
  }
  c.model = std::make_unique<DynamicModel>(c.stage_model ? *c.stage_model : base_.stage_model(),
                                           s, base_.inertias(), loads);
  c.model->SetMeshStiffness(base_.sun_mesh_stiffness(), base_.ring_mesh_stiffness());
  c.model->SetStartAngle(base_.CarrierAngle(0));
  if (models_.size() == kCachedModels) models_.pop_back();
  models_.insert(models_.begin(), std::move(c));
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
