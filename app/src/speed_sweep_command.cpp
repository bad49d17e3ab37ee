#include "speed_sweep_command.hpp"

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
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/report/speed_sweep_run_files.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "options.hpp"

namespace epicycle::app {

using json = nlohmann::json;

namespace {

// The program's sink: the CSV row of each speed as it completes, the plan on the console and the
// progress bar.
class ConsoleSweepSink final : public dynamics::SpeedSweepSink {
 public:
  ConsoleSweepSink(const SpeedSweepArgs& a, json provenance)
      : a_(a), provenance_(std::move(provenance)), bar_(a.quiet) {}

  void Start(const dynamics::SpeedSweepStart& start) override {
    Print(report::SpeedSweepPlanText(start));
    std::fflush(stdout);  // the plan is on screen (or in a log) before the runs start
    std::filesystem::create_directories(a_.out);
    const dynamics::StageDynamics& rig = *start.rig;
    csv_.emplace(path() + ".csv", provenance_, rig.stage_model.helical() ? rig.stage.planets() : 0);
    count_ = static_cast<int>(start.options->sun_speeds_rpm.size());
    bar_.Restart();
  }

  void Speed(const dynamics::SpeedResult& r, const dynamics::SpeedSweepPlan& plan) override {
    csv_->Write(r, plan);
    ++done_;
    failed_ += !r.ok();
    bar_.Show(done_, count_, failed_, "speeds");
  }

  void Close() { csv_->Close(); }
  std::string path() const { return a_.out + "/speed_sweep"; }
  const json& provenance() const { return provenance_; }

 private:
  const SpeedSweepArgs& a_;
  json provenance_;
  ProgressBar bar_;
  std::optional<report::SpeedSweepFile> csv_;
  int count_ = 0, done_ = 0, failed_ = 0;
};

}  // namespace

void RunSpeedSweep(const SpeedSweepArgs& a, dynamics::SpeedSweepRequest request) {
  request.sun_speeds_rpm = dynamics::ParseSpeedSweep("--speed-sweep", a.spec);
  ConsoleSweepSink sink(a, Provenance(a.backend, &request.run.scene));
  const dynamics::SpeedSweepRecord record = dynamics::RunSpeedSweep(request, sink);
  sink.Close();
  Print(report::SpeedSweepRecordText(record));
  const std::string path = sink.path();
  WriteTextFile(path + "_summary.json",
                report::SpeedSweepRecordJson(record, sink.provenance()).dump(2) + "\n");
  report::WriteSpeedSweepPlots(path, record.scene, record.plan, record.speeds);
  PrintWarnings(record.warnings);
  std::printf(
      "\nwrote %s.csv, _summary.json, _k_gamma.svg, _dynamic_factor.svg, _te_amplitude.svg, "
      "_orbit.svg\n",
      path.c_str());
  if (record.failed() > 0) {
    std::string list;
    for (const dynamics::SpeedResult& r : record.speeds)
      if (!r.ok()) list += fmt::format("; {} rpm: {}", io::Num(r.sun_speed_rpm, 9), r.message);
    throw ComputationFailed(
        fmt::format("{} of {} speeds failed{}", record.failed(), record.speeds.size(), list));
  }
}

}  // namespace epicycle::app
