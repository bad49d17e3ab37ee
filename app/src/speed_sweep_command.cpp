#include "speed_sweep_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "console.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "options.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

std::string ModeName(const dynamics::SpeedSweepPlan& plan, int mode) {
  const dynamics::Mode& m = plan.modes[static_cast<std::size_t>(mode)].mode;
  return fmt::format("mode {} ({}, {:.0f} Hz)", mode + 1, dynamics::ModeTypeName(m.type),
                     m.frequency);
}

}  // namespace

void AddTolerances(const dynamics::SimulationOptions& simulation, const std::string& backend,
                   nlohmann::json* j) {
  (*j)["rtol"] = simulation.rtol;
  (*j)["atol_length_m"] = simulation.atol_length;
  (*j)["atol_angle_rad"] = simulation.atol_angle;
  (*j)["rate_tolerance_scale_rad_per_s"] = simulation.rate_scale;
  (*j)["contact_tolerance"] = simulation.contact.tolerance;
  (*j)["backend"] = backend;
}

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

void RunSpeedSweep(const SpeedSweepArgs& a, const dynamics::StageDynamics& rig,
                   const dynamics::SimulationOptions& simulation) {
  const transmission::Scene& scene = rig.scene;
  const geometry::Stage& stage = rig.stage;
  const dynamics::DynamicModel& base = rig.model;
  dynamics::SpeedSweepOptions o;
  o.sun_speeds_rpm = ParseSpeedSweep(a.spec);
  o.threads = a.threads > 0 ? a.threads
                            : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.window_cycles = a.window_cycles > 0
                        ? a.window_cycles
                        : transmission::MeshCycles(stage, transmission::RunRangeFromName(a.range));
  o.outputs_per_cycle = a.outputs_per_cycle;
  o.harmonics = a.harmonics;
  o.window_start = geometry::Rad(a.start_deg);
  o.simulation = simulation;
  // The modes from the tangent mesh stiffness (dynamics/speed_sweep.hpp: the resonances sit at its
  // coincidences, not at the secant's).
  o.modal_mesh_stiffness = dynamics::MeanTangentMeshStiffness(scene, stage, rig.fe);

  std::printf("%s: speed sweep, %zu sun speeds %.1f .. %.1f rpm, sun %s, %d threads\n",
              scene.name.c_str(), o.sun_speeds_rpm.size(), o.sun_speeds_rpm.front(),
              o.sun_speeds_rpm.back(), transmission::SunSupportName(rig.stage_model.setup().sun),
              o.threads);
  for (const std::string& m : rig.compliance.tables().messages()) std::printf("  %s\n", m.c_str());
  std::printf(
      "  mean mesh stiffness: sun-planet %.4g N/m, planet-ring %.4g N/m (secant F/delta: the "
      "mesh damping %.4g and %.4g N s/m); tangent dF/ddelta %.4g and %.4g N/m (the modes); "
      "friction %s, rtol %.1e\n",
      base.sun_mesh_stiffness(), base.ring_mesh_stiffness(), base.sun_mesh_damping(),
      base.ring_mesh_damping(), o.modal_mesh_stiffness[0], o.modal_mesh_stiffness[1],
      transmission::FrictionLawName(scene.dynamics.friction.law).c_str(), simulation.rtol);

  std::filesystem::create_directories(a.out);
  const std::string path = a.out + "/speed_sweep";
  const json provenance = Provenance(a.backend, &scene);
  report::SpeedSweepFile csv(path + ".csv", provenance);

  const dynamics::SpeedSweepPlan plan = dynamics::PlanSpeedSweep(base, o);
  std::printf("  modes of the linearised stage (f, type, modal damping ratio, decay rate):\n");
  for (std::size_t j = 0; j < plan.modes.size(); ++j) {
    const dynamics::ModeDamping& m = plan.modes[j];
    std::string k;
    for (int f : m.families) {
      if (!k.empty()) k += ',';
      k += std::to_string(f);
    }
    std::printf("    mode %-3zu %10.2f Hz  %-13s x%d  family k = %-5s zeta %.4f  sigma %.1f 1/s\n",
                j + 1, m.mode.frequency, dynamics::ModeTypeName(m.mode.type).c_str(),
                m.mode.multiplicity, k.c_str(), m.damping_ratio, m.decay_rate);
  }
  std::printf("  coincidences h f_m = f_j in the range (mesh frequency %.4f Hz per sun rpm):\n",
              plan.mesh_hz_per_rpm);
  for (const dynamics::Coincidence& c : plan.coincidences)
    std::printf("    %9.1f rpm  harmonic %d x %s%s\n", c.sun_speed_rpm, c.harmonic,
                ModeName(plan, c.mode).c_str(),
                c.phasing_excited ? "" : "  (not excited by a symmetric stage: planet phasing)");
  std::printf(
      "  per speed: the quasi-static start, %.3f ms skipped (ln(1/%.0e)/sigma_min, sigma_min = "
      "%.1f 1/s), then %.4g mesh cycles measured from carrier %.3f deg (%zu samples); "
      "quasi-static reference over the same positions: K_gamma %.6f (planned in %.2f s)\n",
      plan.skip_time * 1e3, o.transient_fraction, plan.slowest_decay_rate, o.window_cycles,
      a.start_deg, plan.window_angles.size(), plan.qs_k_gamma, plan.seconds);
  std::fflush(stdout);  // the plan is on screen (or in a log) before the runs start

  const bool tty = !a.quiet && isatty(fileno(stderr));
  int done = 0, failed = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const dynamics::SpeedSweepResult res =
      dynamics::SweepSpeeds(base, o, plan, [&](const dynamics::SpeedResult& r) {
        csv.Write(r, plan);
        ++done;
        failed += !r.ok;
        if (tty)
          Progress(done, static_cast<int>(o.sun_speeds_rpm.size()), failed,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                   "speeds");
      });
  csv.Close();

  std::printf("\n  %-10s %-9s %-9s %-9s %-13s %-11s %-10s %s\n", "sun rpm", "K_gamma", "K_v",
              "mesh", "TE amp urad", "orbit um", "CPU s", "status");
  double cpu = 0;
  for (const dynamics::SpeedResult& r : res.speeds) {
    cpu += r.cpu_seconds;
    const std::string mesh = r.factor_mesh >= 0 ? plan.meshes[r.factor_mesh] : "";
    std::printf("  %-10.1f %-9.5f %-9.5f %-9s %-13.3f %-11.4f %-10.2f %s\n", r.sun_speed_rpm,
                r.k_gamma, r.dynamic_factor, mesh.c_str(), r.te_amplitude * 1e6,
                r.orbit_radius * 1e6, r.cpu_seconds, r.ok ? "ok" : r.message.c_str());
  }
  std::printf(
      "  %.1f s wall for %zu speeds on %d threads, %.1f s CPU in the speeds (%.2f s per speed; "
      "CPU/wall %.2f: the parallel speed-up on an otherwise idle machine)\n",
      res.wall_seconds, res.speeds.size(), o.threads, cpu,
      cpu / static_cast<double>(res.speeds.size()), cpu / std::max(res.wall_seconds, 1e-9));

  // The per-speed results, the modes, the coincidences and the definitions (report library).
  json j = report::SpeedSweepResultsJson(plan, res.speeds);
  j["provenance"] = provenance;
  // The scene's warnings and each speed's results outside the model's validity.
  std::vector<std::string> warnings = scene.warnings;
  for (const dynamics::SpeedResult& r : res.speeds)
    for (const std::string& w : r.warnings)
      warnings.push_back(fmt::format("at {} rpm: {}", Num(r.sun_speed_rpm), w));
  j["warnings"] = warnings;
  j["scene"] = scene.name;
  j["sun_torque_Nm"] = scene.loads.sun_torque;
  j["friction"] = transmission::FrictionLawName(scene.dynamics.friction.law);
  j["integrator"] = a.integrator;
  // rate_tolerance_scale 0: each speed's highest linearised natural frequency (its row's run
  // reports it).
  AddTolerances(simulation, a.backend, &j);
  j["skip_time_s"] = plan.skip_time;
  j["transient_fraction"] = o.transient_fraction;
  j["slowest_modal_decay_rate_per_s"] = plan.slowest_decay_rate;
  j["window_mesh_cycles"] = o.window_cycles;
  j["window_samples"] = plan.window_angles.size();
  j["window_start_carrier_deg"] = a.start_deg;
  j["mesh_frequency_Hz_per_sun_rpm"] = plan.mesh_hz_per_rpm;
  j["mesh_stiffness_sun_planet_N_per_m"] = base.sun_mesh_stiffness();
  j["mesh_stiffness_planet_ring_N_per_m"] = base.ring_mesh_stiffness();
  j["tangent_mesh_stiffness_sun_planet_N_per_m"] = o.modal_mesh_stiffness[0];
  j["tangent_mesh_stiffness_planet_ring_N_per_m"] = o.modal_mesh_stiffness[1];
  j["quasi_static_K_gamma"] = plan.qs_k_gamma;
  j["quasi_static_te_amplitude_urad"] = plan.qs_te_amplitude * 1e6;
  j["failed_speeds"] = res.failed();
  j["threads"] = o.threads;
  j["plan_seconds"] = plan.seconds;
  j["wall_seconds"] = res.wall_seconds;
  j["cpu_seconds_in_speeds"] = cpu;
  j["cpu_over_wall"] = cpu / std::max(res.wall_seconds, 1e-9);
  WriteTextFile(path + "_summary.json", j.dump(2) + "\n");

  report::WriteSpeedSweepPlots(path, scene.name, plan, res.speeds);
  PrintWarnings(warnings);
  std::printf(
      "\nwrote %s.csv, _summary.json, _k_gamma.svg, _dynamic_factor.svg, _te_amplitude.svg, "
      "_orbit.svg\n",
      path.c_str());
  if (res.failed() > 0) {
    std::string list;
    for (const dynamics::SpeedResult& r : res.speeds)
      if (!r.ok) list += fmt::format("; {} rpm: {}", Num(r.sun_speed_rpm), r.message);
    throw ComputationFailed(
        fmt::format("{} of {} speeds failed{}", res.failed(), res.speeds.size(), list));
  }
}

}  // namespace epicycle::app
