#include "epicycle/transmission/mesh_stiffness.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/accumulator.hpp"
#include "epicycle/transmission/geometric_iteration.hpp"
#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/pair_face_width.hpp"
#include "epicycle/transmission/stage_problem.hpp"
#include "ordered_chunks.hpp"

namespace epicycle::transmission {

MeshPairSetup MakeMeshPair(const Scene& scene, const geometry::Stage* stage,
                           const std::string& mesh) {
  MeshPairSetup s;
  if (scene.kind == SceneKind::kPair) {
    if (!mesh.empty() && mesh != "gear1-gear2") {
      throw std::invalid_argument("--mesh = '" + mesh +
                                  "': a pair scene has one mesh, 'gear1-gear2'");
    }
    s.mesh = "gear1-gear2";
    s.spec = scene.pair;
    s.torque = scene.pair_torque;
    s.gap_window = scene.gap_window;
    s.damage = scene.damage;
    s.face_width = scene.face_width;
    return s;
  }
  if (stage == nullptr) throw std::invalid_argument("MakeMeshPair: a stage scene needs its stage");
  std::string names;
  for (const geometry::MeshSummary& m : stage->meshes()) {
    names += (names.empty() ? "" : ", ") + m.name;
    if (m.name != mesh) continue;
    const int i = m.planet;
    const double per_planet = scene.loads.sun_torque / stage->planets();
    s.mesh = mesh;
    if (m.kind == geometry::MeshKind::kSunPlanet) {
      s.spec.gear1 = stage->sun().spec();
      s.spec.gear2 = stage->planet(i).spec();
      s.spec.load_sign = stage->sun_mesh_side();
      s.torque = per_planet;
      s.gears = {BodyName(kSunBody), BodyName(PlanetBody(i))};
    } else {
      s.spec.gear1 = stage->planet(i).spec();
      s.spec.gear2 = stage->ring().spec();
      s.spec.load_sign = stage->ring_mesh_planet_side();
      s.gears = {BodyName(PlanetBody(i)), BodyName(kRingBody)};
      // The same tooth force as the sun mesh: T_p = |T|/n · r_bp / r_bs, on the loaded side.
      s.torque = s.spec.load_sign * std::abs(per_planet) * stage->planet(i).base_radius() /
                 stage->sun().base_radius();
    }
    s.spec.centre_distance = stage->carrier_radius();
    s.gap_window = scene.gap_window;
    s.damage = scene.damage;
    // A helical stage's mesh keeps the stage's slices and coupling (its contact lines cross the
    // face); the pins' tilts and the leads belong to the stage.
    if (s.spec.gear1.helix.helical()) {
      s.face_width.slices = scene.face_width.slices;
      s.face_width.coupling = scene.face_width.coupling;
      s.face_width.coupling_length = scene.face_width.coupling_length;
      s.face_width.coupling_table = m.kind == geometry::MeshKind::kPlanetRing
                                        ? scene.face_width.coupling_table_planet_ring
                                        : scene.face_width.coupling_table;
    }
    return s;
  }
  throw std::invalid_argument("--mesh = '" + mesh + "': the stage's meshes are " + names);
}

void MeshStiffnessOptions::Validate() const {
  if (positions < 2) {
    throw std::invalid_argument("mesh stiffness: positions = " + std::to_string(positions) +
                                ": must be at least 2");
  }
  if (max_geometric_iterations < 1) {
    throw std::invalid_argument("mesh stiffness: max_geometric_iterations = " +
                                std::to_string(max_geometric_iterations) + ": must be at least 1");
  }
  if (cycles < 1 || first_cycle < 0) {
    throw std::invalid_argument("mesh stiffness: cycles = " + std::to_string(cycles) +
                                ", first_cycle = " + std::to_string(first_cycle) +
                                ": must be >= 1 and >= 0");
  }
  if (threads < 0) {
    throw std::invalid_argument("mesh stiffness: threads = " + std::to_string(threads) +
                                ": must be >= 0 (0: one per core)");
  }
  if (!(geometric_tolerance > 0)) {
    throw std::invalid_argument("mesh stiffness: geometric_tolerance = " +
                                std::to_string(geometric_tolerance) + ": must be > 0");
  }
  contact.Validate();
}

namespace {

// One position: the contact problem of the pair with gear 1's moment equilibrium (gear 2 held),
// solved again at the moved pose until the rotation settles.
MeshSample SolveSample(const MeshPairSetup& setup, const DamageModel& damage,
                       const PairFaceWidth& faces, const geometry::GearPair& pair,
                       const FePairCompliance& compliance, const MeshStiffnessOptions& options,
                       solvers::ContactSolver& solver, double angle) {
  MeshSample out;
  out.angle = angle;
  geometry::PairPoses poses = pair.Poses(angle);
  geometry::ContactSearchOptions search;
  search.gap_window = setup.gap_window;
  const double rb1 = pair.gear1().base_radius();
  std::vector<geometry::PotentialContact> contacts;
  std::vector<solvers::LocalTermParameters> local;  // of the last problem built
  std::vector<int> source;                          // a pitted contact's strips: damage.hpp
  std::vector<ContactStrip> strips;
  // A helical pair's slices (helical_slices.hpp): each contact's slice and section turns.
  const bool helical = faces.active() && pair.gear1().spec().helix.helical();
  const double local_width = helical ? LocalWidthFactor(pair.gear1(), pair.gear2()) : 1.0;
  std::vector<int> slice;
  std::vector<std::array<double, 2>> turns;
  geometry::PairPoses built;  // the poses of the last problem built
  GeometricIterationOptions iteration;
  iteration.max_iterations = options.max_geometric_iterations;
  iteration.tolerance = options.geometric_tolerance;
  iteration.warm_start = false;
  const GeometricIterationResult g = IterateGeometry(
      [&](solvers::ContactProblemData* data) -> StageOutcome {
        if (helical) {
          PairSliceContacts found = HelicalPairSlices(pair, faces, poses, search);
          contacts = std::move(found.contacts);
          slice = std::move(found.slice);
          turns = std::move(found.section_turn);
        } else {
          contacts = pair.Contacts(poses, search);
        }
        built = poses;
        if (contacts.empty())
          return {StageStatus::kNoContact, "no potential contact within the gap window"};
        solvers::ContactProblemData& d = *data;
        d.name = setup.mesh + " @ " + std::to_string(geometry::Deg(angle)) + " deg";
        d.compliance = compliance.Matrix(pair, poses, contacts, turns);
        if (helical) {
          // C(j^s, k^t) = C_plane(p_j^s, p_k^t) W_st; without tooth coupling, only a tooth pair's
          // own slices keep their terms.
          const Eigen::MatrixXd& w = faces.coupling();
          for (std::size_t j = 0; j < contacts.size(); ++j)
            for (std::size_t k = 0; k < contacts.size(); ++k) {
              const bool same = contacts[j].tooth_a == contacts[k].tooth_a &&
                                contacts[j].tooth_b == contacts[k].tooth_b &&
                                contacts[j].side_a == contacts[k].side_a;
              d.compliance(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(k)) *=
                  options.tooth_coupling || same ? w(slice[j], slice[k]) : 0.0;
            }
          strips.assign(contacts.size(), ContactStrip{1.0 / faces.slices(), 0.0, 0});
        } else {
          if (!options.tooth_coupling)  // (a pitted contact's strips still share their rows)
            d.compliance = Eigen::MatrixXd(d.compliance.diagonal().asDiagonal());
          if (faces.active()) {
            faces.Expand(&contacts, &d.compliance);  // slice s of contact j at j S + s
            strips.assign(contacts.size(), ContactStrip{1.0 / faces.slices(), 0.0, 0});
          } else if (!damage.empty() &&
                     SplitContacts(damage, std::vector<int>(contacts.size(), 0),
                                   std::vector<int>(contacts.size(), 1), contacts,
                                   setup.gap_window, options.local_terms, &source, &strips)) {
            // Each strip takes its contact's rows of C (the stage model's rule).
            d.compliance = ExpandCompliance(d.compliance, source);
            std::vector<geometry::PotentialContact> parts;
            for (std::size_t k = 0; k < source.size(); ++k) {
              parts.push_back(contacts[static_cast<std::size_t>(source[k])]);
              parts.back().overlap -= strips[k].depth;
            }
            contacts = std::move(parts);
          } else {
            strips.assign(contacts.size(), ContactStrip{});
          }
        }
        // A slice's gap grows by the depth of the pits covering its centre (the stage model's
        // rule, FaceWidthModel::Expand): each slice is one strip of its contact.
        if (faces.active() && !damage.empty())
          for (std::size_t j = 0; j < contacts.size(); ++j) {
            const int s = helical ? slice[j] : static_cast<int>(j) % faces.slices();
            const double pit = damage.DepthAt(0, 1, contacts[j], (s + 0.5) / faces.slices());
            contacts[j].overlap -= pit;
            strips[j].depth = pit;
          }
        const int n = static_cast<int>(contacts.size());
        if (n == 0) return {StageStatus::kNoContact, "no potential contact within the gap window"};
        d.overlap.resize(n);
        d.equality_matrix.resize(1, n);
        d.equality_rhs = Eigen::VectorXd::Constant(1, setup.torque);
        for (int j = 0; j < n; ++j) {
          d.overlap(j) = contacts[j].overlap;
          d.equality_matrix(0, j) = -contacts[j].lever_a;  // ∂δ_j/∂θ_1; G F = T: gear 1's balance
          if (options.local_terms) {
            d.local.emplace_back();
            StageOutcome o = ContactLocalTerm(
                contacts[j], pair.gear1(), pair.gear2(), compliance.material(), compliance.plane(),
                compliance.JoiningDepth(0), compliance.JoiningDepth(1),
                d.name + " contact " + std::to_string(j), &d.local.back());
            if (!o.ok()) return o;
            d.local.back().face_width *= strips[static_cast<std::size_t>(j)].width_fraction;
            // A helical slice's term per unit length of contact line (helical_slices.hpp).
            if (helical) d.local.back().face_width *= local_width;
          }
        }
        d.multiplier_labels = {"gear1 rotation [rad]"};
        local = d.local;
        return {};
      },
      [&](const Eigen::VectorXd& lambda) {
        const double step = lambda(0);
        poses.gear1.rotation += step;
        poses.gear1.geometric_centre =
            poses.gear1.rotation_centre +
            geometry::Rotate(poses.gear1.geometric_centre - poses.gear1.rotation_centre, step);
        return std::abs(step) * rb1;
      },
      solver, options.contact, iteration);
  out.report = g.report;
  if (!g.converged) {
    out.message = g.message;
    return out;
  }
  out.converged = true;
  const double total = g.total(0);
  const solvers::ContactSolution& solution = g.solution;
  out.rotation = total;
  out.approach = std::abs(total) * rb1;
  out.poses = built;
  out.contacts = contacts;
  out.force = solution.force;
  if (faces.active())
    out.face_load = helical ? faces.Loads(solution.force, slice) : faces.Loads(solution.force);
  if (compliance.has_root_stress()) {
    out.fillet_stress = compliance.FilletStresses(pair, built, contacts, solution.force, turns);
    if (!out.fillet_stress.empty())  // the pair's two bodies
      out.root_stress = SummariseRootStress(out.fillet_stress, 2);
  }
  // Tooth pairs: the loaded contacts of the last problem, merged per (teeth, flank).
  std::map<std::array<int, 3>, ToothPairLoad> merged;
  for (std::size_t j = 0; j < contacts.size(); ++j) {
    const double f = solution.force(static_cast<Eigen::Index>(j));
    out.total_force += f;
    if (!(f > 0)) continue;
    if (j < local.size() && local[j].enabled) {
      const double limit = solvers::ValidityLimitForce(local[j]);
      if (limit > 0) out.local_validity_ratio = std::max(out.local_validity_ratio, f / limit);
    }
    const geometry::PotentialContact& c = contacts[j];
    ToothPairLoad& p = merged[{c.tooth_a, c.tooth_b, c.side_a}];
    if (f > p.force) {
      p.kind = c.kind;
      p.roll1 = c.roll_a;
    }
    p.tooth1 = c.tooth_a;
    p.tooth2 = c.tooth_b;
    p.force += f;
  }
  out.mesh_stiffness = out.approach > 0 ? std::abs(setup.torque) / rb1 / out.approach : 0.0;
  if (helical && out.approach > 0) {
    // Each tooth pair's force in each slice (its contacts there, merged as the pairs above).
    std::map<std::array<int, 4>, double> in_slice;
    for (std::size_t j = 0; j < contacts.size(); ++j) {
      const geometry::PotentialContact& c = contacts[j];
      in_slice[{slice[j], c.tooth_a, c.tooth_b, c.side_a}] +=
          solution.force(static_cast<Eigen::Index>(j));
    }
    const double dz = faces.width() / faces.slices();
    for (const auto& [key, f] : in_slice)
      out.peak_slice_pair_stiffness =
          std::max(out.peak_slice_pair_stiffness, f / (out.approach * dz));
  }
  for (auto& [key, p] : merged) {
    p.stiffness = out.approach > 0 ? p.force / out.approach : 0.0;
    p.share = out.total_force > 0 ? p.force / out.total_force : 0.0;
    out.pairs.push_back(p);
  }
  return out;
}

}  // namespace

MeshStiffnessResult ComputeMeshStiffness(const MeshPairSetup& setup, const geometry::GearPair& pair,
                                         const FePairCompliance& compliance,
                                         const MeshStiffnessOptions& options,
                                         const std::function<void(const MeshSample&)>& on_sample) {
  options.Validate();
  if (setup.torque == 0)
    throw std::invalid_argument("mesh stiffness: torque = 0: must be non-zero");
  if (setup.gears.size() != 2)
    throw std::invalid_argument("mesh stiffness: gears = " + std::to_string(setup.gears.size()) +
                                " names: must be 2 (gear 1's and gear 2's)");
  MeshStiffnessResult r;
  r.mesh = setup.mesh;
  r.torque = setup.torque;
  r.face_width = geometry::ContactFaceWidth(pair.gear1(), pair.gear2());
  double sum = 0.0;
  int good = 0;
  r.min_stiffness = std::numeric_limits<double>::infinity();
  r.samples.resize(static_cast<std::size_t>(options.positions));
  RootStressTracker root_stress(setup.gears);
  const DamageModel damage(setup.damage, setup.gears);
  const PairFaceWidth faces(setup.face_width, pair);
  if (!faces.active() && pair.gear1().spec().helix.helical())
    throw std::invalid_argument(
        "mesh stiffness: face_width.slices = " + std::to_string(faces.slices()) +
        ": a helical pair is resolved in slices of the face width and needs slices >= 2");
  r.slices = faces.slices();
  r.helical = faces.active() && pair.gear1().spec().helix.helical();
  Accumulator k_h_beta;
  internal::RunOrderedChunks(
      options.positions, options.threads, options.backend,
      [&](int k, bool, solvers::ContactSolver& solver) {
        // (first·N + cycles·k)/N cycles, in this order so that one cycle from 0 gives the angles
        // c·k/N of a single-cycle sweep bit for bit.
        const double angle = pair.mesh_cycle() *
                             (static_cast<double>(options.first_cycle) * options.positions +
                              static_cast<double>(options.cycles) * k) /
                             options.positions;
        r.samples[static_cast<std::size_t>(k)] =
            SolveSample(setup, damage, faces, pair, compliance, options, solver, angle);
      },
      [&](int k) {
        // In the order of the positions: the statistics do not depend on the thread count.
        const MeshSample& s = r.samples[static_cast<std::size_t>(k)];
        if (s.converged) {
          ++good;
          sum += s.mesh_stiffness;
          r.min_stiffness = std::min(r.min_stiffness, s.mesh_stiffness);
          r.max_stiffness = std::max(r.max_stiffness, s.mesh_stiffness);
          for (const ToothPairLoad& p : s.pairs)
            r.peak_pair_stiffness = std::max(r.peak_pair_stiffness, p.stiffness);
          r.peak_slice_pair_stiffness =
              std::max(r.peak_slice_pair_stiffness, s.peak_slice_pair_stiffness);
          root_stress.Add(s.fillet_stress, s.root_stress, s.angle);
          if (faces.active()) {
            k_h_beta.Add(s.face_load.k_h_beta);
            if (s.face_load.k_h_beta > r.k_h_beta_max) {
              r.k_h_beta_max = s.face_load.k_h_beta;
              r.k_h_beta_angle = s.angle;
              r.largest_z = s.face_load.largest_z;
            }
          }
        } else {
          ++r.failed;
        }
        if (on_sample) on_sample(s);
      });
  r.mean_stiffness = good > 0 ? sum / good : 0.0;
  if (faces.active()) r.k_h_beta_mean = k_h_beta.mean();
  r.root_stress = root_stress.Result();
  if (good == 0) r.min_stiffness = 0.0;
  return r;
}

std::array<int, 2> DamagedToothCycles(const MeshPairSetup& setup, const geometry::GearPair& pair) {
  // The damaged teeth of each gear: pits and cracks named by the setup's gear names.
  std::vector<int> teeth[2];
  for (int g = 0; g < 2; ++g) {
    for (const Pit& p : setup.damage.pits)
      if (p.gear == setup.gears.at(g)) teeth[g].push_back(p.tooth);
    for (const Crack& c : setup.damage.cracks)
      if (c.gear == setup.gears.at(g)) teeth[g].push_back(c.crack.tooth);
  }
  if (teeth[0].empty() && teeth[1].empty()) return {0, 1};
  const int z1 = pair.gear1().teeth(), z2 = pair.gear2().teeth();
  // Over the period in which every damaged tooth comes round (z1 cycles for gear 1's teeth, z2 for
  // gear 2's; both: their least common multiple), the cycles where one is within the window.
  const int period = teeth[1].empty() ? z1 : teeth[0].empty() ? z2 : z1 / std::gcd(z1, z2) * z2;
  constexpr int kPerCycle = 8;
  geometry::ContactSearchOptions search;
  search.gap_window = setup.gap_window;
  std::vector<char> meshes(static_cast<std::size_t>(period), 0);
  for (int c = 0; c < period; ++c) {
    for (int f = 0; f < kPerCycle && !meshes[c]; ++f) {
      const double angle = pair.mesh_cycle() * (c + static_cast<double>(f) / kPerCycle);
      for (const geometry::PotentialContact& k : pair.Contacts(pair.Poses(angle), search)) {
        for (int t : teeth[0]) meshes[c] = meshes[c] || k.tooth_a == t;
        for (int t : teeth[1]) meshes[c] = meshes[c] || k.tooth_b == t;
      }
    }
  }
  // The cycles from the end of the longest run of cycles without the damage (cyclically: a tooth
  // meshing across the period's start is one run), with one cycle of margin each side so that
  // healthy cycles frame it; the sweep may run past the period (the rotation is periodic).
  int gap = 0, gap_end = -1;  // longest run of quiet cycles and the cycle after it
  for (int c = 0, run = 0; c < 2 * period; ++c) {
    run = meshes[static_cast<std::size_t>(c % period)] ? 0 : run + 1;
    if (run > gap && run <= period) {
      gap = run;
      gap_end = (c + 1) % period;
    }
  }
  if (gap == 0) return {0, period};        // always meshing
  if (gap == period) return {0, 1};        // never within the window
  if (gap <= 2) return {gap_end, period};  // no quiet cycles to frame it with
  return {(gap_end + period - 1) % period, period - gap + 2};
}

MeshStiffnessResult ComputeHealthyMeshStiffness(const Scene& scene, const MeshPairSetup& setup,
                                                const geometry::GearPair& pair,
                                                const FeComplianceOptions& fe,
                                                const MeshStiffnessOptions& options) {
  Scene healthy = scene;
  MeshPairSetup healthy_setup = setup;
  healthy.damage = healthy_setup.damage = {};
  return ComputeMeshStiffness(healthy_setup, pair, FePairCompliance(healthy, pair, fe, setup.gears),
                              options);
}

namespace {

// A stage mesh's two bodies in the stage compliance: gear 1's and gear 2's (MakeMeshPair's order).
std::array<int, 2> MeshBodies(geometry::MeshKind kind) {
  return kind == geometry::MeshKind::kSunPlanet ? std::array<int, 2>{kSunBody, PlanetBody(0)}
                                                : std::array<int, 2>{PlanetBody(0), kRingBody};
}

}  // namespace

StageMeshPairs::Mesh::Mesh(const Scene& scene, const geometry::Stage& stage,
                           const FeStageCompliance& stage_compliance, geometry::MeshKind kind)
    : name(geometry::MeshName(0, kind)),
      setup([&] {
        MeshPairSetup healthy = MakeMeshPair(scene, &stage, name);
        healthy.damage = {};
        return healthy;
      }()),
      pair(MakePair(scene, setup.spec)),
      compliance(stage_compliance, MeshBodies(kind)[0], MeshBodies(kind)[1]) {}

StageMeshPairs::StageMeshPairs(const Scene& scene, const geometry::Stage& stage,
                               const FeStageCompliance& compliance)
    : meshes_{
          std::make_unique<const Mesh>(scene, stage, compliance, geometry::MeshKind::kSunPlanet),
          std::make_unique<const Mesh>(scene, stage, compliance,
                                       geometry::MeshKind::kPlanetRing)} {}

std::array<double, 2> MeanMeshStiffness(const StageMeshPairs& pairs, int positions) {
  std::array<double, 2> k{};
  for (std::size_t m = 0; m < 2; ++m) {
    const StageMeshPairs::Mesh& mesh = *pairs.meshes()[m];
    MeshStiffnessOptions opt;
    opt.positions = positions;
    const MeshStiffnessResult r = ComputeMeshStiffness(mesh.setup, mesh.pair, mesh.compliance, opt);
    if (r.failed == positions)
      throw std::runtime_error("mean mesh stiffness of " + mesh.name + ": every position failed");
    k[m] = r.mean_stiffness;
  }
  return k;
}

std::array<double, 2> MeanMeshStiffnessPerWidth(const StageMeshPairs& pairs, int positions) {
  std::array<double, 2> c = MeanMeshStiffness(pairs, positions);
  for (std::size_t m = 0; m < 2; ++m) {
    const geometry::GearPair& pair = pairs.meshes()[m]->pair;
    c[m] /= geometry::ContactFaceWidth(pair.gear1(), pair.gear2());
  }
  return c;
}

compliance::iso6336::PairData IsoPairData(const geometry::GearPair& pair) {
  auto dedendum = [](const geometry::Gear& g) {
    const geometry::GearSpec& s = g.spec();
    if (s.rack) return s.rack->addendum / s.module;
    // Internal gear: its root lies (x + h_f) m outside the reference circle.
    return (g.root_radius() - g.reference_radius()) / s.module - s.profile_shift;
  };
  compliance::iso6336::PairData d;
  d.z1 = pair.gear1().teeth();
  d.z2 = pair.gear2().teeth();
  d.x1 = pair.gear1().spec().profile_shift;
  d.x2 = pair.gear2().spec().profile_shift;
  d.internal = pair.internal();
  d.dedendum1 = dedendum(pair.gear1());
  d.dedendum2 = dedendum(pair.gear2());
  d.pressure_angle = pair.gear1().spec().pressure_angle;
  d.contact_ratio = pair.summary().contact_ratio_iso;
  const geometry::Helix& helix = pair.gear1().spec().helix;
  if (helix.helical()) {
    // ISO 6336-1's basic rack and shifts are the normal section's (the specs hold the transverse
    // m_t = m_n/cos β, tan α_t = tan α_n/cos β and x_t = x_n cos β, geometry::TransverseSpec);
    // ε_α stays the transverse section's.
    const double c = std::cos(helix.angle);
    d.helix_angle = helix.angle;
    d.pressure_angle = std::atan(std::tan(d.pressure_angle) * c);
    d.x1 /= c;
    d.x2 /= c;
    d.dedendum1 /= c;
    d.dedendum2 /= c;
  }
  return d;
}

}  // namespace epicycle::transmission
