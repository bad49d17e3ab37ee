// A mesh-stiffness run's files (docs/quasistatic.md's mesh stiffness, `epicycle stiffness`): the
// samples written as each is computed, then the stiffness plot beside ISO 6336-1's c′ and c_γα,
// the summary JSON (the record's one serialisation, record_json.hpp) and, with slices of the face
// width, K_Hβ over the mesh cycle.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/report/face_width_files.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/transmission/stiffness_run.hpp"

namespace epicycle::report {

/// Writes OUT/stiffness_<mesh>.csv sample by sample (whole lines, every write checked) and, at
/// Finish, _<mesh>.svg, .json and with slices _k_hbeta.svg.
class StiffnessRunFiles : public transmission::StiffnessSink {
 public:
  StiffnessRunFiles(std::string out, nlohmann::json provenance)
      : out_(std::move(out)), provenance_(std::move(provenance)) {}
  void Start(const transmission::StiffnessPlan& plan) override;
  void Sample(const transmission::MeshSample& sample) override;
  /// Closes the CSV file (its last line complete).
  void Close();
  /// The plots and the summary JSON of `record`.
  void Finish(const transmission::StiffnessRecord& record);
  /// OUT/stiffness_<mesh>, the files' common stem.
  const std::string& base() const { return base_; }
  /// Whether Finish writes _k_hbeta.svg (slices of the face width).
  bool k_h_beta() const { return k_h_beta_.has_value(); }

 private:
  std::string out_, base_;
  nlohmann::json provenance_;
  double face_width_ = 0;  ///< b [m], the narrower gear's
  std::optional<MeshStiffnessFile> csv_;
  std::optional<KHBetaPlot> k_h_beta_;
};

}  // namespace epicycle::report
