#include "epicycle/transmission/fe_compliance.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "epicycle/compliance/compliance_operator.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/compliance/influence_cache.hpp"
#include "epicycle/compliance/root_crack.hpp"
#include "scene_internal.hpp"

namespace epicycle::transmission {

namespace {

compliance::PlaneAssumption ToCompliance(solvers::PlaneAssumption p) {
  return p == solvers::PlaneAssumption::kPlaneStrain ? compliance::PlaneAssumption::kPlaneStrain
                                                     : compliance::PlaneAssumption::kPlaneStress;
}

compliance::OperatorBody Body(const GearTables& tables, int gear, const geometry::GearPose& pose,
                              const std::string& name) {
  compliance::OperatorBody b;
  b.table = &tables.Table(gear);
  b.damaged = tables.Damaged(gear);
  b.centre = pose.geometric_centre;
  b.rotation = pose.rotation;
  b.name = name;
  return b;
}

// A point of flank σ of a gear with thickness error Δs carried onto the nominal body the table is
// built on (compliance::NominalBody): the error turns flank σ by σ·Δs/(2 r_b) about the geometric
// centre (geometry::Gear), so the point is turned back by the opposite angle.
Eigen::Vector2d OnNominalBody(const Eigen::Vector2d& p, const geometry::Gear& gear, int side,
                              const Eigen::Vector2d& centre) {
  const double turn = gear.spec().thickness_error / (2.0 * gear.base_radius());
  if (turn == 0.0) return p;
  const double a = -side * turn, c = std::cos(a), s = std::sin(a);
  const Eigen::Vector2d d = p - centre;
  return centre + Eigen::Vector2d(c * d.x() - s * d.y(), s * d.x() + c * d.y());
}

// The two sides of a potential contact: A pushed along −n at its own closest point, B along +n,
// read on the nominal profiles of the nominal bodies the tables are built on (relief, pitch
// deviations and thickness errors are µm surface modifications that do not change the bodies,
// docs/geometry.md).
compliance::OperatorContact Sides(const geometry::PotentialContact& c, int body_a, int body_b,
                                  const geometry::Gear& gear_a, const geometry::Gear& gear_b,
                                  const Eigen::Vector2d& centre_a, const Eigen::Vector2d& centre_b,
                                  std::string label) {
  compliance::OperatorContact o;
  o.side[0] = {body_a, c.tooth_a, c.side_a, OnNominalBody(c.surface_a, gear_a, c.side_a, centre_a),
               -c.normal};
  o.side[1] = {body_b, c.tooth_b, c.side_b, OnNominalBody(c.surface_b, gear_b, c.side_b, centre_b),
               c.normal};
  o.label = std::move(label);
  return o;
}

// A contact side turned by `angle` about its body's centre (point and force direction).
void TurnSide(compliance::ContactSide* side, const Eigen::Vector2d& centre, double angle) {
  side->point = centre + geometry::Rotate(side->point - centre, angle);
  side->direction = geometry::Rotate(side->direction, angle);
}

}  // namespace

std::string DefaultCacheDirectory() {
  if (const char* d = std::getenv("EPICYCLE_CACHE_DIR"); d != nullptr && *d != '\0') return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d != nullptr && *d != '\0')
    return std::string(d) + "/epicycle";
  if (const char* d = std::getenv("HOME"); d != nullptr && *d != '\0')
    return std::string(d) + "/.cache/epicycle";
  return ".epicycle-cache";
}

namespace {

// The start of a crack placed by the body (Crack::start): ISO's 30° point, or the largest root
// tension of a unit load at the tip-most involute point of the grid on the crack's side (the
// largest bending arm of a load on the involute).
double PlacedStart(const Crack& c, const geometry::Gear& gear,
                   const compliance::InfluenceTable& table) {
  if (c.start == CrackStart::kArc) return c.crack.start_arc;
  if (c.start == CrackStart::kIso30) return compliance::IsoCriticalFilletArc(gear);
  const compliance::FlankGrid& grid = table.grid();
  const double involute =
      compliance::ProfilePath(gear).RoleEnd(geometry::SegmentRole::kInvolute) - grid.form_arc;
  int tip = 0;
  for (int i = 0; i < grid.num_points(); ++i)
    if (grid.arc_length[i] <= involute * (1.0 + 1e-9)) tip = i;
  return compliance::LargestRootTensionArc(
      table, gear, {c.crack.tooth, c.crack.side, grid.arc_length[tip]}, c.crack.side);
}

}  // namespace

