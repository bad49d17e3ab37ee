// Stages for the dynamics tests: a scene (text), its stage, FE compliance from the suite's table
// cache or independent linear springs, the stage model and the dynamic model, built in one place.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
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

 private:
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
  std::function<void(dynamics::DynamicSettings&)> edit;  ///< changes to the scene's settings
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
    r.compliance =
        std::make_unique<transmission::FeStageCompliance>(r.scene, *r.stage, SuiteTables());
    setup.local_terms = o.local_terms;
  }
  r.stage_model =
      std::make_unique<transmission::StageModel>(r.scene, *r.stage, *r.compliance, setup);
  dynamics::DynamicSettings settings = dynamics::SettingsFromScene(r.scene);
  if (edit) edit(settings);
  r.model = std::make_unique<dynamics::DynamicModel>(*r.stage_model, r.scene, settings);
  if (spring > 0) {
    r.model->SetMeshStiffness(spring_mesh_stiffness, spring_mesh_stiffness);
  } else {
    const auto k = dynamics::MeanMeshStiffness(r.scene, *r.stage, SuiteTables());
    r.model->SetMeshStiffness(k[0], k[1]);
  }
  return r;
}

}  // namespace epicycle::test
