// The energy balance of the dynamic model with the FE compliance (docs/dynamic.md, "Energy
// balance"): E(t) − E(0) = W_ext − W_diss + W_C closes to the integrator's error at loads far
// apart, and W_C, the work the compliance's change along the flanks adds, equals −∫∂Φ/∂t|_F dt
// (Φ the contacts' complementary energy) computed independently from the contact terms along the
// run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/stage_problem.hpp"
#include "figures.hpp"
#include "epicycle/io/units.hpp"

using namespace epicycle;
using dynamics::DynamicSample;
using test::Sci;
using test::VerifyRow;

namespace {

// The contacts' complementary energy Φ(F) = ½FᵀCF + Σ_j ∫₀^F_j u_j(f) df at the terms' places
// (the compliance C and each local term's curvatures and depths are those of where the contact
// sits on its flanks).
double Complementary(const transmission::ContactTerms& terms, const Eigen::VectorXd& f) {
  double phi = 0.5 * f.dot(terms.compliance * f);
  for (int j = 0; j < f.size() && !terms.local.empty(); ++j)
    phi += solvers::LocalApproachIntegral(terms.local[static_cast<std::size_t>(j)], f(j));
  return phi;
}

// `force` of the contacts `from` onto the contacts `to` by tooth pair: the same mesh, planet,
// flank side and teeth, whatever the contact's kind (a contact passing from the involute onto a
// tip round is a new potential contact to the contact problem's warm start, the same pair here);
// a pair `from` does not have gets 0.
Eigen::VectorXd ByToothPair(const std::vector<transmission::StageContact>& from,
                            const Eigen::VectorXd& force,
                            const std::vector<transmission::StageContact>& to) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(to.size()));
  for (std::size_t i = 0; i < to.size(); ++i)
    for (std::size_t j = 0; j < from.size(); ++j) {
      const transmission::StageContact &x = to[i], &y = from[j];
      if (x.planet == y.planet && x.mesh == y.mesh && x.loaded == y.loaded && x.part == y.part &&
          x.contact.tooth_a == y.contact.tooth_a && x.contact.tooth_b == y.contact.tooth_b)
        out(static_cast<Eigen::Index>(i)) = force(static_cast<Eigen::Index>(j));
    }
  return out;
}

// W_C = −∫ ∂Φ/∂t|_F dt (the stored energy E = FᵀΦ' − Φ changes by Fᵀδ̇ − ∂Φ/∂t|_F) as
// −Σ_k [Φ_k+1(F̄) − Φ_k(F̄)] over consecutive samples (every `stride`-th), F̄ the mean of the two
// samples' elastic forces carried onto each sample's contacts by tooth pair: from the terms
// alone, second order in the sample spacing where they are smooth, and exact for their steps (a
// contact passing an involute–round junction) to the force's change over a spacing.
double ComplianceWorkFromMatrices(const std::vector<DynamicSample>& samples, std::size_t stride) {
  double w = 0;
  for (std::size_t k = 0; k + stride < samples.size(); k += stride) {
    const dynamics::Evaluation& a = samples[k].evaluation;
    const dynamics::Evaluation& b = samples[k + stride].evaluation;
    const Eigen::VectorXd mean =
        0.5 * (a.force + ByToothPair(b.terms.contacts, b.force, a.terms.contacts));
    const Eigen::VectorXd mean_on_b = ByToothPair(a.terms.contacts, mean, b.terms.contacts);
    w -= Complementary(b.terms, mean_on_b) - Complementary(a.terms, mean);
  }
  return w;
}

}  // namespace

