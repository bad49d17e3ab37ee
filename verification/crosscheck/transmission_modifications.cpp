// Undercut, tip relief and pitch deviations through the FE model (mesh-stiffness driver and
// quasi-static stage), against references outside the code under test:
//  - ISO 6336-1 stiffness of the undercut 17/43 pair (±20 %, docs/model.md §8);
//  - Harris's map: loaded transmission error peak-to-peak against relief amount at three loads;
//  - the two-spring theory of the double-contact zone for a tooth with a pitch deviation;
//  - the linear load-sharing theory (docs/model.md §8) for a grade-6 set of sun pitch deviations;
//  - the paper's floating-sun stage: the largest |LSR − 1/3| (off-LOA tip contacts) against
//    tip relief (docs/geometry.md has the study's table).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "epicycle/compliance/iso6336.hpp"
#include "epicycle/geometry/iso.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using test::Figure;
using test::Sci;
using test::VerifyRow;

namespace {

using test::CachedTables;

// Long tip relief: the zone covers the double-contact stretch at the tip, (ε_α − 1) p_b along the
// line of action from the tip circle (outward for an internal gear, whose tip is its inner circle).
double LongReliefStart(const geometry::Gear& g, double contact_ratio) {
  const double rb = g.base_radius(), ra = g.tip_radius();
  const double s_tip = std::sqrt(ra * ra - rb * rb);
  const double length = (contact_ratio - 1.0) * g.base_pitch();
  const double s = g.internal() ? s_tip + length : s_tip - length;
  return std::hypot(rb, s);
}

struct PairCase {
  transmission::Scene scene;
  transmission::MeshPairSetup setup;
};

PairCase LoadPair(const std::string& file) {
  PairCase p;
  p.scene = transmission::ParseScene(test::SceneText(file), file);
  p.setup = transmission::MakeMeshPair(p.scene, nullptr, "");
  return p;
}

// One mesh-cycle sweep of a pair spec (relief and pitch deviations do not change the FE bodies:
// the tables are shared with the nominal pair).
// mode 0: the model; 1: teeth as independent springs with the Hertz term; 2: independent linear
// springs (structural only).
transmission::MeshStiffnessResult SweepPair(const PairCase& c, const geometry::PairSpec& spec,
                                            double torque, int positions, int mode = 0) {
  transmission::MeshPairSetup setup = c.setup;
  setup.spec = spec;
  setup.torque = torque;
  const geometry::GearPair pair(spec);
  const transmission::FePairCompliance fe(c.scene, pair, CachedTables());
  transmission::MeshStiffnessOptions o;
  o.positions = positions;
  // 1e-9 on the nondimensional residual (forces by the load, lengths by the deflection): 1e-14 m
  // of TE, far below the µm studied; the default 1e-10 leaves one relieved position of the map
  // "converged-inaccurate" at 6.6e-10 (the Newton's line search at the relief's start kink).
  o.contact.tolerance = 1e-9;
  o.tooth_coupling = mode == 0;
  o.local_terms = mode != 2;
  transmission::MeshStiffnessResult r =
      transmission::ComputeMeshStiffness(setup, pair, fe, o);
  if (r.failed > 0) {
    // Where the active-set Newton stalls (seen once in a relieved sweep at 1.5× load: its line
    // search fails and the residual stops at 1.3e-9), the sweep is redone with Ipopt, and the
    // fallback is printed.
    Figure("relief sweep: " + std::to_string(r.failed) +
           " position(s) not converged with the Newton back end, redone with Ipopt");
    o.backend = solvers::Backend::kIpopt;
    r = transmission::ComputeMeshStiffness(setup, pair, fe, o);
  }
  for (const auto& smp : r.samples) {
    INFO("at " << smp.angle << " rad: " << smp.message);
    CHECK(smp.converged);
  }
  REQUIRE(r.failed == 0);
  return r;
}

// Peak-to-peak of the loaded transmission error along the line of action [m].
double TePeakToPeak(const transmission::MeshStiffnessResult& r, double rb1) {
  double lo = 1e9, hi = -1e9;
  for (const auto& s : r.samples) {
    lo = std::min(lo, s.rotation * rb1);
    hi = std::max(hi, s.rotation * rb1);
  }
  return hi - lo;
}

}  // namespace

