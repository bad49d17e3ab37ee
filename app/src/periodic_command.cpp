#include "periodic_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "console.hpp"
#include "epicycle/io/number_format.hpp"
#include "epicycle/report/branch_files.hpp"
#include "epicycle/report/record_json.hpp"
#include "speed_sweep_command.hpp"

namespace epicycle::app {

namespace {

// A branch's parameter, range and steps as the user gave them.
struct BranchRange {
  std::string parameter;
  double from = 0, to = 0;
  int steps = 0;
};

// NAME:FROM:TO:N of --continue.
void ParseContinue(const std::string& spec, BranchRange* b) {
  const std::string rule =
      "must be NAME:FROM:TO:N, a number of the scene by its key path, its range and at least N "
      "steps (e.g. sun_torque_Nm:-600:-100:20, errors.pin.planet1.tangential_um:0:4:10)";
  std::vector<std::string> parts;
  std::size_t at = 0;
  for (std::size_t c; (c = spec.find(':', at)) != std::string::npos; at = c + 1)
    parts.push_back(spec.substr(at, c - at));
  parts.push_back(spec.substr(at));
  if (parts.size() != 4) throw std::invalid_argument("--continue = " + spec + ": " + rule);
  b->parameter = parts[0];
  try {
    std::size_t used = 0;
    b->from = std::stod(parts[1], &used);
    if (used != parts[1].size()) throw std::invalid_argument(parts[1]);
    b->to = std::stod(parts[2], &used);
    if (used != parts[2].size()) throw std::invalid_argument(parts[2]);
    b->steps = std::stoi(parts[3], &used);
    if (used != parts[3].size()) throw std::invalid_argument(parts[3]);
  } catch (const std::logic_error&) {
    throw std::invalid_argument("--continue = " + spec + ": " + rule);
  }
}

}  // namespace

void ParseBranch(const std::string& option, const std::string& spec,
                 dynamics::BranchRequest* request) {
  BranchRange b;
  if (option == "--continue") {
    ParseContinue(spec, &b);
  } else {
    const std::vector<double> grid = ParseSpeedSweep(spec);
    b.parameter = dynamics::StagePeriodicSystem::kSunSpeed;
    b.from = grid.front();
    b.to = grid.back();
    b.steps = static_cast<int>(grid.size());
  }
  if (!std::isfinite(b.from) || !std::isfinite(b.to) || b.from == b.to)
    throw std::invalid_argument(option + " = " + spec + ": FROM = " + io::Num(b.from, 9) + ", TO = " +
                                io::Num(b.to, 9) + ": a continuation's range must have non-zero width");
  if (b.steps < 1)
    throw std::invalid_argument(option + " = " + spec + ": N = " + std::to_string(b.steps) +
                                ": must be >= 1 (the largest step is 1/N of the range)");
  request->parameter = b.parameter;
  request->start = b.from;
  request->end = b.to;
  request->steps = b.steps;
  // The period's refusal reaches --continue only (a periodic speed sweep falls back on time
  // integration instead, dynamic_commands.cpp).
  request->names = {option + " NAME", option + " N", "--periodic-points",
                    option == "--continue" ? "--continue" : "--periodic"};
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
