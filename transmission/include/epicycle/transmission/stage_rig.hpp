// A stage scene's geometry and FE compliance built once (read-only after: shared by every run,
// thread and front end that asks for the same scene), and the stage model of its supports: the
// quasi-static run builds one or takes a front end's (QuasiStaticRequest::rig; Python keeps one per
// scene).
#pragma once

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/rating.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/stage_model.hpp"

namespace epicycle::transmission {

struct StageRig {
  Scene scene;  ///< as built (a stage scene)
  RatingInputs rating;  ///< what its ratings take (RateStage), resolved from `scene`
  geometry::Stage stage;
  FeStageCompliance compliance;
  /// @throws std::invalid_argument as RatingInputsOf, MakeStage and FeStageCompliance.
  /// Its stage model resolves a helical stage in slices (helical_slices.hpp): the tables take it.
  StageRig(Scene s, const FeComplianceOptions& fe)
      : scene(std::move(s)),
        rating(RatingInputsOf(scene)),
        stage(MakeStage(scene)),
        compliance(scene, stage, Sliced(fe)) {}
  /// The same with the scene's stage already made (MakeStage(s): checked before the tables).
  StageRig(Scene s, geometry::Stage st, const FeComplianceOptions& fe)
      : scene(std::move(s)),
        rating(RatingInputsOf(scene)),
        stage(std::move(st)),
        compliance(scene, stage, Sliced(fe)) {}
  /// The stage model of `setup` (cheap: the DOF list; it refers to this rig).
  StageModel Model(const StageSetup& setup) const { return StageModel(stage, compliance, setup); }
  /// The stage model of the scene's supports, with or without the local terms.
  StageModel Model(bool local_terms) const {
    StageSetup setup = SetupFromScene(scene);
    setup.local_terms = local_terms;
    return Model(setup);
  }

 private:
  static FeComplianceOptions Sliced(FeComplianceOptions fe) {
    fe.helical_slices = true;
    return fe;
  }
};

}  // namespace epicycle::transmission