TEST_CASE(
    "energy balance with the FE compliance at -600, -6000 and -20000 N m: E(t) - E(0) = "
    "W_ext - W_diss + W_C to the integrator's error, W_C from the contact terms along the run",
    "[crosscheck][dynamics]") {
  // -600 N m is the paper's load, -6000 ten times that; at -20000 N m the teeth deflect 0.6 mm,
  // four times the backlash, past what the model represents (the run warns: contact forces 7.7
  // times the local term's validity, rotations past a tenth of the module): contacts then come
  // and go carrying load at the ends of the modelled profiles (the tip rounds), the stored
  // energy steps, and W_C takes the steps as well. The balance closes there too; the terms'
  // estimate, which assumes contacts that come and go unloaded, is checked at the two loads
  // within the model's validity.
  for (const double torque : {-600.0, -6000.0, -20000.0}) {
    test::RigOptions o;
    o.edit = [](transmission::DynamicSettings& s) {
      s.sun_speed = io::RpmToRadPerSecond(1500);
      s.friction.law = transmission::FrictionLaw::kOff;  // mesh damping 5 %: W_diss > 0
    };
    const std::string text =
        test::Replace(test::WithRunout(test::SceneText("paper_stage.toml")),
                      "sun_torque_Nm = -600.0", "sun_torque_Nm = " + std::to_string(torque));
    const auto rig = test::MakeRig(text, "runout", o);
    double worst[2] = {0, 0}, old_balance = 0, w_c = 0, stored = 0, from_c[2] = {0, 0};
    for (int tight = 0; tight < 2; ++tight) {
      dynamics::SimulationOptions so;
      so.rtol = 1e-8;
      if (tight) so = test::Tightened(so, 100);
      const auto r = test::Run(rig, test::Times(*rig.model, *rig.stage, 1, 400), so);
      REQUIRE(r.completed());
      const dynamics::Evaluation start = test::StartEvaluation(rig, so);
      const double e0 = start.kinetic_energy + start.elastic_energy;
      for (const DynamicSample& s : r.samples) {
        const double de = s.evaluation.kinetic_energy + s.evaluation.elastic_energy - e0;
        const double balance = de - s.external_work + s.dissipated_work - s.compliance_work;
        worst[tight] = std::max(worst[tight], std::abs(balance));
        if (!tight) old_balance = std::max(old_balance, std::abs(balance + s.compliance_work));
      }
      if (!tight) {
        // The run's own samples, with the start as the first: every 2nd and every one.
        std::vector<DynamicSample> all(1);
        all[0].evaluation = start;
        all.insert(all.end(), r.samples.begin(), r.samples.end());
        from_c[0] = ComplianceWorkFromMatrices(all, 2);
        from_c[1] = ComplianceWorkFromMatrices(all, 1);
        w_c = r.samples.back().compliance_work;
        stored = start.contact_energy;
      }
    }
    // The balance is the bodies' work–energy theorem with the contact forces' work as a state:
    // an integration error, which falls with the tolerances (/100: at least 10x), where a
    // missing term would stay (without W_C it is the size of W_C itself).
    const bool converges = worst[1] <= worst[0] / 10;
    // The matrices' sum converges at second order in the spacing: the gap between 200 and 400
    // samples bounds the finer sum's error (3x that gap, a margin over the 1/3 of Richardson).
    const double discretisation = 3 * std::abs(from_c[1] - from_c[0]);
    const double gap = std::abs(w_c - from_c[1]);
    const bool valid = torque > -10000.0;
    const bool matches = !valid || gap <= discretisation + worst[0];
    const std::string load = Sci(torque, 2) + " N m";
    VerifyRow("energy balance with the FE compliance, " + load + ", a mesh cycle at 1500 rpm",
              "E(t) - E(0) = W_ext - W_diss + W_C",
              "largest imbalance " + Sci(worst[0]) + " J, " + Sci(worst[1]) +
                  " J with tolerances / 100 (without W_C: " + Sci(old_balance) + " J)",
              Sci(worst[0]) + " J", "/ 100 tolerances: >= 10x smaller", converges);
    if (valid)
      VerifyRow("compliance work over a mesh cycle, " + load,
              "-sum [Phi_k+1(F) - Phi_k(F)] over the run's 400 samples (C and local terms)",
              "W_C " + Sci(w_c) + " J (" + Sci(w_c / stored) + " of the stored " +
                  Sci(stored) + " J); from the matrices " + Sci(from_c[1]) + " J",
              Sci(gap) + " J", Sci(discretisation + worst[0]) + " J (3 x the 200/400 gap)",
                matches);
    CHECK(converges);
    CHECK(matches);
  }
}
