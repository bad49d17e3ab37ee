#include "periodic_command.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "console.hpp"
#include "epicycle/report/branch_files.hpp"
#include "epicycle/report/record_json.hpp"

namespace epicycle::app {

void ParseBranch(const std::string& option, const std::string& spec,
                 dynamics::BranchRequest* request) {
  dynamics::ParseBranchRange(option, spec, option != "--continue", request);
  // The period's refusal reaches --continue only (a periodic speed sweep falls back on time
  // integration instead, dynamic_commands.cpp).
  request->names.max_points = "--periodic-points";
  request->names.period = option == "--continue" ? "--continue" : "--periodic";
}

namespace {

// The program's sink: the header, each point's console line and CSV line as it is computed.
class ConsoleBranchSink final : public dynamics::BranchSink {
 public:
  ConsoleBranchSink(const BranchArgs& a, nlohmann::json provenance)
      : a_(a), provenance_(std::move(provenance)) {}

  void Start(const dynamics::BranchPlan& plan) override {
    Print(report::BranchPlanText(plan, a_.option + " " + a_.spec));
    std::fflush(stdout);
    std::filesystem::create_directories(a_.out);
    const dynamics::StageDynamics& rig = *plan.rig;
    csv_.emplace(path() + ".csv", provenance_, plan.options->parameter,
                 rig.stage_model.helical() ? rig.stage.planets() : 0);
  }

  void Point(const dynamics::StageBranchRecord& so_far) override {
    csv_->Update(so_far);
    Print(report::BranchPointsText(so_far, printed_));
    printed_ = so_far.points.size();
    if (!a_.quiet) std::fflush(stdout);
  }

  void Close() {
    if (csv_) csv_->Close();
  }
  std::string path() const { return a_.out + "/periodic_branch"; }
  const nlohmann::json& provenance() const { return provenance_; }

 private:
  const BranchArgs& a_;
  nlohmann::json provenance_;
  std::optional<report::BranchFile> csv_;
  std::size_t printed_ = 0;
};

}  // namespace

void RunBranch(const BranchArgs& a, const dynamics::BranchRequest& request) {
  ConsoleBranchSink sink(a, Provenance(request.run.backend, &request.run.scene));
  const dynamics::BranchRecord rec = dynamics::RunBranch(request, sink);
  sink.Close();
  const std::string path = sink.path();
  WriteTextFile(path + "_summary.json", report::SummaryJson(rec, sink.provenance()).dump(2) + "\n");
  report::WriteBranchPlots(path, rec.scene, rec.branch);
  PrintWarnings(rec.warnings);
  Print(report::BranchRecordText(rec));
  std::printf(
      "\nwrote %s.csv, _summary.json, _k_gamma.svg, _te_amplitude.svg, "
      "_spectral_radius.svg\n",
      path.c_str());
  if (!rec.ok())
    throw ComputationFailed(rec.branch.message.empty() ? rec.branch.figures_message
                                                       : rec.branch.message);
}

}  // namespace epicycle::app
