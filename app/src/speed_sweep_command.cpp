#include "speed_sweep_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
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

std::vector<double> ParseSpeedSweep(const std::string& spec) {
  const std::string rule =
      "must be FROM:TO:N, sun speeds in rpm with N speeds, ends included (e.g. 500:12000:24)";
  const auto a = spec.find(':'), b = a == std::string::npos ? a : spec.find(':', a + 1);
  if (b == std::string::npos || spec.find(':', b + 1) != std::string::npos)
    throw std::invalid_argument("--speed-sweep = " + spec + ": " + rule);
  double from = 0, to = 0;
  long n = 0;
  const std::string f = spec.substr(0, a), t = spec.substr(a + 1, b - a - 1),
                    c = spec.substr(b + 1);
  try {
    std::size_t used = 0;
    from = std::stod(f, &used);
    if (used != f.size()) throw std::invalid_argument(f);
    to = std::stod(t, &used);
    if (used != t.size()) throw std::invalid_argument(t);
    n = std::stol(c, &used);
    if (used != c.size()) throw std::invalid_argument(c);
  } catch (const std::logic_error&) {
    throw std::invalid_argument("--speed-sweep = " + spec + ": " + rule);
  }
  if (!kSunSpeedRpm.Holds(from))
    throw std::invalid_argument("--speed-sweep = " + spec + ": FROM = " + f + ": " +
                                kSunSpeedRpm.Describe());
  if (!kSunSpeedRpm.Holds(to))
    throw std::invalid_argument("--speed-sweep = " + spec + ": TO = " + t + ": " +
                                kSunSpeedRpm.Describe());
  if (!kSweepSpeeds.Holds(static_cast<double>(n)) && n > 0)
    throw std::invalid_argument("--speed-sweep = " + spec + ": N = " + std::to_string(n) + ": " +
                                kSweepSpeeds.Describe());
  try {
    return dynamics::SpeedGrid(from, to, static_cast<int>(n));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--speed-sweep = " + spec + ": " + e.what());
  }
}

namespace {

// The program's sink: the CSV row of each speed as it completes, the plan on the console and the
// progress bar.
class ConsoleSweepSink final : public dynamics::SpeedSweepSink {
 public:
  ConsoleSweepSink(const SpeedSweepArgs& a, json provenance)
      : a_(a), provenance_(std::move(provenance)), tty_(!a.quiet && isatty(fileno(stderr))) {}

  void Start(const dynamics::SpeedSweepStart& start) override {
    Print(report::SpeedSweepPlanText(start));
    std::fflush(stdout);  // the plan is on screen (or in a log) before the runs start
    std::filesystem::create_directories(a_.out);
    const dynamics::StageDynamics& rig = *start.rig;
    csv_.emplace(path() + ".csv", provenance_, rig.stage_model.helical() ? rig.stage.planets() : 0);
    count_ = static_cast<int>(start.options->sun_speeds_rpm.size());
    t0_ = std::chrono::steady_clock::now();
  }

  void Speed(const dynamics::SpeedResult& r, const dynamics::SpeedSweepPlan& plan) override {
    csv_->Write(r, plan);
    ++done_;
    failed_ += !r.ok();
    if (tty_)
      Progress(done_, count_, failed_,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(),
               "speeds");
  }

  void Close() { csv_->Close(); }
  std::string path() const { return a_.out + "/speed_sweep"; }
  const json& provenance() const { return provenance_; }

 private:
  const SpeedSweepArgs& a_;
  json provenance_;
  bool tty_;
  std::optional<report::SpeedSweepFile> csv_;
  int count_ = 0, done_ = 0, failed_ = 0;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace

void RunSpeedSweep(const SpeedSweepArgs& a, dynamics::SpeedSweepRequest request) {
  request.sun_speeds_rpm = ParseSpeedSweep(a.spec);
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
