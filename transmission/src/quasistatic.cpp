#include "epicycle/transmission/quasistatic.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/transmission/contact_kinematics.hpp"
#include "epicycle/transmission/geometric_iteration.hpp"
#include "epicycle/io/number_format.hpp"
#include "epicycle/transmission/load_sharing.hpp"
#include "epicycle/transmission/pin.hpp"
#include "ordered_chunks.hpp"

namespace epicycle::transmission {

void QuasiStaticOptions::Validate() const {
  if (max_geometric_iterations < 1)
    throw std::invalid_argument("quasistatic: max_geometric_iterations = " +
                                std::to_string(max_geometric_iterations) + ": must be at least 1");
  if (!(geometric_tolerance > 0) || !std::isfinite(geometric_tolerance))
    throw std::invalid_argument("quasistatic: geometric_tolerance = " +
                                std::to_string(geometric_tolerance) + " m: must be finite and > 0");
  if (threads < 0)
    throw std::invalid_argument("quasistatic: threads = " + std::to_string(threads) +
                                ": must be >= 0 (0: one per core)");
  contact.Validate();
  if (friction.law != FrictionLaw::kOff) {
    friction.Validate();
    if (!(sun_speed > 0) || !std::isfinite(sun_speed))
      throw std::invalid_argument("quasistatic: sun_speed = " + std::to_string(sun_speed) +
                                  " rad/s: friction " + FrictionLawName(friction.law) +
                                  " needs the speed of the rigid kinematics finite and > 0 "
                                  "([dynamics] sun_speed_rpm)");
  }
}

std::vector<std::string> RestFrictionNames() {
  std::vector<std::string> names = io::Names(kFrictionLawNames);
  names.insert(names.begin() + 1, "scene");  // after "off"
  return names;
}

void SetRestFriction(const DynamicSettings& scene, const std::string& choice,
                     QuasiStaticOptions* options) {
  if (choice == "off") {
    options->friction = NoFriction();
    return;
  }
  options->friction = scene.friction;
  options->sun_speed = scene.sun_speed;
  if (choice == "scene") return;
  try {
    options->friction.law = FrictionLawFromName(choice);
  } catch (const std::invalid_argument&) {
    std::string names;
    for (const std::string& n : RestFrictionNames()) names += (names.empty() ? "" : ", ") + n;
    throw std::invalid_argument("friction = \"" + choice + "\": must be one of " + names);
  }
}

namespace {

// Friction at rest (docs/model.md §9): the rigid kinematics of the scene's speed at one carrier
// position give each contact its surface velocities; the law gives φ_j = μ_s(F_j, u_A, u_B) F_j.
class RestFriction {
 public:
  RestFriction(const StageModel& model, double carrier_angle, const QuasiStaticOptions& options,
               const StageLoads& loads)
      : model_(model),
        law_(options.friction),
        modulus_(ContactModulus(model.material())),
        carrier_speed_(RigidCarrierSpeed(model.stage(), options.sun_speed, loads.sun_torque)),
        carrier_angle_(carrier_angle) {
    RigidBodyMotion(model.stage(), carrier_angle, carrier_speed_, &motion_);
  }

  // φ_j and v_s,j of the forces `force` on the problem's contacts at `poses`; with `load`, the
  // generalised loads of the friction forces on the problem's DOFs added to it.
  void Evaluate(const StageProblem& problem, const geometry::StagePoses& poses,
                const Eigen::VectorXd& force, Eigen::VectorXd* phi, Eigen::VectorXd* sliding,
                Eigen::VectorXd* load) const {
    const int n = static_cast<int>(problem.contacts.size());
    phi->setZero(n);
    sliding->setZero(n);
    for (int j = 0; j < n; ++j) {
      const StageContact& s = problem.contacts[static_cast<std::size_t>(j)];
      const SurfaceVelocity u = ContactSurfaceVelocity(model_, s, poses, motion_);
      (*sliding)(j) = u.ua - u.ub;
      const double f = std::max(force(j), 0.0);
      if (!(f > 0)) continue;
      const solvers::LocalTermParameters* local =
          problem.data.local.empty() ? nullptr : &problem.data.local[static_cast<std::size_t>(j)];
      (*phi)(j) =
          FrictionForce(law_, ContactFrictionState(model_, s, local, modulus_), f, u.ua, u.ub);
      if (load != nullptr) AddPairLoad(s, poses, (*phi)(j)*u.tangent, problem.dofs, *load);
    }
  }

