#include "speed_sweep_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "epicycle/dynamics/speed_sweep.hpp"
#include "progress.hpp"
#include "provenance.hpp"
#include "svg_plot.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

std::string Csv(const std::string& text) {  // a free-text cell: no commas or line breaks
  std::string s = text;
  std::replace(s.begin(), s.end(), ',', ';');
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

std::string Row(const dynamics::SpeedResult& r, const dynamics::SpeedSweepPlan& plan) {
  // A failed speed keeps its speed, status and message; its figures are empty (not zeros).
  auto v = [&](double x) { return r.ok ? Num(x) : std::string(); };
  return fmt::format(
      "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.index, Num(r.sun_speed_rpm),
      Num(r.mesh_frequency), r.ok ? "ok" : "failed", v(r.k_gamma), v(r.dynamic_factor),
      r.ok && r.factor_mesh >= 0 ? plan.meshes[r.factor_mesh] : "", v(r.peak_mesh_force),
      v(r.te_amplitude * 1e6), v(r.orbit_radius * 1e6), v(r.lsr_min), v(r.lsr_max), r.stats.steps,
      r.stats.rhs_evaluations, r.stats.failed_solves, Num(r.cpu_seconds), Num(r.wall_seconds),
      Csv(r.message));
}

std::string ModeName(const dynamics::SpeedSweepPlan& plan, int mode) {
  const dynamics::Mode& m = plan.modes[static_cast<std::size_t>(mode)].mode;
  return fmt::format("mode {} ({}, {:.0f} Hz)", mode + 1, dynamics::ModeTypeName(m.type),
                     m.frequency);
}

}  // namespace

