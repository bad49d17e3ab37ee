// Stages for the dynamics tests: a scene (text), its stage, FE compliance from the suite's table
// cache or independent linear springs, the stage model and the dynamic model, built in one place.
#pragma once

#include <complex>
#include <functional>
#include <memory>
#include <numbers>
#include <string>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/stage_mesh_stiffness.hpp"
#include "fe_fixtures.hpp"

namespace epicycle::test {

inline transmission::FeComplianceOptions SuiteTables() { return CachedTables(); }

/// Every potential contact an independent linear spring of compliance c [m/N] (no coupling).
class SpringCompliance : public transmission::StageCompliance {
 public:
  explicit SpringCompliance(double c) : c_(c) {}
  Eigen::MatrixXd Matrix(const geometry::Stage&, const geometry::StagePoses&,
                         const std::vector<transmission::StageContact>& contacts) const override {
    const auto n = static_cast<Eigen::Index>(contacts.size());
    return c_ * Eigen::MatrixXd::Identity(n, n);
  }
  double JoiningDepth(int) const override { return 1e-3; }
  // Springs need no material; the local terms, when a test adds them, see steel.
  const transmission::Material& material() const override { return steel_; }
  solvers::PlaneAssumption plane() const override { return solvers::PlaneAssumption::kPlaneStrain; }