  // The friction outputs of a converged position: φ, v_s, P_f, P_in, P_out and the load-sharing
  // ratios of the whole sun-mesh torques.
  void Outputs(const geometry::StagePoses& poses, const StageLoads& loads,
               PositionResult* r) const {
    const StageProblem& p = r->problem;
    const Eigen::VectorXd& force = r->solution.force;
    Evaluate(p, poses, force, &r->friction_force, &r->sliding_velocity, nullptr);
    r->friction_tangent.assign(p.contacts.size(), Eigen::Vector2d::Zero());
    r->friction_power = r->friction_force.dot(r->sliding_velocity);
    const geometry::Stage& stage = model_.stage();
    r->input_power = loads.sun_torque * carrier_speed_ * stage.sun_ratio();
    std::vector<double> sun_torque = model_.SunMeshTorques(p.contacts, force);
    std::vector<geometry::Vec2> planet_force(static_cast<std::size_t>(stage.planets()),
                                             geometry::Vec2::Zero());
    const std::vector<StageDof> sun_rotation = {{StageDof::kSunRotation, 0}};
    for (std::size_t j = 0; j < p.contacts.size(); ++j) {
      const StageContact& s = p.contacts[j];
      const Eigen::Index k = static_cast<Eigen::Index>(j);
      const SurfaceVelocity u = ContactSurfaceVelocity(model_, s, poses, motion_);
      r->friction_tangent[j] = u.tangent;
      const geometry::Vec2 on_b =
          std::max(force(k), 0.0) * s.contact.normal + r->friction_force(k) * u.tangent;
      const double sign = s.body_b == PlanetBody(s.planet) ? 1.0 : -1.0;
      planet_force[static_cast<std::size_t>(s.planet)] += sign * on_b;
      if (s.body_a != kSunBody) continue;
      Eigen::VectorXd moment = Eigen::VectorXd::Zero(1);
      AddPairLoad(s, poses, r->friction_force(k) * u.tangent, sun_rotation, moment);
      sun_torque[static_cast<std::size_t>(s.planet)] += moment(0);
    }
    double carrier_torque = 0;
    for (int i = 0; i < stage.planets(); ++i) {
      const geometry::Vec2 pin = stage.Pin(i, carrier_angle_);
      const geometry::Vec2& f = planet_force[static_cast<std::size_t>(i)];
      carrier_torque += pin.x() * f.y() - pin.y() * f.x();
    }
    r->output_power = carrier_torque * carrier_speed_;
    r->load_sharing = LoadSharingRatios(sun_torque, loads.sun_torque);
  }

