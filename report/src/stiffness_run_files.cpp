#include "epicycle/report/stiffness_run_files.hpp"

#include <filesystem>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/record_json.hpp"

namespace epicycle::report {

void StiffnessRunFiles::Start(const transmission::StiffnessPlan& p) {
  const transmission::MeshPairSetup& setup = *p.setup;
  std::filesystem::create_directories(out_);
  base_ = out_ + "/stiffness_" + setup.mesh;
  face_width_ = p.face_width;
  csv_.emplace(base_ + ".csv", provenance_, face_width_,
               p.compliance->has_root_stress() ? setup.gears : std::vector<std::string>{},
               setup.face_width.slices);
  if (setup.face_width.active()) k_h_beta_.emplace(std::vector<std::string>{setup.mesh});
}

void StiffnessRunFiles::Sample(const transmission::MeshSample& s) {
  csv_->Write(s);  // written as computed
  if (k_h_beta_ && s.converged) k_h_beta_->Add(geometry::Deg(s.angle), {s.face_load});
}

void StiffnessRunFiles::Close() {
  if (csv_) csv_->Close();
}

void StiffnessRunFiles::Finish(const transmission::StiffnessRecord& record) {
  const transmission::MeshStiffnessResult& result = record.result;
  WriteMeshStiffnessPlot(base_ + ".svg", record.scene + ": " + result.mesh + " mesh stiffness",
                         result, face_width_,
                         {record.iso6336_c_gamma_alpha, record.iso6336_c_prime});
  WriteTextFile(base_ + ".json", SummaryJson(record, provenance_).dump(2) + "\n");
  if (k_h_beta_)  // K_Hβ over the mesh cycle
    WriteTextFile(base_ + "_k_hbeta.svg",
                  k_h_beta_->Svg(record.scene + ": " + result.mesh, "gear 1 rotation [deg]"));
}

}  // namespace epicycle::report