GearTables::GearTables(const Scene& scene, const std::vector<const geometry::Gear*>& gears,
                       const std::vector<std::string>& names, const FeComplianceOptions& options)
    : plane_(ToCompliance(scene.model.plane)) {
  if (!options.helical_slices)
    RequireSpur(scene,
                "this run (its gear bodies' FE compliance is built for spur slices only)");
  if (names.size() != gears.size())
    throw std::invalid_argument("GearTables: " + std::to_string(names.size()) + " names for " +
                                std::to_string(gears.size()) + " gears");
  compliance::InfluenceTableOptions o = options.table;
  if (scene.model.join_depth > 0) o.join_depth = scene.model.join_depth;
  o.join_depth_factor = scene.model.join_depth_factor;
  o.mesh.refinement = scene.model.mesh_refinement;
  o.fillet_stress = o.fillet_stress || scene.model.stresses;
  std::map<std::uint64_t, std::shared_ptr<const compliance::InfluenceTable>> built;
  auto table = [&](const geometry::Gear& g, const compliance::ElasticMaterial& material,
                   const compliance::InfluenceTableOptions& opts) {
    const std::uint64_t key = compliance::InfluenceTableKey(g.spec(), material, opts);
    auto it = built.find(key);
    if (it == built.end()) {
      std::shared_ptr<const compliance::InfluenceTable> t;
      try {
        if (options.cache_directory.empty()) {
          t = std::make_shared<const compliance::InfluenceTable>(
              compliance::InfluenceTable::Build(compliance::NominalBody(g), material, opts));
          messages_.push_back("influence table of '" + g.name() + "' built (no disk cache)");
        } else {
          compliance::CacheReport report;
          t = std::make_shared<const compliance::InfluenceTable>(
              compliance::LoadOrBuildInfluenceTable(g, material, opts, options.cache_directory,
                                                    &report));
          messages_.push_back(report.message);
        }
      } catch (const std::invalid_argument& e) {
        // The scene's join depth, which only a body's grid can check: under the user's key.
        const std::string what = e.what();
        const bool depth =
            scene.model.join_depth > 0 && what.find("join_depth h") != std::string::npos;
        const std::string at = depth ? internal::KeyAt(scene, "model.join_depth_mm") : "";
        if (at.empty()) throw;
        throw std::invalid_argument(at + ": " + what);
      }
      it = built.emplace(key, std::move(t)).first;
    }
    return it->second;
  };
  for (std::size_t i = 0; i < gears.size(); ++i) {
    const geometry::Gear& g = *gears[i];
    const compliance::ElasticMaterial material{
        scene.material.youngs_modulus, scene.material.poisson_ratio, g.spec().face_width, plane_};
    const Crack* crack = scene.damage.CrackOn(names[i]);
    if (crack != nullptr && o.fillet_stress)
      throw std::invalid_argument(
          crack->where + ": a root crack on '" + names[i] +
          "' with root stresses asked ([model] stresses, --stresses or --rating): root stresses "
          "are not tabulated on a cracked body (its crack tip is singular); run the stresses of "
          "the healthy stage, or leave the crack out");
    // A crack placed at the largest root tension needs its gear's fillet stresses.
    compliance::InfluenceTableOptions own = o;
    if (crack != nullptr && crack->start == CrackStart::kLargestTension) own.fillet_stress = true;
    tables_.push_back(table(g, material, own));
    damaged_.emplace_back();
    if (crack == nullptr) continue;
    compliance::RootCrack placed = crack->crack;
    try {
      const geometry::Gear nominal = compliance::NominalBody(g);
      placed.start_arc = PlacedStart(*crack, nominal, *tables_.back());
      placed.Validate(nominal);
      if (options.cache_directory.empty()) {
        damaged_.back() = std::make_shared<const compliance::DamagedInfluence>(
            compliance::DamagedInfluence::Build(nominal, material, placed, o));
        messages_.push_back("damaged rows of '" + names[i] + "' built (no disk cache)");
      } else {
        compliance::CacheReport report;
        damaged_.back() = std::make_shared<const compliance::DamagedInfluence>(
            compliance::LoadOrBuildDamagedInfluence(g, material, placed, o, 1, {},
                                                    options.cache_directory, &report));
        messages_.push_back(report.message);
      }
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(crack->where + ": the root crack of '" + names[i] +
                                  "' cannot be modelled: " + e.what());
    }
    messages_.push_back("root crack of '" + names[i] + "' starts at fillet arc " +
                        std::to_string(placed.start_arc * 1e3) + " mm (" + crack->Describe() + ")");
  }
}