 private:
  const StageModel& model_;
  FrictionModel law_;
  double modulus_ = 0, carrier_speed_ = 0, carrier_angle_ = 0;
  std::vector<BodyMotion> motion_;
};

// The forces of `from` carried to the same tooth pairs of `to` (StageContact::SameToothPair:
// planet, mesh, flank side, teeth, pitted strip and slice; the kind may differ): where a contact
// moves between a flank and a tip round as the members move by the iterations' increments, its
// friction load goes with it (CarryForces, which tells the kinds apart, would drop it and the
// fixed point would cycle between the two states). Each slice and strip keeps its own force: the
// slices of a tooth pair carry different loads (a tilt, a lead, a helix), and the friction of
// another slice's force would leave every iteration's force change at the spread between them.
void CarryPairForces(const std::vector<StageContact>& from, const Eigen::VectorXd& force,
                     const std::vector<StageContact>& to, Eigen::VectorXd* out) {
  out->setZero(static_cast<Eigen::Index>(to.size()));
  for (std::size_t j = 0; j < to.size(); ++j) {
    const StageContact& t = to[j];
    for (std::size_t i = 0; i < from.size(); ++i) {
      const StageContact& f = from[i];
      if (f.SameToothPair(t)) {
        (*out)(static_cast<Eigen::Index>(j)) = force(static_cast<Eigen::Index>(i));
        if (f.contact.kind == t.contact.kind) break;  // else a later one of the same kind wins
      }
    }
  }
}

// Pins of finite stiffness (pin.hpp): a fixed point on the planets' tilts alongside the geometric
// iteration. Each problem is built with the tilts (GearPose::axis_slope of this position's own
// poses, never the shared model) that the pins take under the forces of the previous solve (a
// neighbour's tilts for the first, else none); they have settled when the gap they change across
// the face, b |Δt|, moves by at most the geometric tolerance. With friction at rest both fixed
// points share the iteration, each change taken relative to its own tolerance.
class PinTilts {
 public:
  PinTilts(const StageModel& model, const QuasiStaticOptions& options)
      : model_(model),
        pins_(model.face_width().pins()),
        tolerance_(options.geometric_tolerance),
        face_(std::max(model.face_width().MeshWidth(false), model.face_width().MeshWidth(true))) {}
  bool active() const { return pins_.active(); }

  // Starts `poses` from the neighbour's tilts (or none) and adds the tilts' update to
  // `fixed_point` (after friction's, if it has one); `contacts` and `built` are those of the
  // problem each solve answers.
  void Install(const PositionResult* neighbour, const std::vector<StageContact>& contacts,
               const geometry::StagePoses& built, geometry::StagePoses* poses,
               ForceFixedPoint* fixed_point) {
    for (std::size_t i = 0; i < poses->planets.size(); ++i)
      poses->planets[i].axis_slope =
          neighbour != nullptr && neighbour->pin_tilts.size() == poses->planets.size()
              ? neighbour->pin_tilts[i]
              : Eigen::Vector2d::Zero();
    const std::function<double(const Eigen::VectorXd&)> friction = fixed_point->update;
    const double friction_tolerance = fixed_point->tolerance;
    fixed_point->tolerance = 1;  // both changes are taken relative to their tolerances
    fixed_point->update = [this, &contacts, &built, poses, friction,
                           friction_tolerance](const Eigen::VectorXd& force) {
      const std::vector<PinLoad> load = PinLoadsOf(model_.stage(), built, contacts, force);
      tilt_change_ = 0;
      for (std::size_t i = 0; i < load.size(); ++i) {
        Eigen::Vector2d& t = poses->planets[i].axis_slope;
        const Eigen::Vector2d next = pins_.Tilt(static_cast<int>(i), load[i]);
        tilt_change_ = std::max(tilt_change_, face_ * (next - t).norm());
        t = next;
      }
      double change = tilt_change_ / tolerance_;
      if (friction) {
        friction_change_ = friction(force);
        change = std::max(change, friction_change_ / friction_tolerance);
      }
      return change;
    };
  }

  // The tilts the last problem was built with (`built`: within the tolerance of the settled
  // ones) into `r`; friction's own force change back into `g`; a tilt that has not settled
  // turns the fixed point's status into kTiltNotSettled.
  void Finish(const geometry::StagePoses& built, GeometricIterationResult* g,
              PositionResult* r) const {
    r->pin_tilt_change = tilt_change_;
    for (const geometry::GearPose& p : built.planets) {
      const double c = p.rotation_centre.norm();
      const Eigen::Vector2d er =
          c > 0 ? Eigen::Vector2d(p.rotation_centre / c) : Eigen::Vector2d(1, 0);
      r->pin_tilts.push_back(p.axis_slope);
      r->pin_tilts_carrier.emplace_back(p.axis_slope.dot(er),
                                        p.axis_slope.dot(Eigen::Vector2d(-er.y(), er.x())));
    }
    g->force_change = friction_change_;
    if (g->status == StageStatus::kFrictionNotSettled && tilt_change_ > tolerance_) {
      r->status = StageStatus::kTiltNotSettled;
      r->message = "the planets' tilts on their pins did not settle in " +
                   std::to_string(g->iterations) + " iterations: the last tilt update changed " +
                   "the gap across the face by " + io::Num(tilt_change_) + " m (tolerance " +
                   io::Num(tolerance_) + " m, quasistatic geometric_tolerance)";
    }
  }