TEST_CASE("undercut 17/43 ISO pair: mesh stiffness within 20 % of ISO 6336-1",
          "[crosscheck][slow][transmission][fe]") {
  const PairCase c = LoadPair("iso_pair_17_43.toml");
  const geometry::GearPair pair(c.setup.spec);
  REQUIRE(pair.gear1().undercut());
  const auto r = SweepPair(c, c.setup.spec, c.setup.torque, 40);
  const auto iso = transmission::IsoPairData(pair);
  const double c_gamma = compliance::iso6336::MeshStiffness(iso);
  const double c_prime = compliance::iso6336::SinglePairStiffness(iso);
  const double mean = r.mean_per_width(), peak = r.peak_pair_per_width();
  CHECK(std::abs(mean / c_gamma - 1) <= 0.2);
  CHECK(std::abs(peak / c_prime - 1) <= 0.2);
  VerifyRow("mesh stiffness iso_pair_17_43.toml (undercut pinion): mean [N/(mm um)]",
            "ISO 6336-1 c_gamma_alpha = " + Sci(c_gamma), Sci(mean),
            Sci(mean / c_gamma - 1) + " relative", "20 %", std::abs(mean / c_gamma - 1) <= 0.2);
  VerifyRow("mesh stiffness iso_pair_17_43.toml (undercut pinion): peak single pair",
            "ISO 6336-1 c' = " + Sci(c_prime), Sci(peak), Sci(peak / c_prime - 1) + " relative",
            "20 %", std::abs(peak / c_prime - 1) <= 0.2);
}

TEST_CASE("tip relief: Harris's map of loaded TE peak-to-peak against relief and load",
          "[crosscheck][transmission][fe]") {
  const PairCase c = LoadPair("iso_pair_20_40.toml");
  const geometry::GearPair nominal(c.setup.spec);
  const double rb1 = nominal.gear1().base_radius(), eps = nominal.summary().contact_ratio_iso;
  const double design = c.setup.torque;
  constexpr int kPositions = 30;
  // The mesh deflection at the design load: F/(mean mesh stiffness), the mean approach along the
  // line of action over the cycle without relief (ISO's F/(b c_γα)); the relief is sized on it.
  const auto base = SweepPair(c, c.setup.spec, design, kPositions);
  double deflection = 0;
  for (const auto& s : base.samples) {
    deflection += s.approach / static_cast<double>(base.samples.size());
  }
  const std::vector<double> loads = {0.5, 1.0, 1.5}, reliefs = {0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5};
  std::map<std::pair<double, double>, double> pp;
  for (double f : reliefs) {
    geometry::PairSpec spec = c.setup.spec;
    spec.gear1.modification.tip = {f * deflection, LongReliefStart(nominal.gear1(), eps),
                                   geometry::ReliefShape::kLinear};
    spec.gear2.modification.tip = {f * deflection, LongReliefStart(nominal.gear2(), eps),
                                   geometry::ReliefShape::kLinear};
    for (double load : loads) {
      INFO("relief " << f << " x design deflection, load " << load << " x design");
      pp[{load, f}] = TePeakToPeak(SweepPair(c, spec, load * design, kPositions), rb1);
    }
  }
  std::string table = "Harris map 20/40 (C in units of the design deflection " + Sci(deflection) +
                      " m; TE p-p in um):";
  for (double load : loads) {
    table += "\n  load " + Sci(load, 2) + " x design:";
    for (double f : reliefs) table += " C=" + Sci(f, 2) + ":" + Sci(pp[{load, f}] * 1e6, 3);
  }
  Figure(table);
  // The relief sized to the design deflection removes at least half of the TE variation at the
  // design load ("well below").
  const double ratio = pp[{1.0, 1.0}] / pp[{1.0, 0.0}];
  CHECK(ratio <= 0.5);
  // The best relief grows with the load (Harris): the argmin at half load is below the design
  // load's, which is below 1.5×'s; and the design load's minimum is at C = 0.75–1.25 δ.
  auto best = [&](double load) {
    double f_best = 0, v = 1e9;
    for (double f : reliefs) {
      if (pp[{load, f}] < v) v = pp[{load, f}], f_best = f;
    }
    return f_best;
  };
  CHECK(best(0.5) < best(1.0));
  CHECK(best(1.0) <= best(1.5));
  CHECK(best(1.0) >= 0.75);
  CHECK(best(1.0) <= 1.25);
  VerifyRow("ISO 20/40, long linear tip relief = design deflection: TE p-p at design load",
            "no relief: " + Sci(pp[{1.0, 0.0}] * 1e6) + " um", Sci(pp[{1.0, 1.0}] * 1e6) + " um",
            "ratio " + Sci(ratio), "<= 0.5", ratio <= 0.5);
  VerifyRow(
      "ISO 20/40 Harris map: relief of least TE p-p at 0.5/1/1.5 x design load",
      "grows with load, near the design deflection at design load",
      Sci(best(0.5), 2) + " / " + Sci(best(1.0), 2) + " / " + Sci(best(1.5), 2) + " delta", "-",
      "ordered; 0.75-1.25 at design",
      best(0.5) < best(1.0) && best(1.0) <= best(1.5) && best(1.0) >= 0.75 && best(1.0) <= 1.25);
}

