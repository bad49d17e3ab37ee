// The load across the face width of a quasi-static run with slices (docs/face_width.md): each
// position's line loads per mesh and slice written as it is computed, and at the end the maps of
// the line load over carrier angle and face width and K_Hβ over the run.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/report/files.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/sweep_summary.hpp"

namespace epicycle::report {

/// The meshes of a stage in FaceLoads' order (sun–planet meshes of planets 1…, then the
/// planet–ring meshes): their names ("sun-planet1") and face widths [m].
struct FaceMeshes {
  std::vector<std::string> names;
  std::vector<double> widths;
};
FaceMeshes StageFaceMeshes(const geometry::Stage& stage);

/// The console's table of a run's face loads per mesh ("" without slices): K_Hβ's largest and
/// mean, the carrier angle and z of the largest, the largest L_i K_Hβ.
std::string FaceWidthText(const std::vector<transmission::MeshFaceSummary>& faces);

/// K_Hβ per mesh over a run, gathered one state at a time, drawn as one line per mesh.
class KHBetaPlot {
 public:
  explicit KHBetaPlot(std::vector<std::string> meshes) : meshes_(std::move(meshes)) {
    x_.resize(meshes_.size());
    k_.resize(meshes_.size());
  }
  /// One state at `x` (carrier angle [deg], time [ms]): each mesh's K_Hβ.
  void Add(double x, const std::vector<transmission::MeshFaceLoad>& loads);
  bool empty() const;
  /// The plot's SVG document.
  std::string Svg(const std::string& title, const std::string& x_label) const;

 private:
  std::vector<std::string> meshes_;
  std::vector<std::vector<double>> x_, k_;
};

/// BASE_face_load.csv: one line per position and mesh (carrier_deg, mesh, converged, K_Hbeta,
/// the largest line load's z, the mean and each slice's line load [N/mm]); BASE_face_load.svg (a
/// map per mesh: line load over carrier angle × z) and BASE_k_hbeta.svg (K_Hβ per mesh over the
/// carrier angle) at the end. With `stresses`, each line ends with the position's largest root
/// stress over the slices [MPa], its gear and slice centre z [mm], and the largest Hertz pressure
/// [MPa] and its z [mm], then each slice's root stress sigmaF<s>_MPa and Hertz pressure
/// pH<s>_MPa (MeshFaceLoad::root_stress, hertz_pressure).
class FaceLoadFiles {
 public:
  /// `meshes` the stage's mesh names in face_loads order, `widths` each mesh's face width [m].
  FaceLoadFiles(const std::string& base, const nlohmann::json& provenance, int slices,
                std::vector<std::string> meshes, std::vector<double> widths, int positions,
                bool stresses = false);
  void Write(const transmission::PositionResult& r);
  void Close() { csv_.Close(); }
  void WritePlots(const std::string& title) const;

 private:
  std::string base_;
  CsvFile csv_;
  int slices_ = 0, positions_ = 0, columns_ = 0;
  bool stresses_ = false;
  std::vector<std::string> meshes_;
  std::vector<double> widths_;
  // The maps: per mesh, columns_ × slices_ line loads [N/mm] (the largest of the positions that
  // fall in a column), NaN where none converged; K_Hβ per mesh and position.
  std::vector<std::vector<double>> map_;
  KHBetaPlot k_h_beta_;
  double first_angle_ = 0, last_angle_ = 0;
  int seen_ = 0;
};

}  // namespace epicycle::report