 private:
  const StageModel& model_;
  const PinModel& pins_;
  double tolerance_, face_;
  double tilt_change_ = 0, friction_change_ = 0;
};

// One position with the caller's solver (a sweep's worker keeps one for its chunk).
PositionResult Solve(const StageModel& model, double carrier_angle, const StageLoads& loads,
                     const QuasiStaticOptions& options, const PositionResult* neighbour,
                     solvers::ContactSolver& solver) {
  PositionResult r;
  r.carrier_angle = carrier_angle;
  const std::vector<StageDof>& dofs = model.dofs();
  geometry::StagePoses poses = model.KinematicPoses(carrier_angle);
  GeometricIterationOptions iteration;
  iteration.max_iterations = options.max_geometric_iterations;
  iteration.tolerance = options.geometric_tolerance;
  iteration.accept_inaccurate = options.accept_inaccurate;
  GeometricIterationStart start;
  if (neighbour != nullptr && neighbour->converged &&
      neighbour->displacements.size() == static_cast<Eigen::Index>(dofs.size()) &&
      neighbour->solution.force.size() ==
          static_cast<Eigen::Index>(neighbour->problem.contacts.size())) {
    // What carries over is the deviation from the kinematic motion (the loaded TE, the planets'
    // rotations, the floating sun's and elastic pins' deflections); the kinematic poses are those
    // of the new angle. The forces start the first contact solve where the contacts match.
    r.warm_started = true;
    start.displacements = neighbour->displacements;
    poses = StageModel::Displace(poses, dofs, start.displacements);
    start.forces = [&](int, Eigen::VectorXd* force) {
      return CarryForces(neighbour->problem.contacts, neighbour->solution.force, r.problem.contacts,
                         force) > 0;
    };
  }
  const bool root_stress = model.compliance().has_root_stress();
  // Friction at rest: a fixed point on the forces alongside the geometric iteration. Each
  // problem's W carries the friction loads of the forces of the previous solve (carried over to
  // the problem's contacts; a neighbour's for the first, else none); it has settled when the
  // forces change by at most the contact tolerance, relative to the largest.
  std::unique_ptr<RestFriction> friction;
  ForceFixedPoint fixed_point;
  std::vector<StageContact> last_contacts;  // the contacts and forces of the last solve
  Eigen::VectorXd last_force, used_force, phi, sliding;
  geometry::StagePoses built;  // the poses of the last problem (friction, root stress)
  if (options.friction.law != FrictionLaw::kOff) {
    friction = std::make_unique<RestFriction>(model, carrier_angle, options, loads);
    if (r.warm_started) {
      last_contacts = neighbour->problem.contacts;
      last_force = neighbour->solution.force;
    }
    fixed_point.tolerance = options.contact.tolerance;
    fixed_point.update = [&](const Eigen::VectorXd& force) {
      double change = std::numeric_limits<double>::infinity();
      if (used_force.size() == force.size()) {
        const double diff = (force - used_force).cwiseAbs().maxCoeff();
        change = diff == 0 ? 0.0 : diff / force.cwiseAbs().maxCoeff();
      }
      last_contacts = r.problem.contacts;
      last_force = force;
      return change;
    };
  }
  // Pins of finite stiffness: the tilts' fixed point beside the geometric iteration (PinTilts).
  PinTilts tilts(model, options);
  if (tilts.active())
    tilts.Install(r.warm_started ? neighbour : nullptr, r.problem.contacts, built, &poses,
                  &fixed_point);
  GeometricIterationResult g = IterateGeometry(
      [&](solvers::ContactProblemData* data) {
        if (root_stress || friction || tilts.active()) built = poses;
        StageOutcome o = model.Problem(poses, loads, &r.problem);
        if (o.ok() && friction) {
          used_force.setZero(static_cast<Eigen::Index>(r.problem.contacts.size()));
          if (last_force.size() > 0)
            CarryPairForces(last_contacts, last_force, r.problem.contacts, &used_force);
          friction->Evaluate(r.problem, poses, used_force, &phi, &sliding,
                             &r.problem.data.equality_rhs);
        }
        if (o.ok()) *data = r.problem.data;
        return o;
      },
      [&](const Eigen::VectorXd& lambda) {
        poses = StageModel::Displace(poses, dofs, lambda);
        return model.DisplacementSize(dofs, lambda);
      },
      solver, options.contact, iteration, start, fixed_point);
  r.converged = g.converged;
  r.status = g.status;
  r.message = std::move(g.message);
  if (tilts.active()) tilts.Finish(built, &g, &r);
  r.geometric_iterations = g.iterations;
  r.contact_iterations = g.contact_iterations;
  r.solution = std::move(g.solution);
  r.report = g.report;
  r.poses = poses;
  r.displacements = g.total;
  // The problem as solved: with elastic supports, W less the earlier iterations' deflections.
  if (g.rhs.size() > 0) r.problem.data.equality_rhs = g.rhs;
  // Outputs from the last contact problem (solved at the poses before its own small increment).
  const int n = model.planets();
  r.load_sharing = model.LoadSharing(r.problem.contacts, r.solution.force, loads.sun_torque);
  if (model.face_width().active() &&
      r.solution.force.size() == static_cast<Eigen::Index>(r.problem.contacts.size()))
  {
    r.face_loads = FaceLoads(model.stage(), model.face_width().slices(), r.problem.contacts,
                             r.solution.force);
    // Each mesh's misalignment, from its most loaded contact (ISO 6336-1 method C's input).
    std::vector<double> most(r.face_loads.size(), 0.0);
    for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
      const StageContact& c = r.problem.contacts[j];
      const std::size_t m =
          (c.mesh == geometry::MeshKind::kPlanetRing ? static_cast<std::size_t>(n) : 0) +
          static_cast<std::size_t>(c.planet);
      const double f = r.solution.force(static_cast<Eigen::Index>(j));
      if (m >= most.size() || !(f > most[m])) continue;
      most[m] = f;
      const FaceWidthModel::Misalignment a = model.face_width().MeshMisalignment(r.poses, c);
      r.face_loads[m].misalignment_assembly = a.assembly;
      r.face_loads[m].misalignment_deflection = a.deflection;
    }
  }
  if (IsHelicalStage(model.stage()) &&
      r.solution.force.size() == static_cast<Eigen::Index>(r.problem.contacts.size()))
    r.helical = HelicalLoadsOf(model.stage(), poses, r.problem.contacts, r.solution.force);
  if (friction) {
    r.friction = true;
    r.force_change = g.force_change;
    if (r.solution.force.size() == static_cast<Eigen::Index>(r.problem.contacts.size()))
      friction->Outputs(built, loads, &r);
  }
  r.planet_rotations.assign(n, 0.0);
  r.planet_displacements.assign(n, geometry::Vec2::Zero());
  for (std::size_t k = 0; k < dofs.size() && g.total.size() > 0; ++k) {
    const double v = g.total(static_cast<Eigen::Index>(k));
    switch (dofs[k].kind) {
      case StageDof::kSunRotation:
        r.transmission_error = v;
        break;
      case StageDof::kSunX:
        r.sun_displacement.x() = v;
        break;
      case StageDof::kSunY:
        r.sun_displacement.y() = v;
        break;
      case StageDof::kPlanetRotation:
        r.planet_rotations[dofs[k].planet] = v;
        break;
      case StageDof::kPlanetX:
        r.planet_displacements[dofs[k].planet].x() = v;
        break;
      case StageDof::kPlanetY:
        r.planet_displacements[dofs[k].planet].y() = v;
        break;
      default:
        break;
    }
  }
  if (r.converged && root_stress) {
    TangentialLoads rubbing;  // friction at rest: its forces load the teeth too
    const bool rubs = r.friction && r.friction_tangent.size() == r.problem.contacts.size();
    if (rubs) rubbing = {r.friction_force, r.friction_tangent};
    // With slices each slice's stresses are the plane model's at its own line load, the gears'
    // extremes those over the slices (docs/model.md §10, "Stresses across the face").
    std::vector<std::vector<compliance::FilletStress>> slices;
    r.fillet_stress =
        StateFilletStresses(model.compliance(), model.stage(), built, r.problem.contacts,
                            r.solution.force, rubs ? &rubbing : nullptr, &slices);
    if (!r.face_loads.empty())
      AddFaceStresses(r.problem.contacts, r.problem.data.local, r.solution.force, slices,
                      &r.face_loads);
    if (!r.fillet_stress.empty())
      r.root_stress = SummariseRootStress(r.fillet_stress, PlanetBody(model.planets()));
  }
  return r;
}

}  // namespace

