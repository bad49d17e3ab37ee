// A dynamic run's files and console text (dynamic_run_files.hpp).
#include "epicycle/report/dynamic_run_files.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/record_json.hpp"

namespace epicycle::report {

DynamicRunOutput::DynamicRunOutput(std::string out, nlohmann::json provenance)
    : out_(std::move(out)), base_(out_ + "/dynamic"), provenance_(std::move(provenance)) {}

DynamicRunOutput::~DynamicRunOutput() = default;

void DynamicRunOutput::Start(const dynamics::DynamicPlan& p) {
  const dynamics::DynamicModel& model = p.rig->model;
  scene_name_ = p.rig->scene.name;
  sun_name_ = transmission::SunSupportName(p.rig->stage_model.setup().sun);
  std::filesystem::create_directories(out_);
  if (!p.started) return;
  const int n = p.rig->stage.planets();
  std::vector<std::string> face_meshes;
  if (p.rig->scene.face_width.active()) {
    face_meshes = StageFaceMeshes(p.rig->stage).names;
    k_h_beta_.emplace(face_meshes);
  }
  files_ = std::make_unique<DynamicRunFiles>(base_, provenance_, n,
                                             p.rig->compliance.has_root_stress(), face_meshes,
                                             p.rig->stage_model.helical());
  if (*p.spectrum) vibration_.emplace(base_, provenance_, model, **p.spectrum);
  plots_ = std::make_unique<DynamicPlots>(base_, n, *p.span);
}

void DynamicRunOutput::Step(const dynamics::DynamicSample& s) {
  ++steps_;
  files_->Write(s);
  if (vibration_) vibration_->Write(s);
  plots_->Add(s);
  if (k_h_beta_) k_h_beta_->Add(s.time * 1e3, s.face_loads);
}

void DynamicRunOutput::Stop() {
  files_->Close();
  plots_->Write(scene_name_, sun_name_);
  if (k_h_beta_ && !k_h_beta_->empty())
    WriteTextFile(base_ + "_k_hbeta.svg", k_h_beta_->Svg(scene_name_, "time [ms]"));
  if (vibration_) spectrum_text_ = vibration_->Close(scene_name_);
  vibration_.reset();  // it refers to the run's model
}

void DynamicRunOutput::Finish(const dynamics::DynamicRecord& record) {
  WriteTextFile(base_ + "_summary.json", DynamicRecordJson(record, provenance_).dump(2) + "\n");
}

std::string DynamicPlanText(const dynamics::DynamicPlan& p, const std::string& integrator,
                            const std::string& backend) {
  const transmission::Scene& scene = p.rig->scene;
  const dynamics::DynamicModel& model = p.rig->model;
  std::string t = fmt::format(
      "{}: {} planets, sun {}, input torque {:.1f} N m, sun speed {:.1f} rpm (mesh frequency "
      "{:.1f} Hz)\n",
      scene.name, p.rig->stage.planets(),
      transmission::SunSupportName(p.rig->stage_model.setup().sun), scene.loads.sun_torque,
      io::RadPerSecondToRpm(std::abs(model.sun_speed())), p.span->mesh_frequency);
  for (const std::string& m : p.rig->compliance.tables().messages()) t += "  " + m + "\n";
  for (const std::string& d : scene.damage.Describe()) t += "  " + d + "\n";
  t += fmt::format(
      "  mean mesh stiffness: sun-planet {:.4g} N/m, planet-ring {:.4g} N/m; mesh damping {:.4g} "
      "and {:.4g} N s/m\n",
      model.sun_mesh_stiffness(), model.ring_mesh_stiffness(), model.sun_mesh_damping(),
      model.ring_mesh_damping());
  t += fmt::format("  friction {}, integrator {} (rtol {:.1e}), back end {}, {} DOFs\n",
                   transmission::FrictionLawName(scene.dynamics.friction.law), integrator,
                   p.options->rtol, backend, model.size());
  if (!p.started) return t;
  return t + fmt::format(
                 "  t = 0: the quasi-static solution at carrier {:.4f} deg (no start-up "
                 "transient), {:.4f} s simulated in {} outputs, {} per mesh cycle (highest mode "
                 "{:.0f} Hz; {:.2f} s of set-up)\n",
                 geometry::Deg(model.CarrierAngle(0)), p.span->duration, p.span->outputs,
                 p.outputs_per_cycle, p.highest_mode_hz, p.setup_seconds);
}

std::string DynamicRecordText(const dynamics::DynamicRecord& r, int planets) {
  std::string t = DynamicRunText(r.summary, r.stats, planets);
  t += FaceWidthText(r.summary.face_width);
  if (r.rating) t += RatingText(*r.rating);
  return t;
}

}  // namespace epicycle::report