TEST_CASE("pitch deviation: the pair force jumps as two springs in the double-contact zone",
          "[crosscheck][transmission][fe]") {
  const PairCase c = LoadPair("iso_pair_20_40.toml");
  const geometry::GearPair nominal(c.setup.spec);
  const double e_fp = 4e-6;  // cumulative pitch deviation of one tooth of gear 1 [m]
  const double e = nominal.loaded_side() * e_fp * std::cos(c.setup.spec.gear1.pressure_angle);
  for (const int mode : {2, 1, 0}) {
    const bool linear = mode == 2;
    const auto base = SweepPair(c, c.setup.spec, c.setup.torque, 48, mode);
    const auto lo = SweepPair(c, c.setup.spec, 0.95 * c.setup.torque, 48, mode);
    const auto hi = SweepPair(c, c.setup.spec, 1.05 * c.setup.torque, 48, mode);
    // The tooth that enters contact during the cycle: loaded in the last sample, not in the first.
    std::map<int, int> first_loaded;
    for (int i = 0; i < static_cast<int>(base.samples.size()); ++i) {
      for (const auto& p : base.samples[i].pairs) first_loaded.try_emplace(p.tooth1, i);
    }
    int tooth = -1, entry = 0;
    for (const auto& [t, i] : first_loaded) {
      if (i > entry) tooth = t, entry = i;
    }
    REQUIRE(tooth >= 0);
    geometry::PairSpec spec = c.setup.spec;
    spec.gear1.pitch_deviations.assign(spec.gear1.teeth, 0.0);
    spec.gear1.pitch_deviations[tooth] = e_fp;
    const auto dev = SweepPair(c, spec, c.setup.torque, 48, mode);
    // Loads earlier: its first loaded sample is not later, and there it carries more.
    int dev_entry = -1;
    for (int i = 0; i < static_cast<int>(dev.samples.size()) && dev_entry < 0; ++i) {
      for (const auto& p : dev.samples[i].pairs) {
        if (p.tooth1 == tooth) dev_entry = i;
      }
    }
    CHECK(dev_entry >= 0);
    CHECK(dev_entry <= entry);
    // Two springs k1 (this tooth's pair), k2 (the other) sharing F: F1 = (k1 F + k1 k2 e)/(k1 +
    // k2), so the jump is ΔF1 = k1 k2 e/(k1 + k2), k_j = F_j/δ of the nominal sample.
    double worst = 0;
    int compared = 0;
    for (std::size_t i = 0; i < base.samples.size(); ++i) {
      const auto& s0 = base.samples[i];
      const auto& s1 = dev.samples[i];
      if (s0.pairs.size() != 2 || s1.pairs.size() != 2) continue;
      const transmission::ToothPairLoad *p0 = nullptr, *q0 = nullptr, *p1 = nullptr;
      for (const auto& p : s0.pairs) (p.tooth1 == tooth ? p0 : q0) = &p;
      for (const auto& p : s1.pairs) {
        if (p.tooth1 == tooth) p1 = &p;
      }
      if (!p0 || !q0 || !p1 || p0->kind != geometry::ContactKind::kInvolute ||
          q0->kind != geometry::ContactKind::kInvolute)
        continue;
      // Linear springs: k_j = F_j/δ. Full model: the tangent k_j = ΔF_j/Δδ of a ±5 % load step
      // (the Hertz term makes the secant F/δ too soft for an increment).
      double k1 = p0->stiffness, k2 = q0->stiffness;
      if (!linear) {
        const auto tangent = [&](const transmission::ToothPairLoad* p) {
          const auto& a = lo.samples[i];
          const auto& b = hi.samples[i];
          double fa = 0, fb = 0;
          for (const auto& q : a.pairs) fa += q.tooth1 == p->tooth1 ? q.force : 0.0;
          for (const auto& q : b.pairs) fb += q.tooth1 == p->tooth1 ? q.force : 0.0;
          return (fb - fa) / (b.approach - a.approach);
        };
        k1 = tangent(p0);
        k2 = tangent(q0);
      }
      const double theory = k1 * k2 * e / (k1 + k2);
      const double model = p1->force - p0->force;
      worst = std::max(worst, std::abs(model / theory - 1));
      Figure("pitch jump mode " + std::to_string(mode) + " sample " + std::to_string(i) +
             ": model " + Sci(model) + " N, two-spring theory " + Sci(theory) + " N");
      ++compared;
    }
    REQUIRE(compared >= 2);
    // Independent linear springs: exact up to the contact solve (1e-10) and the moved contact
    // points (the compliance at a point moved by ~e along the flank changes by ~e/(tooth height)
    // ≈ 1e-3). With the Hertz term: the tangent stiffness from a ±5 % step carries a second-order
    // error of about (e/δ)²/2 ≈ 1e-2 over the increment e/δ ≈ 0.25. The full model couples the
    // two teeth through the bodies (C_12 > 0): an increment shared by both pairs (the load step)
    // sees C_11 + C_12, the pitch deviation's differential one C_11 + C_22 − 2 C_12, so the
    // two-spring prediction from load-step stiffnesses is too low there: reported, not asserted.
    const std::string name = std::string("ISO 20/40, 4 um pitch deviation on one tooth, ") +
                             (mode == 2   ? "independent linear springs"
                              : mode == 1 ? "independent springs with the Hertz term"
                                          : "full model (teeth coupled by the bodies)") +
                             ": force jump in double contact";
    if (mode == 0) {
      test::ReportRow(name, "two springs k1 k2 e/(k1 + k2), tangent k from a load step",
                      std::to_string(compared) + " positions", Sci(worst) + " relative",
                      "above: body coupling stiffens the differential mode");
    } else {
      const double tol = mode == 2 ? 2e-3 : 1e-2;
      CHECK(worst <= tol);
      VerifyRow(name, "two springs k1 k2 e/(k1 + k2)", std::to_string(compared) + " positions",
                Sci(worst) + " relative", Sci(tol, 0), worst <= tol);
    }
  }
}