PositionResult SolvePosition(const StageModel& model, double carrier_angle, const StageLoads& loads,
                             const QuasiStaticOptions& options) {
  return SolvePosition(model, carrier_angle, loads, options, nullptr);
}

PositionResult SolvePosition(const StageModel& model, double carrier_angle, const StageLoads& loads,
                             const QuasiStaticOptions& options, const PositionResult* neighbour) {
  options.Validate();
  auto solver = solvers::MakeContactSolver(options.backend);
  return Solve(model, carrier_angle, loads, options, neighbour, *solver);
}

std::vector<double> LoadSharingFactors(const PositionResult& r) {
  std::vector<double> l;
  const double n = static_cast<double>(r.load_sharing.size());
  for (double v : r.load_sharing) l.push_back(n * v);
  return l;
}

double MeshLoadFactor(const PositionResult& r) {
  double k = 0.0;
  for (double v : LoadSharingFactors(r)) k = std::max(k, v);
  return k;
}

double SweepAngle(double start, double span, int k, int count) {
  return start + span * k / count;
}

std::vector<double> SweepAngles(double start, double span, int count) {
  if (count < 1)
    throw std::invalid_argument("sweep: positions = " + std::to_string(count) +
                                ": must be at least 1");
  std::vector<double> a;
  for (int k = 0; k < count; ++k) a.push_back(SweepAngle(start, span, k, count));
  return a;
}

