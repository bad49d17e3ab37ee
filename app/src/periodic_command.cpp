#include "periodic_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "console.hpp"
#include "epicycle/report/branch_files.hpp"
#include "speed_sweep_command.hpp"

namespace epicycle::app {

namespace {

// The integrator's tolerances and contact back end as the summary's keys (the speed sweep's
// record names them alike: rtol, atol_length_m, atol_angle_rad, rate_tolerance_scale_rad_per_s,
// contact_tolerance, backend).
void AddTolerances(const dynamics::SimulationOptions& simulation, const std::string& backend,
                   nlohmann::json* j) {
  (*j)["rtol"] = simulation.rtol;
  (*j)["atol_length_m"] = simulation.atol_length;
  (*j)["atol_angle_rad"] = simulation.atol_angle;
  (*j)["rate_tolerance_scale_rad_per_s"] = simulation.rate_scale;
  (*j)["contact_tolerance"] = simulation.contact.tolerance;
  (*j)["backend"] = backend;
}

// NAME:FROM:TO:N of --continue.
void ParseContinue(const std::string& spec, BranchArgs* b) {
  const std::string rule =
      "must be NAME:FROM:TO:N, a parameter of the stage, its range and at least N steps (e.g. "
      "sun_torque_Nm:-600:-100:20)";
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
  std::string list;
  bool known = false;
  for (const std::string& n : dynamics::StagePeriodicSystem::ParameterNames()) {
    known = known || n == b->parameter;
    list += (list.empty() ? "" : ", ") + n;
  }
  if (!known)
    throw std::invalid_argument("--continue = " + spec + ": NAME = " + b->parameter +
                                ": not a parameter of the stage's periodic orbits (" + list + ")");
}

}  // namespace

BranchArgs ParseBranch(const std::string& option, const std::string& spec,
                       const transmission::Scene& scene) {
  BranchArgs b;
  b.option = option;
  b.spec = spec;
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
    throw std::invalid_argument(option + " = " + spec + ": FROM = " + Num(b.from) + ", TO = " +
                                Num(b.to) + ": a continuation's range must have non-zero width");
  if (b.steps < 1)
    throw std::invalid_argument(option + " = " + spec + ": N = " + std::to_string(b.steps) +
                                ": must be >= 1 (the largest step is 1/N of the range)");
  const dynamics::StagePeriod period =
      dynamics::StagePeriodMeshCycles(geometry::Stage(scene.stage), scene.damage);
  try {
    dynamics::CheckBranchPeriod(period, dynamics::StageBranchOptions{}.max_period_mesh_cycles);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--periodic: " + std::string(e.what()));
  }
  return b;
}

void RunBranch(const BranchArgs& a, const dynamics::StageDynamics& rig,
               const dynamics::SimulationOptions& simulation) {
  const transmission::Scene& scene = rig.scene;
  dynamics::StageBranchOptions o;
  o.parameter = a.parameter;
  o.start = a.from;
  o.end = a.to;
  o.period = dynamics::StagePeriodMeshCycles(rig.stage, scene.damage);
  o.max_step = std::max(1.0 / a.steps, o.min_step);
  o.initial_step = std::min(o.initial_step, o.max_step);
  if (a.max_points > 0) o.max_points = a.max_points;
  o.simulation = simulation;
  std::printf(
      "%s: periodic orbits continued over %s from %s to %s (%s), sun %s, period %ld mesh "
      "cycle(s), rtol %.1e\n",
      scene.name.c_str(), o.parameter.c_str(), Num(o.start).c_str(), Num(o.end).c_str(),
      (a.option + " " + a.spec).c_str(), transmission::SunSupportName(rig.stage_model.setup().sun),
      o.period.mesh_cycles, simulation.rtol);
  for (const std::string& m : rig.compliance.tables().messages()) std::printf("  %s\n", m.c_str());
  std::printf("  %-6s %-14s %-10s %-11s %-10s %-12s %s\n", "point", o.parameter.c_str(),
              "stability", "max |mu|", "K_gamma", "TE amp urad", "bifurcations before");
  std::fflush(stdout);

  std::filesystem::create_directories(a.out);
  const std::string path = a.out + "/periodic_branch";
  const nlohmann::json provenance = Provenance(a.backend, &scene);
  report::BranchFile csv(path + ".csv", provenance, o.parameter);
  std::size_t printed = 0;
  const dynamics::StageBranchRecord rec =
      dynamics::ContinueStageBranch(rig.model, o, [&](const dynamics::StageBranchRecord& r) {
        csv.Update(r);
        for (; printed < r.points.size(); ++printed) {
          const dynamics::StageBranchPoint& p = r.points[printed];
          std::string before;
          for (const dynamics::StageBranchBifurcation& b : r.bifurcations)
            if (b.after_point == p.index)
              before +=
                  fmt::format("{} at {} ", dynamics::BifurcationKindName(b.kind), Num(b.parameter));
          std::printf("  %-6d %-14s %-10s %-11.6f %-10.5f %-12.4f %s\n", p.index,
                      Num(p.parameter).c_str(), dynamics::StabilityName(p.stability).c_str(),
                      p.spectral_radius, p.k_gamma, p.te_amplitude * 1e6, before.c_str());
        }
        if (!a.quiet) std::fflush(stdout);
      });
  csv.Close();

  nlohmann::json j = report::BranchJson(rec);
  j["provenance"] = provenance;
  j["scene"] = scene.name;
  j["warnings"] = scene.warnings;
  AddTolerances(simulation, a.backend, &j);
  j["range"] = {o.start, o.end};
  j["max_step"] = o.max_step;
  WriteTextFile(path + "_summary.json", j.dump(2) + "\n");
  report::WriteBranchPlots(path, scene.name, rec);
  PrintWarnings(scene.warnings);
  int unstable = 0;
  for (const dynamics::StageBranchPoint& p : rec.points)
    unstable += p.stability == dynamics::Stability::kUnstable;
  std::printf(
      "\n  %zu points (%d unstable), %zu bifurcations; %ld periods integrated with the "
      "variational equations (%ld steps); %.2f s CPU, %.2f s wall\n",
      rec.points.size(), unstable, rec.bifurcations.size(), rec.integrations, rec.steps,
      rec.cpu_seconds, rec.wall_seconds);
  std::printf(
      "\nwrote %s.csv, _summary.json, _k_gamma.svg, _te_amplitude.svg, "
      "_spectral_radius.svg\n",
      path.c_str());
  if (!rec.ok()) throw ComputationFailed(rec.message.empty() ? rec.figures_message : rec.message);
}

}  // namespace epicycle::app