namespace {

struct StageRun {
  transmission::Scene scene;
  std::unique_ptr<geometry::Stage> stage;
  std::vector<transmission::PositionResult> results;
};

StageRun SweepStage(const transmission::Scene& scene, transmission::SunSupport sun,
                    const std::vector<double>& angles, bool require_converged = true) {
  StageRun r;
  r.scene = scene;
  r.stage = std::make_unique<geometry::Stage>(scene.stage);
  transmission::QuasiStaticOptions o;
  transmission::StageSetup setup = transmission::SetupFromScene(scene);
  setup.sun = sun;
  r.results = transmission::Sweep(
      transmission::StageModel(*r.stage, test::Compliance("paper_stage.toml"), setup), scene.loads,
      angles, o);
  for (const auto& p : r.results) {
    INFO(geometry::Deg(p.carrier_angle) << " deg: " << p.message);
    if (require_converged) REQUIRE(p.converged);
  }
  return r;
}

// Long tip relief of amount C on the sun, the planets and the ring (each gear's zone from its
// mesh's contact ratio; the planet's from the smaller of its two).
transmission::Scene WithTipRelief(transmission::Scene s, double amount) {
  const geometry::Stage st(s.stage);
  const double eps_sp = st.meshes()[0].contact_ratio_iso, eps_pr = st.meshes()[1].contact_ratio_iso;
  s.stage.sun.modification.tip = {amount, LongReliefStart(st.sun(), eps_sp),
                                  geometry::ReliefShape::kLinear};
  s.stage.planet.modification.tip = {amount,
                                     LongReliefStart(st.planet(0), std::min(eps_sp, eps_pr)),
                                     geometry::ReliefShape::kLinear};
  s.stage.ring.modification.tip = {amount, LongReliefStart(st.ring(), eps_pr),
                                   geometry::ReliefShape::kLinear};
  return s;
}

// The largest |LSR_i − 1/n| over a sweep's converged positions, and over those with a loaded
// tip-round (off-line-of-action) contact.
std::pair<double, double> LargestDeviation(const StageRun& r) {
  double all = 0, tips = 0;
  const int n = r.stage->planets();
  for (const auto& p : r.results) {
    if (!p.converged) continue;
    double d = 0;
    for (double l : p.load_sharing) d = std::max(d, std::abs(l - 1.0 / n));
    bool tip = false;
    for (std::size_t j = 0; j < p.problem.contacts.size(); ++j) {
      tip = tip || (p.solution.force[j] > 0 &&
                    p.problem.contacts[j].contact.kind != geometry::ContactKind::kInvolute);
    }
    all = std::max(all, d);
    if (tip) tips = std::max(tips, d);
  }
  return {all, tips};
}

}  // namespace