GearTables GearTables::Healthy(const std::vector<int>& gears) const {
  GearTables out;
  out.plane_ = plane_;
  for (const int g : gears) {
    if (g < 0 || g >= size())
      throw std::invalid_argument("GearTables::Healthy: gear " + std::to_string(g) +
                                  ": must lie in [0, " + std::to_string(size()) + ")");
    out.tables_.push_back(tables_[static_cast<std::size_t>(g)]);
    out.damaged_.emplace_back();
  }
  return out;
}

namespace {

std::vector<const geometry::Gear*> StageGears(const geometry::Stage& stage) {
  std::vector<const geometry::Gear*> g{&stage.sun(), &stage.ring()};
  for (int i = 0; i < stage.planets(); ++i) g.push_back(&stage.planet(i));
  return g;
}

}  // namespace

FeStageCompliance::FeStageCompliance(const Scene& scene, const geometry::Stage& stage,
                                     const FeComplianceOptions& options)
    : tables_(scene, StageGears(stage), BodyNames(PlanetBody(stage.planets())), options),
      material_(scene.material),
      plane_(scene.model.plane) {
  for (int b = 0; b < PlanetBody(stage.planets()); ++b) names_.push_back(BodyName(b));
}

void FeStageCompliance::Operator(const geometry::Stage& stage, const geometry::StagePoses& poses,
                                 const std::vector<StageContact>& contacts,
                                 std::vector<compliance::OperatorBody>* bodies,
                                 std::vector<compliance::OperatorContact>* oc) const {
  bodies->clear();
  bodies->reserve(static_cast<std::size_t>(PlanetBody(stage.planets())));
  bodies->push_back(Body(tables_, kSunBody, poses.sun, names_[kSunBody]));
  bodies->push_back(Body(tables_, kRingBody, poses.ring, names_[kRingBody]));
  for (int i = 0; i < stage.planets(); ++i)
    bodies->push_back(Body(tables_, PlanetBody(i), poses.planets.at(i), names_.at(PlanetBody(i))));
  auto gear = [&](int body) -> const geometry::Gear& {
    return body == kSunBody    ? stage.sun()
           : body == kRingBody ? stage.ring()
                               : stage.planet(body - PlanetBody(0));
  };
  oc->clear();
  oc->reserve(contacts.size());
  for (const StageContact& s : contacts) {
    oc->push_back(Sides(s.contact, s.body_a, s.body_b, gear(s.body_a), gear(s.body_b),
                        bodies->at(s.body_a).centre, bodies->at(s.body_b).centre, {}));
    // A helical slice was searched with each body's section turned by its lead: its sides are
    // carried back onto the section the poses describe (docs/model.md §10).
    if (s.section_turn_a != 0 || s.section_turn_b != 0) {
      TurnSide(&oc->back().side[0], bodies->at(s.body_a).centre, -s.section_turn_a);
      TurnSide(&oc->back().side[1], bodies->at(s.body_b).centre, -s.section_turn_b);
    }
  }
}

bool FeStageCompliance::has_root_stress() const {
  for (int b = 0; b < tables_.size(); ++b)
    if (!tables_.Table(b).has_fillet_stress()) return false;
  return tables_.size() > 0;
}

