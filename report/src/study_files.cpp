#include "epicycle/report/study_files.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "epicycle/report/files.hpp"

namespace epicycle::report {

namespace {

nlohmann::json Stat(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

nlohmann::json SampleSummaryJson(const studies::SampleSummary& s) {
  nlohmann::json j = {{"count", s.count},
                      {"mean", Stat(s.mean)},
                      {"mean_ci", {Stat(s.mean_lower), Stat(s.mean_upper)}},
                      {"std", Stat(s.standard_deviation)},
                      {"min", Stat(s.min)},
                      {"max", Stat(s.max)},
                      {"confidence_level", s.level}};
  nlohmann::json p = nlohmann::json::array();
  for (const auto& q : s.percentiles)
    p.push_back({{"p", q.p}, {"value", Stat(q.value)}, {"ci", {Stat(q.lower), Stat(q.upper)}}});
  j["percentiles"] = p;
  return j;
}

nlohmann::json ExceedanceJson(const studies::Exceedance& e) {
  return {{"k_gamma_limit", e.threshold},
          {"cases", e.count},
          {"above", e.above},
          {"probability", Stat(e.p)},
          {"ci", {Stat(e.lower), Stat(e.upper)}},
          {"interval", "Clopper-Pearson (exact binomial)"},
          {"confidence_level", e.level}};
}

std::string ExceedanceText(const studies::Exceedance& e) {
  const char* f = "{:.4f}";
  return fmt::format("  P(K_gamma > {}) = {} [{}, {}] ({} of {} cases; {:g} % Clopper-Pearson)\n",
                     e.threshold, Num(e.p, f, "-"), Num(e.lower, f, "-"), Num(e.upper, f, "-"),
                     e.above, e.count, 100.0 * e.level);
}

std::string SampleSummaryText(const std::string& name, const studies::SampleSummary& s,
                              const std::string& unit) {
  const char* f = "{:.6g}";
  std::string out =
      fmt::format("  {:<22} mean {} [{}, {}], std {}, max {}{}\n", name, Num(s.mean, f, "-"),
                  Num(s.mean_lower, f, "-"), Num(s.mean_upper, f, "-"),
                  Num(s.standard_deviation, f, "-"), Num(s.max, f, "-"), unit);
  for (const auto& q : s.percentiles)
    out += fmt::format("  {:<22} P{:<5} {} [{}, {}]\n", "", 100.0 * q.p, Num(q.value, f, "-"),
                       Num(q.lower, f, "-"), Num(q.upper, f, "-"));
  return out;
}

nlohmann::json StudyRootStressJson(const std::vector<studies::GearStressStatistics>& gears) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& g : gears) {
    nlohmann::json e = {{"gear", g.gear},
                        {"tension_MPa", SampleSummaryJson(g.tension)},
                        {"compression_magnitude_MPa", SampleSummaryJson(g.compression)},
                        {"largest_range_MPa", SampleSummaryJson(g.range)}};
    if (g.s_f.count > 0) e["S_F"] = SampleSummaryJson(g.s_f);
    if (g.s_h.count > 0) e["S_H"] = SampleSummaryJson(g.s_h);
    list.push_back(e);
  }
  return list;
}

std::string StudyRootStressText(const std::vector<studies::GearStressStatistics>& gears) {
  if (gears.empty()) return "";
  // The P95 of each (kStudyPercentiles' second level) with its interval.
  auto cell = [](const studies::SampleSummary& s) {
    const char* f = "{:.1f}";
    for (const auto& q : s.percentiles)
      if (q.p == 0.95)
        return fmt::format("{:>7} {:>7} [{}, {}]", Num(s.mean, f, "-"), Num(q.value, f, "-"),
                           Num(q.lower, f, "-"), Num(q.upper, f, "-"));
    return fmt::format("{:>7}", Num(s.mean, f, "-"));
  };
  std::string out = fmt::format(
      "  root stress [MPa], each case's largest: mean, P95 [CI]\n    {:<8}  {:<30} {:<30} {}\n",
      "gear", "tension", "|compression|", "range");
  for (const auto& g : gears)
    out += fmt::format("    {:<8}  {:<30} {:<30} {}\n", g.gear, cell(g.tension),
                       cell(g.compression), cell(g.range));
  if (std::none_of(gears.begin(), gears.end(), [](const auto& g) { return g.s_f.count > 0; }))
    return out;
  // The safety factors' low tail: the P5 (kSafetyPercentiles' second level) and the smallest.
  auto low = [](const studies::SampleSummary& s) {
    const char* f = "{:.2f}";
    for (const auto& q : s.percentiles)
      if (q.p == 0.05)
        return fmt::format("{:>6} {:>6} [{}, {}] {:>6}", Num(s.mean, f, "-"), Num(q.value, f, "-"),
                           Num(q.lower, f, "-"), Num(q.upper, f, "-"), Num(s.min, f, "-"));
    return fmt::format("{:>6}", Num(s.mean, f, "-"));
  };
  out += fmt::format(
      "  safety factors from each case's own stresses: mean, P5 [CI], smallest\n    {:<8}  {:<34} "
      "{}\n",
      "gear", "S_F (root tension)", "S_H (contact pressure)");
  for (const auto& g : gears)
    out += fmt::format("    {:<8}  {:<34} {}\n", g.gear, low(g.s_f), low(g.s_h));
  return out;
}

}  // namespace epicycle::report
