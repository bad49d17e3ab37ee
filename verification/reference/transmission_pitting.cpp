// Pits and spalls (docs/model.md §9, "Pitting and spalls") through the drivers, against references
// outside the damage code:
//  1. rigid bodies: a full-width pit deeper than the approach changes the unloaded transmission
//     error by its depth along the line of action where the pitted tooth is the only one in
//     contact, and not at all where another pair touches (the healthy rigid overlaps of the
//     contact search, and the depth);
//  2. a spall covering w of the face width: the stage model's intact strip has the local term of
//     width (1 − w)b (local_term.hpp's closed form written out here) and shares its contact's
//     compliance rows;
//  3. loaded: the mesh stiffness of the ISO 20/40 pair with one spall lies between the healthy
//     pair's and that of the pair with the tooth removed in the spall's region, and where the
//     spalled tooth carries alone its approach grows by the local terms' difference of the two
//     widths (closed form).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/stage_model.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using test::Figure;

namespace {

struct IsoPair {
  transmission::Scene scene =
      transmission::ParseScene(test::SceneText("iso_pair_20_40.toml"), "iso_pair_20_40.toml");
  transmission::MeshPairSetup setup = transmission::MakeMeshPair(scene, nullptr, "");
  geometry::GearPair pair{scene.pair};
  transmission::FePairCompliance fe{scene, pair, test::CachedTables()};
};

IsoPair& Iso() {
  static IsoPair p;
  return p;
}

transmission::MeshStiffnessResult Sweep(const transmission::Damage& damage, double torque,
                                        int positions) {
  IsoPair& p = Iso();
  transmission::MeshPairSetup setup = p.setup;
  setup.damage = damage;
  setup.torque = torque;
  transmission::MeshStiffnessOptions o;
  o.positions = positions;
  o.threads = 1;
  o.geometric_tolerance = 1e-14;  // [m]: settles the rotation far below the depths compared
  return transmission::ComputeMeshStiffness(setup, p.pair, p.fe, o);
}

// The tooth of gear 1 that carries the load alone in the healthy sweep (the single-pair zone of a
// pair with ε_α = 1.64: 36 % of the cycle), at the middle sample of that zone, and the roll range
// it runs over while in contact during the cycle.
struct ToothRun {
  int tooth = -1;
  double roll_min = 1e9, roll_max = -1e9;  // [rad]
};
// The teeth of gear 1 carrying load at a sample (F > 0, either flank).
std::vector<int> LoadedTeeth(const transmission::MeshSample& s) {
  std::vector<int> teeth;
  for (std::size_t j = 0; j < s.contacts.size(); ++j)
    if (s.force(static_cast<Eigen::Index>(j)) > 0 &&
        std::find(teeth.begin(), teeth.end(), s.contacts[j].tooth_a) == teeth.end())
      teeth.push_back(s.contacts[j].tooth_a);
  return teeth;
}
ToothRun SingleZoneTooth(const transmission::MeshStiffnessResult& healthy) {
  std::vector<int> single;
  for (std::size_t k = 0; k < healthy.samples.size(); ++k)
    if (LoadedTeeth(healthy.samples[k]).size() == 1) single.push_back(static_cast<int>(k));
  REQUIRE(!single.empty());
  ToothRun t;
  t.tooth = LoadedTeeth(healthy.samples[single[single.size() / 2]])[0];
  for (const transmission::MeshSample& s : healthy.samples)
    for (const geometry::PotentialContact& c : s.contacts)
      if (c.tooth_a == t.tooth && c.kind == geometry::ContactKind::kInvolute &&
          c.side_a == Iso().pair.loaded_side()) {
        t.roll_min = std::min(t.roll_min, c.roll_a);
        t.roll_max = std::max(t.roll_max, c.roll_a);
      }
  return t;
}

transmission::Pit PitOn(const ToothRun& run, double width_fraction, double depth) {
  transmission::Pit p;
  p.gear = "gear1";
  p.tooth = run.tooth;
  p.flank = Iso().pair.loaded_side();
  // The whole stretch the tooth runs over in the cycle, with a margin of 1 degree of roll, so
  // that no contact of the sweep crosses the pit's edge (a step of the profile).
  p.roll_from = run.roll_min - geometry::Rad(1.0);
  p.roll_to = run.roll_max + geometry::Rad(1.0);
  p.width_fraction = width_fraction;
  p.depth = depth;
  return p;
}

// u_local of docs/model.md §4 (solvers/local_term.hpp), written out from its formula for the test:
// Σ_B 2 k_B F/(π b) [asinh(h_B/L) − c_B (h_B/L)(√(1 + (h_B/L)²) − h_B/L)], plane strain.
double HertzApproach(const solvers::LocalTermParameters& p, double width, double force) {
  double inv_e = 0;
  for (const solvers::LocalBody& b : p.body)
    inv_e += (1 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus;
  const double half = std::sqrt(4 * force * p.reduced_radius / (std::numbers::pi * width / inv_e));
  double u = 0;
  for (const solvers::LocalBody& b : p.body) {
    const double k = (1 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus;
    const double c = b.poisson_ratio / (1 - b.poisson_ratio);
    const double s = b.depth / half;
    // s(√(1 + s²) − s) rationalised, s/(√(1 + s²) + s): no cancellation at large s.
    u += 2 * k * force / (std::numbers::pi * width) *
         (std::asinh(s) - c * s / (std::sqrt(1 + s * s) + s));
  }
  return u;
}

}  // namespace

TEST_CASE("pitting: a full-width pit changes the rigid transmission error by its depth",
          "[reference][transmission]") {
  // Rigid bodies: a torque of 1e-6 N·m, whose elastic approach (≈ F/k_mesh = 2.7e-5 N /
  // 2.6e8 N/m ≈ 1e-13 m, the local term adding ≈ 1e-15 m) is eight orders below the depth.
  constexpr double kTorque = 1e-6, kDepth = 20e-6;
  constexpr int kPositions = 24;
  const transmission::MeshStiffnessResult healthy = Sweep({}, kTorque, kPositions);
  REQUIRE(healthy.failed == 0);
  const ToothRun run = SingleZoneTooth(healthy);
  transmission::Damage damage;
  damage.pits.push_back(PitOn(run, 1.0, kDepth));
  const transmission::MeshStiffnessResult pitted = Sweep(damage, kTorque, kPositions);
  REQUIRE(pitted.failed == 0);
  const geometry::GearPair& pair = Iso().pair;
  geometry::ContactSearchOptions search;
  search.gap_window = Iso().scene.gap_window;
  int alone = 0, shared = 0, between = 0;
  double worst = 0;
  const double rb1 = pair.gear1().base_radius();
  for (int k = 0; k < kPositions; ++k) {
    const transmission::MeshSample& h = healthy.samples[k];
    const transmission::MeshSample& p = pitted.samples[k];
    // The reference: the rigid overlaps of the healthy loaded flanks at the kinematic pose, each
    // as the turn of gear 1 that closes it, measured along its line of action:
    // c_j = −δ_j r_b1/|lever_j| (exact for an involute contact, whose overlap grows by r_b1 dθ;
    // first order for a tip round). The pit lowers tooth `run.tooth`'s involute contact by the
    // depth, along its normal, which is the line of action: its c grows by d. Gear 1 turns
    // until the first contact closes.
    double healthy_close = 1e9, others_close = 1e9, pitted_close = 1e9;
    bool others_involute = false;
    for (const geometry::PotentialContact& c : pair.Contacts(pair.Poses(h.angle), search)) {
      if (c.side_a != pair.loaded_side()) continue;
      const double close = -c.overlap * rb1 / std::abs(c.lever_a);
      healthy_close = std::min(healthy_close, close);
      if (c.tooth_a == run.tooth && c.kind == geometry::ContactKind::kInvolute) {
        pitted_close = std::min(pitted_close, close + kDepth);
      } else if (close < others_close) {
        others_close = close;
        others_involute = c.kind == geometry::ContactKind::kInvolute;
      }
    }
    const double measured = p.approach - h.approach;  // [m] along the line of action
    // Tolerance: both elastic approaches (each run's own, whatever pairs carry it) and the
    // geometric iteration's tolerance of each run (1e-14 m).
    const double tol = h.approach + p.approach + 2e-14;
    INFO("position " << k << ": measured " << measured << " m, closing distances: healthy "
                     << healthy_close << ", pitted tooth " << pitted_close << ", others "
                     << others_close);
    double expected = 0;
    if (others_involute && std::abs(others_close - healthy_close) <= 1e-9) {
      // Another pair touches (conjugate to 1e-10): it carries, nothing changes.
      ++shared;
      expected = 0;
    } else if (pitted_close < others_close - 1e-9 &&
               std::abs(pitted_close - kDepth - healthy_close) <= 1e-9) {
      // The pitted tooth is the first to close, alone: the whole depth.
      ++alone;
      expected = kDepth;
    } else {
      // A neighbour's tip round closes first, after less than the depth (first order only:
      // the bounds).
      ++between;
      CHECK(measured >= -tol);
      CHECK(measured <= kDepth + tol);
      continue;
    }
    CHECK(std::abs(measured - expected) <= tol);
    worst = std::max(worst, std::abs(measured - expected));
  }
  // Both kinds of positions occur in the cycle (ε_α = 1.64: the single-pair zone is 36 %).
  CHECK(alone >= 4);
  CHECK(shared >= 4);
  Figure(
      "pitting: rigid TE change, full-width pit 20 um: positions alone / shared / between / "
      "worst error: " +
      std::to_string(alone) + " / " + std::to_string(shared) + " / " + std::to_string(between) +
      " / " + test::Sci(worst) + " m");
}

TEST_CASE("pitting: a spall's intact strip has the local term of the remaining width",
          "[reference][transmission]") {
  // The paper stage at carrier 0: a spall over w = 0.3 of planet 1's face on the tooth that
  // meshes with the sun, over that contact's roll ± 1 degree.
  const transmission::Scene scene = test::PaperScene();
  const geometry::Stage stage(scene.stage);
  const transmission::FeStageCompliance& fe = test::Compliance("paper_stage.toml");
  transmission::StageSetup setup = transmission::SetupFromScene(scene);
  const transmission::StageModel healthy(stage, fe, setup);
  const geometry::StagePoses poses = healthy.KinematicPoses(0.0);
  const transmission::ContactTerms h = healthy.Terms(poses);
  int j0 = -1;  // the loaded involute sun–planet 1 contact of largest overlap
  for (int j = 0; j < h.size(); ++j) {
    const transmission::StageContact& s = h.contacts[j];
    if (s.planet == 0 && s.mesh == geometry::MeshKind::kSunPlanet && s.loaded &&
        s.contact.kind == geometry::ContactKind::kInvolute &&
        (j0 < 0 || s.contact.overlap > h.contacts[j0].contact.overlap))
      j0 = j;
  }
  REQUIRE(j0 >= 0);
  const geometry::PotentialContact& c0 = h.contacts[j0].contact;
  constexpr double kW = 0.3, kDepth = 10e-6;
  transmission::Pit pit;
  pit.gear = "planet1";
  pit.tooth = c0.tooth_b;
  pit.flank = c0.side_b;
  pit.roll_from = c0.roll_b - geometry::Rad(1.0);
  pit.roll_to = c0.roll_b + geometry::Rad(1.0);
  pit.width_fraction = kW;
  pit.depth = kDepth;
  setup.damage.pits.push_back(pit);
  const transmission::StageModel damaged(stage, fe, setup);
  const transmission::ContactTerms d = damaged.Terms(poses);
  REQUIRE(d.size() == h.size() + 1);  // one contact split in two strips
  // The strips follow their contact: j0 (intact, part 0) and j0 + 1 (pitted, part 1).
  const transmission::StageContact& intact = d.contacts[j0];
  const transmission::StageContact& spall = d.contacts[j0 + 1];
  CHECK(intact.part == 0);
  CHECK(intact.pit_depth == 0);
  CHECK(spall.part == 1);
  CHECK(spall.pit_depth == kDepth);
  CHECK(spall.Label() == h.contacts[j0].Label() + " pitted 1");
  const double b = scene.stage.sun.face_width;
  // Exact: the widths are (1 − w) b and w b (one multiplication each), the rest of the term that
  // of the healthy contact.
  CHECK(d.local[j0].face_width == (1 - kW) * b);
  CHECK(d.local[j0 + 1].face_width == kW * b);
  CHECK(d.local[j0].reduced_radius == h.local[j0].reduced_radius);
  // The approach against the closed form of width (1 − w) b at forces across the load range
  // (1 N to 20 kN): the same formula evaluated in another order, to round-off (a dozen
  // operations, each within 1.1e-16: 1e-14 relative).
  double worst = 0;
  for (double f : {1.0, 100.0, 3e3, 2e4}) {
    const double expected = HertzApproach(h.local[j0], (1 - kW) * b, f);
    const double got = solvers::LocalApproach(d.local[j0], f);
    CHECK(std::abs(got - expected) <= 1e-14 * expected);
    worst = std::max(worst, std::abs(got - expected) / expected);
    CHECK(std::abs(solvers::LocalApproach(d.local[j0 + 1], f) -
                   HertzApproach(h.local[j0], kW * b, f)) <= 1e-14 * expected / kW);
  }
  // Both strips share their contact's rows of C; the overlaps are the contact's and δ − d.
  for (int k = 0; k < h.size(); ++k) {
    const int dk = k > j0 ? k + 1 : k;
    CHECK(d.compliance(j0, dk) == h.compliance(j0, k));
    CHECK(d.compliance(j0 + 1, dk) == h.compliance(j0, k));
  }
  CHECK(d.compliance(j0 + 1, j0 + 1) == h.compliance(j0, j0));
  CHECK(d.overlap(j0) == h.overlap(j0));
  CHECK(d.overlap(j0 + 1) == h.overlap(j0) - kDepth);
  Figure("pitting: intact strip's local term against the closed form of width (1 - w) b: " +
         test::Sci(worst) + " (relative)");
}

TEST_CASE("pitting: a spall lowers the ISO 20/40 pair's mesh stiffness within its bounds",
          "[reference][transmission]") {
  // The scene's 200 N·m. The spall: w = 0.5 of the face, 20 µm deep (deeper than the local
  // approach of the intact strip, ≈ 5 µm at 5.3 kN: its pitted strip stays open); "removed": the
  // same region without any material (w = 1, 1 mm deep, beyond the 100 µm gap window).
  constexpr int kPositions = 24;
  const double torque = Iso().setup.torque;
  const transmission::MeshStiffnessResult healthy = Sweep({}, torque, kPositions);
  REQUIRE(healthy.failed == 0);
  const ToothRun run = SingleZoneTooth(healthy);
  constexpr double kW = 0.5;
  transmission::Damage spall, removed;
  spall.pits.push_back(PitOn(run, kW, 20e-6));
  removed.pits.push_back(PitOn(run, 1.0, 1e-3));
  const transmission::MeshStiffnessResult s = Sweep(spall, torque, kPositions);
  const transmission::MeshStiffnessResult r = Sweep(removed, torque, kPositions);
  REQUIRE(s.failed == 0);
  // With the tooth removed, a position where it was the only loaded pair within the gap window
  // has no loaded contact left (the next teeth are further than the window): no F ≥ 0 carries
  // the torque, the pair is infinitely compliant there at this window, k = 0.
  for (const transmission::MeshSample& m : r.samples)
    if (!m.converged) CHECK_THAT(m.message, Catch::Contains("no F >= 0 satisfies G F = W"));
  const double rb1 = Iso().pair.gear1().base_radius();
  const double force = std::abs(torque) / rb1;  // one pair carrying: F = T/r_b1 [N]
  int single = 0;
  double worst_single = 0;
  for (int k = 0; k < kPositions; ++k) {
    const double kh = healthy.samples[k].mesh_stiffness, ks = s.samples[k].mesh_stiffness,
                 kr = r.samples[k].converged ? r.samples[k].mesh_stiffness : 0.0;
    INFO("position " << k << ": healthy " << kh << ", spall " << ks << ", removed " << kr);
    // The bounds, to the contact solve's tolerance (1e-10 relative on the approach).
    CHECK(ks <= kh * (1 + 1e-9));
    CHECK(ks >= kr * (1 - 1e-9));
    // Where the spalled tooth carries alone in the healthy run, the approach grows by the local
    // terms' difference of the two widths, and by the change of the structural term where the
    // contact has moved (below).
    const transmission::MeshSample& h = healthy.samples[k];
    if (k == 0 || k + 1 == kPositions) continue;
    const std::vector<int> teeth = LoadedTeeth(h);
    if (teeth.size() != 1 || teeth[0] != run.tooth) continue;
    if (LoadedTeeth(healthy.samples[k - 1]).size() != 1 ||
        LoadedTeeth(healthy.samples[k + 1]).size() != 1)
      continue;
    ++single;
    // The reference at the poses each run settled at: one loaded contact (healthy) or strip
    // (spall, the pitted strip open), F = T/r_b1 (an involute contact's lever is r_b1), the
    // approach C_jj F + u_local(F) with C_jj from the compliance layer at that pose (gear 2 is
    // held, so the spalled run's contact point has moved along gear 1's flank only) and u_local
    // the closed form above of the width (1 − w) b, resp. b, and of the radii at that pose.
    const transmission::MeshSample& p = s.samples[k];
    auto loaded = [](const transmission::MeshSample& m, int* carrying) {
      int j0 = -1;
      *carrying = 0;
      for (std::size_t j = 0; j < m.contacts.size(); ++j)
        if (m.force(static_cast<Eigen::Index>(j)) > 0) {
          j0 = static_cast<int>(j);
          ++*carrying;
        }
      return j0;
    };
    int nh = 0, ns = 0;
    const int jh = loaded(h, &nh), js = loaded(p, &ns);
    REQUIRE(nh == 1);
    REQUIRE(ns == 1);  // the intact strip alone: the pitted one is open
    auto approach = [&](const transmission::MeshSample& m, int j, double width) {
      const std::vector<geometry::PotentialContact> one{m.contacts[static_cast<std::size_t>(j)]};
      solvers::LocalTermParameters l;
      REQUIRE(transmission::ContactLocalTerm(
                  one[0], Iso().pair.gear1(), Iso().pair.gear2(), Iso().fe.material(),
                  Iso().fe.plane(), Iso().fe.JoiningDepth(0), Iso().fe.JoiningDepth(1), "", &l)
                  .ok());
      return Iso().fe.Matrix(Iso().pair, m.poses, one)(0, 0) * force +
             HertzApproach(l, width, force);
    };
    const double b = Iso().setup.spec.gear1.face_width;
    const double growth = approach(p, js, (1 - kW) * b) - approach(h, jh, b);
    const double measured = p.approach - h.approach;
    // Tolerance: each run's geometric tolerance (1e-14 m) and the contact solve's gap residual,
    // 1e-10 of the deflection scale F C_jj ≈ 1.7e-5 m (1.7e-15 m), per run.
    const double tol = 2 * (1e-14 + 1e-10 * force * 3.3e-9);
    INFO("approach growth " << measured << " m, reference " << growth << " m");
    CHECK(std::abs(measured - growth) <= tol);
    worst_single = std::max(worst_single, std::abs(measured - growth) / growth);
  }
  CHECK(single >= 2);
  Figure("pitting: ISO 20/40 mean stiffness drop, spall w 0.5, 20 um: " +
         test::Sci(1 - s.mean_stiffness / healthy.mean_stiffness) +
         " (tooth removed: " + std::to_string(r.failed) + " of " + std::to_string(kPositions) +
         " positions without a loaded contact)");
  Figure("pitting: single-pair approach growth against the reference (worst relative): " +
         test::Sci(worst_single));
}

TEST_CASE(
    "pitting: the stiffness sweep of a damaged pair covers the cycles its tooth meshes in, "
    "framed by healthy cycles",
    "[reference][transmission]") {
  // A full-width 20 µm pit over gear 2's tooth 7's whole involute (flank of the load): the sweep
  // (DamagedToothCycles) must hold every position where the tooth carries load, and its first
  // and last cycles must be healthy, equal to the healthy pair's there (bit-identical: the same
  // solves), while inside somewhere the pit acts.
  IsoPair& p = Iso();
  const geometry::Gear& g2 = p.pair.gear2();
  transmission::MeshPairSetup setup = p.setup;
  transmission::Pit pit;
  pit.gear = "gear2";
  pit.tooth = 7;
  pit.roll_from = g2.involute().u_min;
  pit.roll_to = g2.involute().u_max;
  pit.width_fraction = 1.0;
  pit.depth = 20e-6;
  for (int flank : {1, -1}) {
    pit.flank = flank;
    setup.damage.pits.push_back(pit);
  }
  const auto [first, cycles] = transmission::DamagedToothCycles(setup, p.pair);
  REQUIRE(cycles >= 3);
  constexpr int kPerCycle = 8;
  transmission::MeshStiffnessOptions o;
  o.positions = kPerCycle * cycles;
  o.first_cycle = first;
  o.cycles = cycles;
  o.threads = 1;
  const transmission::MeshStiffnessResult d =
      transmission::ComputeMeshStiffness(setup, p.pair, p.fe, o);
  transmission::MeshPairSetup healthy_setup = p.setup;
  const transmission::MeshStiffnessResult h =
      transmission::ComputeMeshStiffness(healthy_setup, p.pair, p.fe, o);
  // Where the healthy pair loads tooth 7 of gear 2 (every such position of the pair's period
  // lies in the sweep: counted over a full turn of gear 2, z2 cycles).
  auto loads_tooth = [](const transmission::MeshSample& s) {
    for (std::size_t j = 0; j < s.contacts.size(); ++j)
      if (s.force(static_cast<Eigen::Index>(j)) > 0 && s.contacts[j].tooth_b == 7) return true;
    return false;
  };
  int inside = 0;
  for (const transmission::MeshSample& s : h.samples) inside += loads_tooth(s) ? 1 : 0;
  transmission::MeshStiffnessOptions turn = o;
  turn.first_cycle = 0;
  turn.cycles = p.pair.gear2().teeth();
  turn.positions = kPerCycle * turn.cycles;
  int all = 0;
  for (const transmission::MeshSample& s :
       transmission::ComputeMeshStiffness(healthy_setup, p.pair, p.fe, turn).samples)
    all += loads_tooth(s) ? 1 : 0;
  CHECK(inside > 0);
  CHECK(inside == all);
  bool acts = false;
  for (int k = 0; k < o.positions; ++k) {
    const bool margin = k < kPerCycle || k >= o.positions - kPerCycle;
    const double dk = d.samples[k].mesh_stiffness, hk = h.samples[k].mesh_stiffness;
    if (margin) CHECK(dk == hk);
    acts = acts || dk < hk * (1 - 1e-6);
  }
  CHECK(acts);
  Figure("pitting: damaged-tooth sweep cycles " + std::to_string(first) + ".." +
         std::to_string(first + cycles - 1) + ", positions loading the tooth " +
         std::to_string(inside) + " of " + std::to_string(all) + " over gear 2's turn");
}
