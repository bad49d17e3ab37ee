// A dynamic run's files and console text (docs/dynamic.md): the steps, tooth pairs and bearings
// written as each output step is computed, the vibration signals and spectra when asked, the
// plots at the end and the summary JSON (the record's one serialisation, record_json.hpp).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/report/face_width_files.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/report/spectrum_files.hpp"

namespace epicycle::report {

/// Writes OUT/dynamic_steps.csv, _pairs.csv and _bearings.csv step by step (DynamicRunFiles),
/// with a spectrum OUT/dynamic_vibration.csv (VibrationFiles), and gathers the plots; with slices
/// of the face width, K_Hβ per mesh in the steps file and over the run in OUT/dynamic_k_hbeta.svg. A run whose
/// quasi-static start failed gets its folder and summary only.
class DynamicRunOutput : public dynamics::DynamicSink {
 public:
  DynamicRunOutput(std::string out, nlohmann::json provenance);
  ~DynamicRunOutput() override;
  /// @throws std::runtime_error naming a file that cannot be created.
  void Start(const dynamics::DynamicPlan& plan) override;
  void Step(const dynamics::DynamicSample& sample) override;
  long steps() const { return steps_; }               ///< output steps written [-]
  bool started() const { return files_ != nullptr; }  ///< the step files were created
  /// Closes the step files, writes the plots and the spectrum.
  void Stop() override;
  /// VibrationFiles::Close's summary ("" without a spectrum).
  const std::string& spectrum_text() const { return spectrum_text_; }
  /// OUT/dynamic_summary.json of `record`.
  void Finish(const dynamics::DynamicRecord& record);
  /// OUT/dynamic, the files' common stem.
  const std::string& base() const { return base_; }

 private:
  std::string out_, base_, scene_name_, sun_name_, spectrum_text_;
  nlohmann::json provenance_;
  long steps_ = 0;
  std::unique_ptr<DynamicRunFiles> files_;
  std::unique_ptr<DynamicPlots> plots_;
  std::optional<VibrationFiles> vibration_;
  std::optional<KHBetaPlot> k_h_beta_;  ///< with slices of the face width
};

/// The run's header on the console: scene, support, torque, speed and mesh frequency, the tables'
/// and damage's messages, the mesh stiffness and damping, friction, integrator (`integrator`,
/// `backend` as the user named them) and, for a run that started, the start and the outputs.
std::string DynamicPlanText(const dynamics::DynamicPlan& plan, const std::string& integrator,
                            const std::string& backend);

/// The record on the console: LSR per planet, K_γ, TE, the sun's orbit, the integrator's counts
/// and times, the root stresses and the rating when present (a stage of `planets` planets).
std::string DynamicRecordText(const dynamics::DynamicRecord& record, int planets);

}  // namespace epicycle::report
