// One quasi-static run of a stage, as every front end asks for it: a request (the scene and typed
// overrides, every default resolved here), a run that builds the rig once and streams each
// position to a sink, and one record of what the run found (docs/quasistatic.md). The program
// (`epicycle quasistatic`) parses its options into a request and formats the record; report/
// writes the record's one serialisation (report::QuasiStaticRecordJson), whose keys are the
// record's fields as VisitRecord names them.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/rating.hpp"
#include "epicycle/transmission/record.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/stage_rig.hpp"
#include "epicycle/transmission/sweep_summary.hpp"

namespace epicycle::transmission {

/// What a quasi-static run is asked for. `what` names the front end's option for each field in
/// its messages (the program: "--positions"; Python: "positions"), so that a rule broken is
/// reported under the name the user typed.
struct QuasiStaticRequest {
  Scene scene;                            ///< read and validated (ReadScene)
  std::optional<SunSupport> sun;          ///< overrides [supports] sun when given
  std::string backend = "newton";         ///< contact back end (solvers::BackendFromName)
  RunRange range = RunRange::kMeshCycle;  ///< the carrier span swept when no angles are given
  int positions = 0;                      ///< positions over the range; 0: DefaultPositions
  std::vector<double> angles_deg;  ///< the carrier angles [deg] instead of a range (not empty)
  double start_deg = 0.0;          ///< the range's first carrier angle [deg]
  int threads = 0;                 ///< worker threads; 0: one per core
  bool warm_start = true;          ///< each position from its neighbour's forces
  bool local_terms = true;         ///< the contacts' local terms (false: linear contacts)
  std::string friction = "off";    ///< friction at rest: off, scene, or a law's name
  bool stresses = false;           ///< root stresses too (also when the scene asks for them)
  bool rating = false;             ///< ISO 6336 ratings (implies stresses)
  /// false: the scene's [[face_width.pin]] left out, every planet held at its given tilt (the
  /// pins rigid in tilt: the run without the tilt's feedback).
  bool pin_feedback = true;
  FeComplianceOptions tables;      ///< the influence tables' cache
  /// The stage and tables built from `scene` with its stresses as run (a front end's cache, e.g.
  /// Python's per scene); null: the run builds its own.
  std::shared_ptr<const StageRig> rig;
  /// The names of the options that set angles_deg and rating, for their messages.
  std::string angles_option = QuasiStaticArguments::kAnglesDeg.keyword,
              rating_option = QuasiStaticArguments::kRating.keyword;
};

/// What the run has built before its first position (for a front end's header and files).
struct QuasiStaticPlan {
  const Scene* scene = nullptr;  ///< the scene as run (sun and stresses overridden)
  const geometry::Stage* stage = nullptr;
  const FeStageCompliance* compliance = nullptr;
  const QuasiStaticOptions* options = nullptr;  ///< the sweep's resolved options
  int positions = 0;                            ///< the positions to run
  double first_angle = 0;                       ///< [rad]
  double span = 0;                              ///< the range's carrier span [rad]; 0 for a list
  double table_seconds = 0;                     ///< wall time to build or load the tables [s]
  bool friction = false;
};

/// Where a run streams what it computes, in order.
class QuasiStaticSink {
 public:
  virtual ~QuasiStaticSink() = default;
  /// Once, after the rig is built and before the first position.
  virtual void Start(const QuasiStaticPlan& /*plan*/) {}
  /// Each position k (0-based, in sweep order) as soon as it is computed; every result is let go
  /// after this call (flat memory).
  virtual void Position(const PositionResult& /*result*/, int /*k*/) {}
};

/// The failed positions listed by name in a record; the rest are counted.
inline constexpr int kListedFailures = 100;

/// What a quasi-static run found. Every field is in the record's one serialisation
/// (VisitRecord), named with its unit there.
struct QuasiStaticRecord {
  std::string scene;  ///< the scene's name
  SunSupport sun = SunSupport::kFixed;
  double sun_torque = 0;  ///< [N·m], the scene's input torque with its sign
  std::string backend;
  bool local_terms = true, warm_start = true;
  std::optional<FrictionLaw> friction;  ///< set when friction at rest was on
  int threads = 0;                      ///< as asked (0: one per core)
  int positions = 0, converged_positions = 0;
  std::vector<std::string> failures;  ///< "ANGLE deg: MESSAGE" of the first kListedFailures
  int failures_not_listed = 0;
  double sweep_seconds = 0, table_seconds = 0;  ///< wall times [s]
  SweepSummary summary;                         ///< statistics over the converged positions
  std::optional<StageRating> rating;            ///< when asked and a position converged
  std::vector<std::string> warnings;            ///< the scene's and the validity checks'
};

/// Builds the stage, its tables and model once, sweeps the positions (each to `sink` as it is
/// computed) and returns the record. A failed position is in the record, not an exception.
/// @throws std::invalid_argument for a request that breaks a rule (named by its field or option)
QuasiStaticRecord RunQuasiStatic(const QuasiStaticRequest& request, QuasiStaticSink& sink);

/// The record's fields, each once with its name and unit (its serialisation's keys).
void VisitRecord(const QuasiStaticRecord& record, RecordVisitor& visit);

}  // namespace epicycle::transmission