std::vector<compliance::FilletStress> FeStageCompliance::FilletStresses(
    const geometry::Stage& stage, const geometry::StagePoses& poses,
    const std::vector<StageContact>& contacts, const Eigen::VectorXd& force,
    const TangentialLoads* friction) const {
  std::vector<compliance::OperatorBody> bodies;
  std::vector<compliance::OperatorContact> oc;
  Operator(stage, poses, contacts, &bodies, &oc);
  if (friction == nullptr) return compliance::FilletStresses(bodies, oc, force);
  const std::size_t n = contacts.size();
  if (static_cast<std::size_t>(friction->force.size()) != n || friction->tangent.size() != n)
    throw std::invalid_argument("FilletStresses: friction loads of " +
                                std::to_string(friction->force.size()) + " forces and " +
                                std::to_string(friction->tangent.size()) + " tangents for " +
                                std::to_string(n) + " contacts");
  // Each friction force as a load at its contact's sides: |φ| along ±sign(φ) t (on B along φ t,
  // on A the opposite), only where the contact carries a normal force (φ = μ F).
  Eigen::VectorXd all(static_cast<Eigen::Index>(2 * n));
  all.head(static_cast<Eigen::Index>(n)) = force;
  for (std::size_t j = 0; j < n; ++j) {
    const auto k = static_cast<Eigen::Index>(j);
    const double phi = force(k) > 0 ? friction->force(k) : 0.0;
    compliance::OperatorContact t = oc[j];
    const Eigen::Vector2d d = (phi < 0 ? -1.0 : 1.0) * friction->tangent[j];
    t.side[0].direction = -d;
    t.side[1].direction = d;
    oc.push_back(std::move(t));
    all(static_cast<Eigen::Index>(n + j)) = std::abs(phi);
  }
  return compliance::FilletStresses(bodies, oc, all);
}

void FeStageCompliance::Assemble(const geometry::Stage& stage, const geometry::StagePoses& poses,
                                 const std::vector<StageContact>& contacts, Eigen::MatrixXd* out,
                                 std::string* off_flank) const {
  // Kept per thread (the compliance is shared by the studies' threads): the dynamic model
  // assembles C on every evaluation without allocating.
  thread_local std::vector<compliance::OperatorBody> bodies;
  thread_local std::vector<compliance::OperatorContact> oc;
  Operator(stage, poses, contacts, &bodies, &oc);
  // The labels only when something is wrong: this is on the dynamic model's hot path.
  auto labelled = [&](std::string text) {
    for (std::size_t j = 0; j < contacts.size(); ++j)
      text += (j == 0 ? "; contacts: " : ", ") + std::to_string(j) + " = " + contacts[j].Label();
    return text;
  };
  try {
    compliance::AssembleCompliance(bodies, oc, out, off_flank);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(labelled(e.what()));
  }
  if (off_flank != nullptr && !off_flank->empty()) *off_flank = labelled(*off_flank);
}

Eigen::MatrixXd FeStageCompliance::Matrix(const geometry::Stage& stage,
                                          const geometry::StagePoses& poses,
                                          const std::vector<StageContact>& contacts) const {
  Eigen::MatrixXd c;
  Assemble(stage, poses, contacts, &c, nullptr);
  return c;
}

StageOutcome FeStageCompliance::TryMatrix(const geometry::Stage& stage,
                                          const geometry::StagePoses& poses,
                                          const std::vector<StageContact>& contacts,
                                          Eigen::MatrixXd* out) const {
  std::string off_flank;
  Assemble(stage, poses, contacts, out, &off_flank);
  if (off_flank.empty()) return {};
  return {StageStatus::kOffFlankGrid, off_flank};
}

double FeStageCompliance::JoiningDepth(int body) const { return tables_.Table(body).join_depth(); }

FePairCompliance::FePairCompliance(const Scene& scene, const geometry::GearPair& pair,
                                   const FeComplianceOptions& options,
                                   const std::vector<std::string>& gears)
    : tables_(scene, {&pair.gear1(), &pair.gear2()}, gears, options),
      material_(scene.material),
      plane_(scene.model.plane) {}

FePairCompliance::FePairCompliance(const FeStageCompliance& stage, int body1, int body2)
    : tables_(stage.tables().Healthy({body1, body2})),
      material_(stage.material()),
      plane_(stage.plane()) {}