TEST_CASE("paper stage, floating sun: tip relief against the off-LOA load-sharing deviation",
          "[crosscheck][transmission][fe]") {
  // The fast version of the study in docs/geometry.md: no relief and 10 µm of long tip relief on
  // every gear, one mesh cycle. The off-LOA tip contacts are what disturbs the floating sun's
  // equalisation (docs/model.md §8); relief takes the load off the tips, so the largest deviation
  // must fall. The floor of the comparison is the LOA-only deviation (2.6e-5 today,
  // docs/quasistatic.md).
  const auto base = test::PaperScene();
  const std::vector<double> angles =
      transmission::SweepAngles(0.0, geometry::Stage(base.stage).mesh_cycle(), 48);
  const auto none = LargestDeviation(SweepStage(base, transmission::SunSupport::kFloating, angles));
  const auto relieved = LargestDeviation(
      SweepStage(WithTipRelief(base, 10e-6), transmission::SunSupport::kFloating, angles));
  Figure("paper stage floating: largest |LSR - 1/3| no relief " + Sci(none.first) +
         " (at tip contacts " + Sci(none.second) + "), 10 um tip relief " + Sci(relieved.first) +
         " (at tip contacts " + Sci(relieved.second) + ")");
  CHECK(none.second > 1e-3);  // the deviation the relief is meant to remove is there
  CHECK(relieved.first < 0.5 * none.first);
  VerifyRow("paper stage, floating sun, 10 um long tip relief: largest |LSR - 1/3|",
            "no relief: " + Sci(none.first), Sci(relieved.first),
            "ratio " + Sci(relieved.first / none.first), "< 0.5",
            relieved.first < 0.5 * none.first);
}

TEST_CASE("grade-6 sun pitch deviations: mesh-cycle load sharing follows the linear theory",
          "[crosscheck][transmission][fe]") {
  // Fixed sun. docs/model.md §8: F_i = F/n + k (ē − e_i), so the mesh-cycle mean of 1 − L_i is
  // n k (e_i − ē)/F, with e_i planet i's projected error: a sun tooth turned ccw by F_p,j moves
  // its loaded flank (σ_s) into the planet by σ_s F_p,j cos α, i.e. e = −σ_s F_p,j cos α; within a
  // cycle e_i is the force-weighted mean over planet i's loaded sun-mesh pairs of the nominal run,
  // averaged over the cycle's positions. k: the path stiffness of the nominal run, ΣF/(n δ) with δ
  // the sun's mean rotation on its base circle. Over one revolution of the sun relative to the
  // carrier every planet meets every sun tooth.
  auto scene = test::PaperScene();
  geometry::Stage nominal_stage(scene.stage);
  const int zs = scene.stage.sun.teeth;
  const double cycle = nominal_stage.mesh_cycle();
  const int cycles = zs, per_cycle = 6;
  const auto angles = transmission::SweepAngles(0.0, cycles * cycle, cycles * per_cycle);
  const StageRun base = SweepStage(scene, transmission::SunSupport::kFixed, angles);
  auto with = scene;
  with.stage.sun.pitch_deviations =
      geometry::iso::RandomPitchDeviations(zs, scene.stage.sun.module, 6, 11);
  const StageRun dev = SweepStage(with, transmission::SunSupport::kFixed, angles);
  const int n = nominal_stage.planets();
  const double force = std::abs(scene.loads.sun_torque) / nominal_stage.sun().base_radius();
  const double rbs = nominal_stage.sun().base_radius();
  const int sigma = nominal_stage.sun_mesh_side();
  const double ca = std::cos(scene.stage.sun.pressure_angle);
  double worst = 0, largest = 0, mean_te = 0;
  for (const auto& p : base.results)
    mean_te += std::abs(p.transmission_error) / static_cast<double>(base.results.size());
  // The path stiffness: the sun's base-circle approach shared by n paths in parallel.
  const double k = force / (n * rbs * mean_te);
  for (int c = 0; c < cycles; ++c) {
    std::vector<double> e(n, 0.0), model(n, 0.0);
    for (int q = 0; q < per_cycle; ++q) {
      const auto& p0 = base.results[c * per_cycle + q];
      const auto& p1 = dev.results[c * per_cycle + q];
      for (int i = 0; i < n; ++i) {
        double fe = 0, f = 0;
        for (std::size_t j = 0; j < p0.problem.contacts.size(); ++j) {
          const auto& sc = p0.problem.contacts[j];
          if (sc.planet != i || sc.mesh != geometry::MeshKind::kSunPlanet || !sc.loaded) continue;
          const double fj = p0.solution.force[j];
          fe += fj * (-sigma * with.stage.sun.pitch_deviations[sc.contact.tooth_a] * ca);
          f += fj;
        }
        e[i] += (f > 0 ? fe / f : 0.0) / per_cycle;
        model[i] += n * (p0.load_sharing[i] - p1.load_sharing[i]) / per_cycle;  // Δ(1 − L_i)
      }
    }
    double ebar = 0;
    for (double v : e) ebar += v / n;
    for (int i = 0; i < n; ++i) {
      const double theory = n * k * (e[i] - ebar) / force;
      largest = std::max(largest, std::abs(theory));
      worst = std::max(worst, std::abs(model[i] - theory));
    }
  }
  // 10 % of the largest predicted change (cycles where a planet's change is near zero are judged
  // on that scale, not on their own).
  CHECK(largest > 1e-3);
  CHECK(worst <= 0.10 * largest);
  VerifyRow(
      "paper stage, fixed sun, ISO 1328-1 grade-6 sun pitch set: mesh-cycle change of 1 - L_i",
      "linear theory n k (e_i - e_mean)/F, largest " + Sci(largest),
      std::to_string(cycles) + " cycles x 3 planets", Sci(worst / largest) + " of largest", "10 %",
      worst <= 0.10 * largest);
}