std::size_t ResultBytes(const PositionResult& r) {
  const solvers::ContactProblemData& d = r.problem.data;
  auto strings = [](const std::vector<std::string>& v) {
    std::size_t b = v.capacity() * sizeof(std::string);
    for (const std::string& s : v) b += s.capacity() + 1;
    return b;
  };
  auto matrix = [](const auto& m) { return static_cast<std::size_t>(m.size()) * sizeof(double); };
  return sizeof(PositionResult) + r.message.capacity() +
         (r.load_sharing.capacity() + r.planet_rotations.capacity()) * sizeof(double) +
         r.planet_displacements.capacity() * sizeof(geometry::Vec2) +
         r.problem.contacts.capacity() * sizeof(StageContact) +
         r.problem.dofs.capacity() * sizeof(StageDof) + matrix(d.compliance) + matrix(d.overlap) +
         d.local.capacity() * sizeof(solvers::LocalTermParameters) + matrix(d.equality_matrix) +
         matrix(d.equality_rhs) + matrix(d.support_stiffness) + strings(d.contact_labels) +
         strings(d.multiplier_labels) + d.name.capacity() + matrix(r.solution.force) +
         matrix(r.solution.multiplier) + r.poses.planets.capacity() * sizeof(geometry::GearPose) +
         matrix(r.displacements) + matrix(r.friction_force) + matrix(r.sliding_velocity) +
         r.friction_tangent.size() * sizeof(Eigen::Vector2d);
}

