// A quasi-static run's files and console text (docs/quasistatic.md): the positions and tooth pairs
// written as each position is computed, the contact problems dumped when asked, the summary JSON
// (the record's one serialisation, record_json.hpp) and the plots at the end.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/report/face_width_files.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"

namespace epicycle::report {

/// Writes OUT/quasistatic_positions.csv and _pairs.csv position by position (whole lines, every
/// write checked), with slices of the face width _face_load.csv too (FaceLoadFiles), gathers the
/// plots, and dumps each position's contact problem into `dump` when
/// it is not empty (files named STEM_SUN_local|linear_K).
class QuasiStaticRunFiles : public transmission::QuasiStaticSink {
 public:
  struct Options {
    std::string out;        ///< the output folder (created)
    std::string dump;       ///< the contact problems' folder ("": none)
    std::string dump_stem;  ///< the dumped problems' name stem (the scene file's)
    std::string backend;    ///< for the dumped problems' descriptions
    bool linear = false;    ///< no local terms (names the dumped problems)
  };
  QuasiStaticRunFiles(Options options, nlohmann::json provenance);
  ~QuasiStaticRunFiles() override;
  void Start(const transmission::QuasiStaticPlan& plan) override;
  void Position(const transmission::PositionResult& result, int k) override;
  /// Closes the CSV files (their last lines complete).
  void Close();
  /// The summary JSON of `record` and the plots.
  void Finish(const transmission::QuasiStaticRecord& record);
  /// OUT/quasistatic, the files' common stem.
  const std::string& base() const { return base_; }

 private:
  Options options_;
  nlohmann::json provenance_;
  std::string base_, sun_name_, scene_name_;
  std::unique_ptr<QuasiStaticFiles> files_;
  std::unique_ptr<QuasiStaticPlots> plots_;
  std::unique_ptr<FaceLoadFiles> faces_;  ///< with slices of the face width
};

/// The run's header on the console: scene, support, load and back end, the tables' and damage's
/// messages, the positions and how they are solved, friction at rest.
std::string QuasiStaticPlanText(const transmission::QuasiStaticPlan& plan,
                                const std::string& backend, bool cold, int threads);

/// The record on the console: LSR per planet, K_γ, TE, the sun's displacement, friction, stresses,
/// the rating, the positions converged and the failures listed (`base` names the positions file
/// for those not listed).
std::string QuasiStaticRecordText(const transmission::QuasiStaticRecord& record,
                                  const std::string& base);

}  // namespace epicycle::report