TEST_CASE("study: paper stage, floating sun, largest |LSR - 1/3| against tip relief",
          "[.study][transmission][fe]") {
  // Run by tools/relief_study.sh (not in the default suite); the table is in docs/geometry.md.
  // Long linear tip relief of amount C on every gear, one mesh cycle at 96 positions, −600 N·m.
  const auto base = test::PaperScene();
  const std::vector<double> angles =
      transmission::SweepAngles(0.0, geometry::Stage(base.stage).mesh_cycle(), 96);
  int failed = 0;
  auto largest = [&](double amount, geometry::ReliefShape shape) {
    auto s = WithTipRelief(base, amount);
    for (auto* g : {&s.stage.sun, &s.stage.planet, &s.stage.ring})
      g->modification.tip.shape = shape;
    const StageRun r = SweepStage(s, transmission::SunSupport::kFloating, angles, false);
    for (const auto& p : r.results) {
      if (!p.converged) {
        ++failed;
        Figure("relief study: C = " + Sci(amount * 1e6, 3) + " um at " +
               Sci(geometry::Deg(p.carrier_angle), 4) + " deg not converged: " + p.message);
      }
    }
    return LargestDeviation(r);
  };
  for (const auto shape : {geometry::ReliefShape::kLinear, geometry::ReliefShape::kParabolic}) {
    const char* name = shape == geometry::ReliefShape::kLinear ? "linear" : "parabolic";
    std::string table = std::string("relief study (") + name +
                        "): C [um] | largest |LSR - 1/3| | at tip-round contacts";
    double below = -1, prev_c = 0, prev_v = 0;
    for (double c : {0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 7.5, 10.0, 15.0, 20.0, 30.0}) {
      const auto [all, tips] = largest(c * 1e-6, shape);
      table += "\n  " + Sci(c, 2) + " | " + Sci(all) + " | " + Sci(tips);
      if (below < 0 && all < 1e-3 && c > 0) {
        // Bisection on the amount between the last grid point above 1e-3 and this one.
        double lo = prev_c, hi = c;
        for (int it = 0; it < 12; ++it) {
          const double mid = 0.5 * (lo + hi);
          (largest(mid * 1e-6, shape).first < 1e-3 ? hi : lo) = mid;
        }
        below = hi;
      }
      prev_c = c;
      prev_v = all;
    }
    (void)prev_v;
    table += "\n  falls below 1e-3 (the paper's 0.1 %) at C = " +
             (below < 0 ? std::string("never in 0-30 um") : Sci(below, 3) + " um");
    Figure(table);
  }
  Figure("relief study: " + std::to_string(failed) + " positions not converged (left out)");
}