void CheckSweepMemory(const PositionResult& sample, std::size_t positions,
                      std::size_t memory_bytes) {
  const double each = static_cast<double>(ResultBytes(sample));
  const double total = each * static_cast<double>(positions),
               limit = 0.5 * static_cast<double>(memory_bytes);
  if (memory_bytes == 0 || total <= limit) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "a sweep of %zu positions keeps about %.1f GB of results in memory (%.1f kB per "
                "position: %zu potential contacts), more than half of the %.1f GB available: at "
                "most %.0f positions",
                positions, total / 1e9, each / 1e3, sample.problem.contacts.size(),
                static_cast<double>(memory_bytes) / 1e9, std::floor(limit / each));
  throw std::invalid_argument(text);
}

std::size_t AvailableMemoryBytes() {
  if (std::FILE* f = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    unsigned long long kb = 0;
    bool found = false;
    while (!found && std::fgets(line, sizeof line, f) != nullptr)
      found = std::sscanf(line, "MemAvailable: %llu kB", &kb) == 1;
    std::fclose(f);
    if (found) return static_cast<std::size_t>(kb) * 1024;
  }
  const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(size)
                               : 0;
}

namespace {

// The sweep with its results in `ring`: position k in slot k mod ring.size(), at least
// min(count, kSweepInFlight + 1) slots (RunOrderedChunks keeps every position in flight within
// kSweepInFlight of the first not yet handed on, and k − 1's slot while k is solved).
void RunSweep(const StageModel& model, const StageLoads& loads, int count,
              const std::function<double(int)>& angle, const QuasiStaticOptions& options,
              std::vector<PositionResult>& ring,
              const std::function<void(const PositionResult&, int)>& on_result,
              const PositionResult* start = nullptr) {
  options.Validate();
  if (count < 0)
    throw std::invalid_argument("sweep: positions = " + std::to_string(count) + ": must be >= 0");
  const std::size_t slots = ring.size();
  auto slot = [&](int k) -> PositionResult& { return ring[static_cast<std::size_t>(k) % slots]; };
  internal::RunOrderedChunks(
      count, options.threads, options.backend,
      [&](int k, bool chunk_first, solvers::ContactSolver& solver) {
        // A chunk's first position cold (position 0 from `start` if given), each next one from
        // its neighbour.
        const PositionResult* neighbour =
            !options.warm_start ? nullptr : !chunk_first ? &slot(k - 1) : k == 0 ? start : nullptr;
        PositionResult r = Solve(model, angle(k), loads, options, neighbour, solver);
        slot(k) = std::move(r);
      },
      [&](int k) {
        if (on_result) on_result(slot(k), k);
      },
      kSweepInFlight);
}

}  // namespace

void SweepEach(const StageModel& model, const StageLoads& loads, int count,
               const std::function<double(int)>& angle, const QuasiStaticOptions& options,
               const std::function<void(const PositionResult&, int)>& on_result,
               const PositionResult* start) {
  std::vector<PositionResult> ring(
      static_cast<std::size_t>(std::clamp(count, 1, kSweepInFlight + 1)));
  RunSweep(model, loads, count, angle, options, ring, on_result, start);
}

std::vector<PositionResult> Sweep(
    const StageModel& model, const StageLoads& loads, const std::vector<double>& carrier_angles,
    const QuasiStaticOptions& options,
    const std::function<void(const PositionResult&, int)>& on_result) {
  const std::size_t count = carrier_angles.size();
  std::vector<PositionResult> out(std::max<std::size_t>(count, 1));
  RunSweep(
      model, loads, static_cast<int>(count),
      [&](int k) { return carrier_angles[static_cast<std::size_t>(k)]; }, options, out,
      [&](const PositionResult& r, int k) {
        if (k == 0 && count > 10000) CheckSweepMemory(r, count, AvailableMemoryBytes());
        if (on_result) on_result(r, k);
      });
  out.resize(count);
  return out;
}

}  // namespace epicycle::transmission
