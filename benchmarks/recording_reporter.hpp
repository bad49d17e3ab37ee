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
      if (!fresh && !(s < it->second)) continue;
      it->second = s;
      // The counters of the run kept (the least disturbed).
      std::map<std::string, double>& kept = counters_[run.benchmark_name()];
      kept.clear();
      for (const auto& [name, counter] : run.counters) kept[name] = counter.value;
      const auto c = run.counters.find("converged");
      if (c != run.counters.end()) converged_[run.benchmark_name()] = c->second.value > 0.5;
    }
  }
  /// CPU seconds per iteration, NaN if the benchmark did not run.
  double seconds(const std::string& name) const {
    const auto it = seconds_.find(name);
    return it == seconds_.end() ? NAN : it->second;
  }
  /// A counter of the kept run (the least CPU time), NaN if the benchmark did not run or has no
  /// such counter.
  double counter(const std::string& name, const std::string& counter) const {
    const auto it = counters_.find(name);
    if (it == counters_.end()) return NAN;
    const auto c = it->second.find(counter);
    return c == it->second.end() ? NAN : c->second;
  }
  bool converged(const std::string& name) const {
    const auto it = converged_.find(name);
    return it != converged_.end() && it->second;
  }

 private:
  std::map<std::string, double> seconds_;
  std::map<std::string, bool> converged_;
  std::map<std::string, std::map<std::string, double>> counters_;
};

}  // namespace epicycle::bench
