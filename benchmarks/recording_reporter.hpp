// A console reporter that also records each benchmark's CPU seconds per iteration (and whether
// its answer converged), so that a benchmark program can print the ratios its targets are stated
// in after the runs. Shared by bench_contact and bench_dynamics.
#pragma once

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace epicycle::bench {

class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred || run.iterations == 0) continue;
      // CPU time: the machine is shared, and wall time counts the other processes. With
      // repetitions, the smallest (the least disturbed) is kept.
      const double s = run.cpu_accumulated_time / static_cast<double>(run.iterations);
      const auto [it, fresh] = seconds_.emplace(run.benchmark_name(), s);
      if (!fresh) it->second = std::min(it->second, s);
      const auto c = run.counters.find("converged");
      if (c != run.counters.end()) converged_[run.benchmark_name()] = c->second.value > 0.5;
    }
  }
  /// CPU seconds per iteration, NaN if the benchmark did not run.
  double seconds(const std::string& name) const {
    const auto it = seconds_.find(name);
    return it == seconds_.end() ? NAN : it->second;
  }
  bool converged(const std::string& name) const {
    const auto it = converged_.find(name);
    return it != converged_.end() && it->second;
  }

 private:
  std::map<std::string, double> seconds_;
  std::map<std::string, bool> converged_;
};

}  // namespace epicycle::bench