 private:
  transmission::Material steel_;
  double c_;
};

struct DynamicRig {
  transmission::Scene scene;
  std::unique_ptr<geometry::Stage> stage;
  std::unique_ptr<transmission::StageCompliance> compliance;
  std::unique_ptr<transmission::StageModel> stage_model;
  std::unique_ptr<dynamics::DynamicModel> model;
};

struct RigOptions {
  transmission::SunSupport sun = transmission::SunSupport::kFixed;
  double spring = 0;  ///< > 0: spring contacts of this compliance [m/N], no local terms
  double spring_mesh_stiffness = 0;  ///< mesh stiffness for the damping with springs [N/m]
  bool local_terms = true;           ///< FE compliance: with the local contact terms
  std::function<void(transmission::DynamicSettings&)> edit;  ///< changes to the scene's settings
};

/// A rig of `text` (a scene file's text): spring contacts, or the FE compliance from the suite's
/// table cache with the mean mesh stiffness of the mesh-stiffness driver.
inline DynamicRig MakeRig(const std::string& text, const std::string& name, const RigOptions& o) {
  const double spring = o.spring, spring_mesh_stiffness = o.spring_mesh_stiffness;
  const auto sun = o.sun;
  const auto& edit = o.edit;
  DynamicRig r;
  r.scene = transmission::ParseScene(text, name);
  r.scene.supports.sun = sun;
  r.stage = std::make_unique<geometry::Stage>(r.scene.stage);
  transmission::StageSetup setup = transmission::SetupFromScene(r.scene);
  if (spring > 0) {
    r.compliance = std::make_unique<SpringCompliance>(spring);
    setup.local_terms = false;
  } else {
    transmission::FeComplianceOptions fe = SuiteTables();
    fe.helical_slices = true;  // a helical stage in slices (the dynamic driver's, dynamic_run.cpp)
    r.compliance = std::make_unique<transmission::FeStageCompliance>(r.scene, *r.stage, fe);
    setup.local_terms = o.local_terms;
  }
  r.stage_model = std::make_unique<transmission::StageModel>(*r.stage, *r.compliance, setup);
  transmission::DynamicSettings settings = r.scene.dynamics;
  if (edit) edit(settings);
  r.model = std::make_unique<dynamics::DynamicModel>(*r.stage_model, settings, r.scene.inertia,
                                                     r.scene.loads);
  if (spring > 0) {
    r.model->SetMeshStiffness(spring_mesh_stiffness, spring_mesh_stiffness);
  } else if (r.stage_model->helical()) {
    // As StageDynamics: a helical stage's meshes from its own quasi-static sweep.
    const auto k = transmission::ComputeStageMeshStiffness(*r.stage_model, r.scene.loads).secant;
    r.model->SetMeshStiffness(k[0], k[1]);
  } else {
    // As StageDynamics: planet 1's meshes on the stage's own tables.
    const auto k = transmission::MeanMeshStiffness(transmission::StageMeshPairs(
        r.scene, *r.stage, dynamic_cast<const transmission::FeStageCompliance&>(*r.compliance)));
    r.model->SetMeshStiffness(k[0], k[1]);
  }
  return r;
}

// Helpers of the dynamics cross-checks.

// Output times: `per_cycle` per mesh cycle over `cycles` mesh cycles.
inline std::vector<double> Times(const dynamics::DynamicModel& m, const geometry::Stage& st,
                                 double cycles, int per_cycle, double skip = 0.0) {
  const double tc = st.mesh_cycle() / std::abs(m.carrier_speed());
  std::vector<double> t;
  const int n = static_cast<int>(std::lround(cycles * per_cycle));
  for (int i = 1; i <= n; ++i) t.push_back(skip * tc + tc * cycles * i / n);
  return t;
}

inline dynamics::SimulationResult Run(const DynamicRig& rig, const std::vector<double>& times,
                                      dynamics::SimulationOptions o = {}) {
  const Eigen::VectorXd d0 = rig.model->QuasiStaticStart(o.contact, o.backend);
  return dynamics::Simulate(*rig.model, o, d0, Eigen::VectorXd::Zero(rig.model->size()), times);
}

// The options with every tolerance (rtol, the absolute ones and the works') divided by `factor`.
inline dynamics::SimulationOptions Tightened(dynamics::SimulationOptions o, double factor) {
  o.rtol /= factor;
  o.atol_length /= factor;
  o.atol_angle /= factor;
  o.atol_energy /= factor;
  return o;
}

// The evaluation of the run's start (the quasi-static state at rest), with its energies.
inline dynamics::Evaluation StartEvaluation(const DynamicRig& rig,
                                            const dynamics::SimulationOptions& o) {
  const Eigen::VectorXd d0 = rig.model->QuasiStaticStart(o.contact, o.backend);
  auto solver = solvers::MakeContactSolver(o.backend);
  dynamics::Evaluation start;
  rig.model->Evaluate(0.0, d0, Eigen::VectorXd::Zero(rig.model->size()), *solver, o.contact,
                      nullptr, &start);
  return start;
}

inline std::string WithRunout(const std::string& text) {
  return text + "\n[[errors.runout]]\ngear = \"planet1\"\namplitude_um = 20.0\nphase_deg = 0.0\n";
}

// The quasi-static-limit setting: FE compliance without the local term, friction off, sun fixed,
// the sun at `rpm`.
inline RigOptions QuasiStaticLimitOptions(double rpm) {
  RigOptions o;
  o.local_terms = false;
  o.edit = [rpm](transmission::DynamicSettings& s) {
    s.sun_speed = io::RpmToRadPerSecond(rpm);
    s.friction.law = transmission::FrictionLaw::kOff;
  };
  return o;
}
// The quasi-static-limit setting of the run-out case: planet 1 with 20 µm run-out; `extra`
// appended to the scene's text (e.g. "[model]\nstresses = true\n").
inline DynamicRig LowSpeedRunoutRig(double rpm, const std::string& extra = "") {
  return MakeRig(WithRunout(SceneText("paper_stage.toml")) + "\n" + extra, "runout",
                 QuasiStaticLimitOptions(rpm));
}

// Largest |LSR_dyn − LSR_qs| over the samples, the quasi-static solver at each sample's carrier
// angle on the same stage model.
inline double QuasiStaticGap(const DynamicRig& rig,
                             const std::vector<dynamics::DynamicSample>& samples) {
  double worst = 0;
  transmission::QuasiStaticOptions qo;
  for (const dynamics::DynamicSample& s : samples) {
    const auto q =
        transmission::SolvePosition(*rig.stage_model, s.carrier_angle, rig.scene.loads, qo);
    REQUIRE(q.converged);
    for (std::size_t i = 0; i < q.load_sharing.size(); ++i)
      worst = std::max(worst, std::abs(s.load_sharing[i] - q.load_sharing[i]));
  }
  return worst;
}

// |Σ x_k e^{−i 2π l k/N}|·2/N: amplitude of harmonic l of N samples over one period.
inline double Harmonic(const std::vector<std::complex<double>>& x, int l) {
  std::complex<double> s = 0;
  const int n = static_cast<int>(x.size());
  for (int k = 0; k < n; ++k) s += x[k] * std::polar(1.0, -2 * std::numbers::pi * l * k / n);
  return 2.0 * std::abs(s) / n;
}

// The stage with every member on bearings, as in Lin & Parker's model: sun, planets and ring
// elastic (the carrier turned at its speed: held in the linearisation).
inline constexpr double kBearing = 1e8;      // [N/m]
inline constexpr double kRingTorsion = 1e9;  // of u = r θ [N/m]: k_θ = 1e9 r_r² N·m/rad

inline std::string AllElastic(const std::string& text) {
  return Replace(text, "[contact]",
                 "[supports]\nsun = \"elastic\"\nsun_stiffness_N_per_um = 100.0\n"
                 "planet_stiffness_N_per_um = 100.0\n\n[contact]");
}

// Mean of L_1 − 1 over the samples (the load-sharing factor of planet 1, ideal 0 deviation).
inline double MeanDeviation(const std::vector<double>& lsr1) {
  double s = 0;
  for (double v : lsr1) s += 3 * v - 1;
  return s / static_cast<double>(lsr1.size());
}

inline std::string WithPin(const std::string& text, double radial_um, double tangential_um) {
  return text + "\n[[errors.pin]]\ngear = \"planet1\"\nradial_um = " + std::to_string(radial_um) +
         "\ntangential_um = " + std::to_string(tangential_um) + "\n";
}

}  // namespace epicycle::test