void FePairCompliance::Operator(const geometry::GearPair& pair, const geometry::PairPoses& poses,
                                const std::vector<geometry::PotentialContact>& contacts,
                                const std::vector<std::array<double, 2>>& section_turns,
                                std::vector<compliance::OperatorBody>* bodies,
                                std::vector<compliance::OperatorContact>* oc) const {
  if (!section_turns.empty() && section_turns.size() != contacts.size())
    throw std::invalid_argument("FePairCompliance: " + std::to_string(section_turns.size()) +
                                " section turns for " + std::to_string(contacts.size()) +
                                " contacts");
  *bodies = {Body(tables_, 0, poses.gear1, "gear1"), Body(tables_, 1, poses.gear2, "gear2")};
  oc->clear();
  oc->reserve(contacts.size());
  for (std::size_t j = 0; j < contacts.size(); ++j) {
    oc->push_back(Sides(contacts[j], 0, 1, pair.gear1(), pair.gear2(), (*bodies)[0].centre,
                        (*bodies)[1].centre, "contact " + std::to_string(j)));
    // A helical slice's sides back onto the section the poses describe (as the stage's).
    if (!section_turns.empty()) {
      TurnSide(&oc->back().side[0], (*bodies)[0].centre, -section_turns[j][0]);
      TurnSide(&oc->back().side[1], (*bodies)[1].centre, -section_turns[j][1]);
    }
  }
}

Eigen::MatrixXd FePairCompliance::Matrix(
    const geometry::GearPair& pair, const geometry::PairPoses& poses,
    const std::vector<geometry::PotentialContact>& contacts,
    const std::vector<std::array<double, 2>>& section_turns) const {
  std::vector<compliance::OperatorBody> bodies;
  std::vector<compliance::OperatorContact> oc;
  Operator(pair, poses, contacts, section_turns, &bodies, &oc);
  return compliance::AssembleCompliance(bodies, oc);
}

bool FePairCompliance::has_root_stress() const {
  return tables_.Table(0).has_fillet_stress() && tables_.Table(1).has_fillet_stress();
}

std::vector<compliance::FilletStress> FePairCompliance::FilletStresses(
    const geometry::GearPair& pair, const geometry::PairPoses& poses,
    const std::vector<geometry::PotentialContact>& contacts, const Eigen::VectorXd& force,
    const std::vector<std::array<double, 2>>& section_turns) const {
  std::vector<compliance::OperatorBody> bodies;
  std::vector<compliance::OperatorContact> oc;
  Operator(pair, poses, contacts, section_turns, &bodies, &oc);
  return compliance::FilletStresses(bodies, oc, force);
}

double ContactBodyShare(const FePairCompliance& compliance, const geometry::GearPair& pair,
                        const geometry::PairPoses& poses,
                        const geometry::PotentialContact& contact) {
  const geometry::GearPose* pose[2] = {&poses.gear1, &poses.gear2};
  const geometry::Gear* gear[2] = {&pair.gear1(), &pair.gear2()};
  const int tooth[2] = {contact.tooth_a, contact.tooth_b}, side[2] = {contact.side_a, contact.side_b};
  const Eigen::Vector2d surface[2] = {contact.surface_a, contact.surface_b};
  const Eigen::Vector2d direction[2] = {-contact.normal, contact.normal};
  double self = 0, body = 0;
  for (int b = 0; b < 2; ++b) {
    const compliance::InfluenceTable& t = compliance.tables().Table(b);
    const Eigen::Rotation2Dd to_body(-pose[b]->rotation);
    const Eigen::Vector2d centre = pose[b]->geometric_centre;
    const Eigen::Vector2d p =
        to_body * (OnNominalBody(surface[b], *gear[b], side[b], centre) - centre);
    const Eigen::Vector2d d = to_body * direction[b];
    const compliance::FlankPosition at = t.Locate(p, tooth[b], side[b]);
    const compliance::InfluenceTable::DirectedNode load = t.PrepareDirected(at, d);
    self += t.DirectedCompliance(load, load);
    for (int k : {-1, 1}) {
      compliance::FlankPosition next = at;
      next.tooth += k;
      const Eigen::Vector2d dk = Eigen::Rotation2Dd(k * 2 * geometry::kPi / t.teeth()) * d;
      body += 0.5 * t.DirectedCompliance(load, t.PrepareDirected(next, dk));
    }
  }
  const double share = body / self;
  if (!(share >= 0 && share < 1))
    throw std::invalid_argument("ContactBodyShare: phi = " + std::to_string(share) +
                                ": must be in [0, 1) (the neighbours' compliance over the contact's)");
  return share;
}

}  // namespace epicycle::transmission