std::vector<double> ParseSpeedSweep(const std::string& spec) {
  const std::string rule =
      "must be FROM:TO:N, sun speeds in rpm with N speeds, ends included (e.g. 500:12000:24)";
  const auto a = spec.find(':'), b = a == std::string::npos ? a : spec.find(':', a + 1);
  if (b == std::string::npos || spec.find(':', b + 1) != std::string::npos)
    throw std::invalid_argument("--speed-sweep = " + spec + ": " + rule);
  double from = 0, to = 0;
  long n = 0;
  try {
    std::size_t used = 0;
    const std::string f = spec.substr(0, a), t = spec.substr(a + 1, b - a - 1),
                      c = spec.substr(b + 1);
    from = std::stod(f, &used);
    if (used != f.size()) throw std::invalid_argument(f);
    to = std::stod(t, &used);
    if (used != t.size()) throw std::invalid_argument(t);
    n = std::stol(c, &used);
    if (used != c.size()) throw std::invalid_argument(c);
  } catch (const std::logic_error&) {
    throw std::invalid_argument("--speed-sweep = " + spec + ": " + rule);
  }
  if (n > 100000)
    throw std::invalid_argument("--speed-sweep = " + spec + ": N = " + std::to_string(n) +
                                ": must be <= 100000");
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
  o.window_cycles = a.window_cycles > 0       ? a.window_cycles
                    : a.range == "cycle"      ? 1.0
                    : a.range == "revolution" ? static_cast<double>(stage.ring().teeth())
                                              : static_cast<double>(stage.planet(0).teeth());
  o.outputs_per_cycle = a.outputs_per_cycle;
  o.harmonics = a.harmonics;
  o.window_start = geometry::Rad(a.start_deg);
  o.simulation = simulation;
  // The modes from the tangent mesh stiffness (dynamics/speed_sweep.hpp: the resonances sit at its
  // coincidences, not at the secant's).
  o.modal_mesh_stiffness = dynamics::MeanTangentMeshStiffness(scene, stage, rig.fe);

  std::printf("%s: speed sweep, %zu sun speeds %.1f .. %.1f rpm, sun %s, %d threads\n",
              scene.name.c_str(), o.sun_speeds_rpm.size(), o.sun_speeds_rpm.front(),
              o.sun_speeds_rpm.back(),
              rig.stage_model.setup().sun == transmission::SunSupport::kFixed      ? "fixed"
              : rig.stage_model.setup().sun == transmission::SunSupport::kFloating ? "floating"
                                                                                   : "elastic",
              o.threads);
  for (const std::string& m : rig.compliance.tables().messages()) std::printf("  %s\n", m.c_str());
  std::printf(
      "  mean mesh stiffness: sun-planet %.4g N/m, planet-ring %.4g N/m (secant F/delta: the "
      "mesh damping %.4g and %.4g N s/m); tangent dF/ddelta %.4g and %.4g N/m (the modes); "
      "friction %s, rtol %.1e\n",
      base.sun_mesh_stiffness(), base.ring_mesh_stiffness(), base.sun_mesh_damping(),
      base.ring_mesh_damping(), o.modal_mesh_stiffness[0], o.modal_mesh_stiffness[1],
      scene.dynamics.friction.c_str(), simulation.rtol);

  std::filesystem::create_directories(a.out);
  const std::string path = a.out + "/speed_sweep";
  std::ofstream csv(path + ".csv");
  if (!csv) throw std::runtime_error(path + ".csv: cannot be written");
  const json provenance = Provenance(a.backend, &scene);
  csv << ProvenanceCsvLine(provenance);
  csv << "index,sun_speed_rpm,mesh_frequency_Hz,status,K_gamma,dynamic_factor,"
         "dynamic_factor_mesh,peak_mesh_force_N,te_amplitude_urad,sun_orbit_radius_um,lsr_min,"
         "lsr_max,steps,evaluations,failed_contact_solves,cpu_s,wall_s,message\n";
  csv.flush();

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
        csv << Row(r, plan);
        csv.flush();
        ++done;
        failed += !r.ok;
        if (tty)
          Progress(done, static_cast<int>(o.sun_speeds_rpm.size()), failed,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                   "speeds");
      });

  std::printf("\n  %-10s %-9s %-9s %-9s %-13s %-11s %-10s %s\n", "sun rpm", "K_gamma", "K_v",
              "mesh", "TE amp urad", "orbit um", "CPU s", "status");
  double cpu = 0;
  json speeds = json::array();
  for (const dynamics::SpeedResult& r : res.speeds) {
    cpu += r.cpu_seconds;
    const std::string mesh = r.factor_mesh >= 0 ? plan.meshes[r.factor_mesh] : "";
    std::printf("  %-10.1f %-9.5f %-9.5f %-9s %-13.3f %-11.4f %-10.2f %s\n", r.sun_speed_rpm,
                r.k_gamma, r.dynamic_factor, mesh.c_str(), r.te_amplitude * 1e6,
                r.orbit_radius * 1e6, r.cpu_seconds, r.ok ? "ok" : r.message.c_str());
    json j = {{"sun_speed_rpm", r.sun_speed_rpm},
              {"mesh_frequency_Hz", r.mesh_frequency},
              {"ok", r.ok},
              {"message", r.message},
              {"steps", r.stats.steps},
              {"evaluations", r.stats.rhs_evaluations},
              {"failed_contact_solves", r.stats.failed_solves},
              {"cpu_s", r.cpu_seconds},
              {"wall_s", r.wall_seconds},
              {"warnings", r.warnings}};
    if (r.ok) {
      j["K_gamma"] = r.k_gamma;
      j["dynamic_factor"] = r.dynamic_factor;
      j["dynamic_factor_mesh"] = mesh;
      j["peak_mesh_force_N"] = r.peak_mesh_force;
      j["te_amplitude_urad"] = r.te_amplitude * 1e6;
      j["sun_orbit_radius_um"] = r.orbit_radius * 1e6;
      j["lsr_min"] = r.lsr_min;
      j["lsr_max"] = r.lsr_max;
    }
    speeds.push_back(j);
  }
  std::printf(
      "  %.1f s wall for %zu speeds on %d threads, %.1f s CPU in the speeds (%.2f s per speed; "
      "CPU/wall %.2f: the parallel speed-up on an otherwise idle machine)\n",
      res.wall_seconds, res.speeds.size(), o.threads, cpu,
      cpu / static_cast<double>(res.speeds.size()), cpu / std::max(res.wall_seconds, 1e-9));

  json modes = json::array(), coincidences = json::array();
  for (const dynamics::ModeDamping& m : plan.modes)
    modes.push_back({{"frequency_Hz", m.mode.frequency},
                     {"type", dynamics::ModeTypeName(m.mode.type)},
                     {"multiplicity", m.mode.multiplicity},
                     {"cyclic_families_k", m.families},
                     {"damping_ratio", m.damping_ratio},
                     {"decay_rate_per_s", m.decay_rate}});
  for (const dynamics::Coincidence& c : plan.coincidences)
    coincidences.push_back({{"sun_speed_rpm", c.sun_speed_rpm},
                            {"frequency_Hz", c.frequency},
                            {"mode", c.mode + 1},
                            {"harmonic", c.harmonic},
                            {"phasing_excited", c.phasing_excited}});
  json qs_force = json::object();
  for (std::size_t q = 0; q < plan.meshes.size(); ++q)
    qs_force[plan.meshes[q]] = plan.qs_peak_mesh_force[q];
  json j;
  j["provenance"] = provenance;
  // The scene's warnings and each speed's results outside the model's validity.
  std::vector<std::string> warnings = scene.warnings;
  for (const dynamics::SpeedResult& r : res.speeds)
    for (const std::string& w : r.warnings)
      warnings.push_back(fmt::format("at {} rpm: {}", Num(r.sun_speed_rpm), w));
  j["warnings"] = warnings;
  j["scene"] = scene.name;
  j["sun_torque_Nm"] = scene.loads.sun_torque;
  j["friction"] = scene.dynamics.friction;
  j["integrator"] = a.integrator;
  j["rtol"] = simulation.rtol;
  j["atol_length_m"] = simulation.atol_length;
  j["atol_angle_rad"] = simulation.atol_angle;
  // 0: each speed's highest linearised natural frequency (its row's run reports it).
  j["rate_tolerance_scale_rad_per_s"] = simulation.rate_scale;
  j["contact_tolerance"] = simulation.contact.tolerance;
  j["backend"] = a.backend;
  j["definitions"] = {
      {"K_gamma", "max over window samples and planets of n LSR_i"},
      {"dynamic_factor",
       "max over meshes of (peak total normal force of the mesh in motion, damping included) / "
       "(peak quasi-static total normal force of that mesh at the same carrier angles)"},
      {"te_amplitude", "half the peak-to-peak dynamic transmission error at the sun"},
      {"sun_orbit_radius", "largest sun-centre displacement over the window"},
      {"window",
       "each speed starts at the quasi-static solution, skips skip_time_s (start transient below "
       "transient_fraction in every mode) and measures window_mesh_cycles from "
       "window_start_carrier_deg"}};
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
  j["quasi_static_peak_mesh_force_N"] = qs_force;
  j["modes"] = modes;
  j["coincidences"] = coincidences;
  j["speeds"] = speeds;
  j["failed_speeds"] = res.failed();
  j["threads"] = o.threads;
  j["plan_seconds"] = plan.seconds;
  j["wall_seconds"] = res.wall_seconds;
  j["cpu_seconds_in_speeds"] = cpu;
  j["cpu_over_wall"] = cpu / std::max(res.wall_seconds, 1e-9);
  WriteTextFile(path + "_summary.json", j.dump(2) + "\n");

  // Plots against speed, the coincidences marked (dashed: not reached by a symmetric stage's
  // mesh excitation, see dynamics/speed_sweep.hpp).
  std::vector<XMarker> markers;
  for (const dynamics::Coincidence& c : plan.coincidences) {
    // A degenerate pair split by an error (e.g. 4941.95 and 4942.25 Hz): one marker "m2,3 h4".
    const std::string tail = fmt::format(" h{}", c.harmonic);
    if (!markers.empty() &&
        std::abs(markers.back().x - c.sun_speed_rpm) <= 1e-3 * c.sun_speed_rpm &&
        markers.back().label.ends_with(tail)) {
      XMarker& m = markers.back();
      m.label.insert(m.label.size() - tail.size(), fmt::format(",{}", c.mode + 1));
      m.dashed = m.dashed && !c.phasing_excited;
      continue;
    }
    markers.push_back({c.sun_speed_rpm, fmt::format("m{}", c.mode + 1) + tail, !c.phasing_excited});
  }
  auto plot = [&](const std::string& what, const std::string& unit, const std::string& file,
                  double scale, auto field, std::vector<double> refs) {
    LinePlot p{scene.name + ": " + what + " against sun speed",
               "sun speed [rpm]",
               what + " [" + unit + "]",
               {},
               false,
               std::move(refs)};
    PlotSeries s{what, {}, {}, false};
    for (const dynamics::SpeedResult& r : res.speeds) {
      if (!r.ok) continue;
      s.x.push_back(r.sun_speed_rpm);
      s.y.push_back(field(r) * scale);
    }
    p.series.push_back(s);
    p.x_markers = markers;
    WriteTextFile(path + "_" + file + ".svg", RenderSvg(p));
  };
  plot("K_gamma", "-", "k_gamma", 1.0, [](const auto& r) { return r.k_gamma; }, {plan.qs_k_gamma});
  plot("dynamic factor", "-", "dynamic_factor", 1.0, [](const auto& r) { return r.dynamic_factor; },
       {1.0});
  plot("TE amplitude", "urad", "te_amplitude", 1e6, [](const auto& r) { return r.te_amplitude; },
       {plan.qs_te_amplitude * 1e6});
  plot("sun orbit radius", "um", "orbit", 1e6, [](const auto& r) { return r.orbit_radius; }, {});
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
