// `epicycle quasistatic SCENE`: the quasi-static load sharing of a stage over a sweep of carrier
// positions. Results are written as they are computed (CSV per position and per tooth pair, a
// JSON summary at the end), with SVG plots of the load-sharing ratios, the loaded static
// transmission error and the sun's path. A position that fails is reported and the sweep goes on.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "epicycle/transmission/validity.hpp"
#include "progress.hpp"
#include "provenance.hpp"
#include "svg_plot.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

struct QuasiStaticArgs {
  std::string scene, backend = "newton", out = "quasistatic-out", range = "cycle", sun, cache, dump;
  int positions = 0;  // 0: 36 over a mesh cycle, 360 over a revolution
  int threads = 0;    // 0: one per core
  std::vector<double> angles_deg;
  double start_deg = 0.0;
  bool no_cache = false, no_local = false, quiet = false, cold = false;
};

void RunQuasiStatic(const QuasiStaticArgs& a) {
  transmission::Scene scene = transmission::ReadScene(a.scene);
  if (scene.kind != transmission::SceneKind::kStage)
    throw std::invalid_argument(a.scene + ": a gear-pair scene; quasistatic needs a stage");
  if (a.sun == "fixed") scene.supports.sun = transmission::SunSupport::kFixed;
  if (a.sun == "floating") scene.supports.sun = transmission::SunSupport::kFloating;
  const geometry::Stage stage(scene.stage);
  const int n = stage.planets();

  std::vector<double> angles;
  if (!a.angles_deg.empty()) {
    for (double d : a.angles_deg) angles.push_back(geometry::Rad(d));
  } else {
    // One mesh cycle; one planet revolution relative to the carrier (what a planet's run-out
    // sees: 2π z_p/z_r of carrier angle with the ring fixed); one carrier revolution.
    const bool cycle = a.range == "cycle";
    const double span = cycle                 ? stage.mesh_cycle()
                        : a.range == "planet" ? 2.0 * std::numbers::pi * stage.planet(0).teeth() /
                                                    stage.ring().teeth()
                                              : 2.0 * std::numbers::pi;
    const int count = a.positions > 0 ? a.positions : (cycle ? 36 : 360);
    angles = transmission::SweepAngles(geometry::Rad(a.start_deg), span, count);
  }

  transmission::FeComplianceOptions fe;
  if (!a.no_cache)
    fe.cache_directory = a.cache.empty() ? transmission::DefaultCacheDirectory() : a.cache;
  const auto t0 = std::chrono::steady_clock::now();
  const transmission::FeStageCompliance compliance(scene, stage, fe);
  const double table_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  transmission::StageSetup setup = transmission::SetupFromScene(scene);
  setup.local_terms = !a.no_local;
  const transmission::StageModel model(stage, compliance, setup);
  transmission::QuasiStaticOptions opt;
  opt.backend = solvers::BackendFromName(a.backend);
  opt.threads = a.threads;
  opt.warm_start = !a.cold;

  const char* sun_name = setup.sun == transmission::SunSupport::kFixed      ? "fixed"
                         : setup.sun == transmission::SunSupport::kFloating ? "floating"
                                                                                : "elastic";
  std::printf("%s: %d planets, sun %s, input torque %.1f N m, back end %s\n", scene.name.c_str(), n,
              sun_name, scene.loads.sun_torque, a.backend.c_str());
  for (const std::string& m : compliance.tables().messages()) std::printf("  %s\n", m.c_str());
  const std::string threads =
      a.threads == 0 ? std::string("one thread per core") : fmt::format("{} thread(s)", a.threads);
  std::printf("  %zu positions from %.4f deg (%.2f s for the tables), %s, %s\n", angles.size(),
              geometry::Deg(angles.front()), table_seconds,
              a.cold ? "every position cold" : "each warm-started from its neighbour",
              threads.c_str());

  std::filesystem::create_directories(a.out);
  if (!a.dump.empty()) std::filesystem::create_directories(a.dump);
  const std::string base = a.out + "/quasistatic";
  std::ofstream pos(base + "_positions.csv"), pairs(base + "_pairs.csv");
  if (!pos || !pairs) throw std::runtime_error(a.out + ": cannot write the result files");
  const json provenance = Provenance(a.backend, &scene);
  pos << ProvenanceCsvLine(provenance);
  pairs << ProvenanceCsvLine(provenance);
  pos << "carrier_deg,converged";
  for (int i = 1; i <= n; ++i) pos << ",LSR_" << i;
  for (int i = 1; i <= n; ++i) pos << ",L_" << i;
  pos << ",K_gamma,transmission_error_urad,sun_x_um,sun_y_um,geometric_iterations,"
         "contact_iterations,warm_started,residual,status,active_contacts,contacts,solve_ms,"
         "message\n";
  pairs << "carrier_deg,mesh,kind,flank,teeth,force_N\n";

  const bool tty = !a.quiet && isatty(fileno(stderr));
  int failed = 0;
  std::vector<std::string> failures;
  const auto t1 = std::chrono::steady_clock::now();
  const auto results = transmission::Sweep(
      model, scene.loads, angles, opt, [&](const transmission::PositionResult& r, int k) {
        const double deg = geometry::Deg(r.carrier_angle);
        if (!r.converged) {
          ++failed;
          failures.push_back(fmt::format("{:.4f} deg: {}", deg, r.message));
          if (!tty)
            std::fprintf(stderr, "  position %.4f deg FAILED: %s\n", deg, r.message.c_str());
        }
        std::string msg = r.message;
        for (char& c : msg)
          if (c == ',' || c == '\n') c = ';';
        pos << fmt::format("{:.6f},{}", deg, r.converged ? 1 : 0);
        const auto l = transmission::LoadSharingFactors(r);
        for (double v : r.load_sharing) pos << "," << Num(r.converged ? v : NAN);
        for (double v : l) pos << "," << Num(r.converged ? v : NAN);
        pos << "," << Num(r.converged ? transmission::MeshLoadFactor(r) : NAN) << ","
            << Num(r.converged ? r.transmission_error * 1e6 : NAN) << ","
            << Num(r.converged ? r.sun_displacement.x() * 1e6 : NAN) << ","
            << Num(r.converged ? r.sun_displacement.y() * 1e6 : NAN) << ","
            << r.geometric_iterations << "," << r.contact_iterations << ","
            << (r.warm_started ? 1 : 0) << "," << Num(r.report.residual.total) << ","
            << solvers::StatusName(r.report.status) << "," << r.report.active_contacts << ","
            << r.problem.contacts.size() << "," << Num(r.report.total_seconds * 1e3, "{:.4g}")
            << "," << msg << "\n";
        pos.flush();
        for (std::size_t j = 0; j < r.problem.contacts.size() && r.converged; ++j) {
          const double f = r.solution.force(static_cast<Eigen::Index>(j));
          if (!(f > 0)) continue;
          const auto& c = r.problem.contacts[j];
          const std::string mesh = c.mesh == geometry::MeshKind::kSunPlanet
                                       ? fmt::format("sun-planet{}", c.planet + 1)
                                       : fmt::format("planet{}-ring", c.planet + 1);
          pairs << fmt::format("{:.6f},{},{},{},{}/{},{}\n", deg, mesh,
                               geometry::KindName(c.contact.kind), c.loaded ? "drive" : "coast",
                               c.contact.tooth_a, c.contact.tooth_b, Num(f));
        }
        pairs.flush();
        if (!a.dump.empty() && r.problem.data.compliance.size() > 0) {
          solvers::ContactProblemFile file;
          file.data = r.problem.data;
          file.data.name =
              fmt::format("{}_{}_{}_{:03d}", std::filesystem::path(a.scene).stem().string(),
                          sun_name, a.no_local ? "linear" : "local", k);
          file.category = "stage";
          for (const auto& item : provenance.items())
            if (item.value().is_string())
              file.provenance[item.key()] = item.value().get<std::string>();
          file.description =
              fmt::format("{} at carrier {:.4f} deg, sun {}, back end {}: {}", scene.name, deg,
                          sun_name, a.backend, r.converged ? "converged" : r.message);
          solvers::WriteContactProblemFile(file, a.dump + "/" + file.data.name + ".json");
        }
        if (tty)
          Progress(k + 1, static_cast<int>(angles.size()), failed,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(),
                   "positions");
      });
  const double sweep_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();

  std::vector<std::string> warnings = scene.warnings;
  for (const std::string& w : transmission::QuasiStaticWarnings(stage, results))
    warnings.push_back(w);

  // Summary over the converged positions (none converged: no statistics, "-" in the report).
  const transmission::SweepSummary summary = transmission::SummariseSweep(results, n);
  const int good = summary.converged;
  std::printf("\n  planet   LSR mean     LSR min      LSR max      (ideal 1/n = %.6f)\n", 1.0 / n);
  json planets = json::array();
  for (int i = 0; i < n; ++i) {
    const char* f = "{:<12.6f}";
    std::printf("  %-8d %s %s %s\n", i + 1, Finite(summary.lsr_mean[i], f, "-           ").c_str(),
                Finite(summary.lsr_min[i], f, "-           ").c_str(),
                Finite(summary.lsr_max[i], f, "-").c_str());
    json p = {{"planet", i + 1}};
    // No converged position: null statistics (JSON has no NaN), never a made-up number.
    p["lsr_mean"] = good ? json(summary.lsr_mean[i]) : json(nullptr);
    p["lsr_min"] = good ? json(summary.lsr_min[i]) : json(nullptr);
    p["lsr_max"] = good ? json(summary.lsr_max[i]) : json(nullptr);
    planets.push_back(p);
  }
  if (good > 0) {
    std::printf("  K_gamma (max L_i)            %.6f\n", summary.k_gamma);
    std::printf("  transmission error           %.3f .. %.3f urad (peak to peak %.3f urad)\n",
                summary.transmission_error_min * 1e6, summary.transmission_error_max * 1e6,
                summary.TransmissionErrorPeakToPeak() * 1e6);
    std::printf("  sun displacement, largest    %.3f um\n", summary.sun_displacement_max * 1e6);
  } else {
    std::printf("  K_gamma, transmission error, sun displacement: - (no position converged)\n");
  }
  std::printf("  positions converged          %d of %zu, %.3f s (%.3f ms per position)\n", good,
              angles.size(), sweep_seconds,
              1e3 * sweep_seconds / static_cast<double>(angles.size()));
  for (const std::string& f : failures) std::printf("  FAILED %s\n", f.c_str());
  PrintWarnings(warnings);

  json j;
  j["provenance"] = provenance;
  j["warnings"] = warnings;
  j["scene"] = scene.name;
  j["sun_support"] = sun_name;
  j["sun_torque_Nm"] = scene.loads.sun_torque;
  j["backend"] = a.backend;
  j["local_terms"] = !a.no_local;
  j["warm_start"] = !a.cold;
  j["threads"] = a.threads;  // 0: one per core
  j["positions"] = angles.size();
  j["converged_positions"] = good;
  j["failures"] = failures;
  j["planets"] = planets;
  j["K_gamma_max"] = good ? json(summary.k_gamma) : json(nullptr);
  j["transmission_error_min_urad"] =
      good ? json(summary.transmission_error_min * 1e6) : json(nullptr);
  j["transmission_error_max_urad"] =
      good ? json(summary.transmission_error_max * 1e6) : json(nullptr);
  j["sun_displacement_max_um"] = good ? json(summary.sun_displacement_max * 1e6) : json(nullptr);
  j["sweep_seconds"] = sweep_seconds;
  j["table_seconds"] = table_seconds;
  WriteTextFile(base + "_summary.json", j.dump(2) + "\n");

  LinePlot lsr{scene.name + ": load-sharing ratio (sun " + sun_name + ")",
               "carrier angle [deg]",
               "LSR_i [-]",
               {},
               false,
               {1.0 / n}};
  LinePlot te{scene.name + ": loaded static transmission error at the sun",
              "carrier angle [deg]",
              "sun rotation from kinematic [urad]",
              {},
              false,
              {}};
  LinePlot path{scene.name + ": sun centre path", "x [um]", "y [um]", {}, true, {}};
  PlotSeries te_s{"TE", {}, {}}, path_s{"sun centre", {}, {}};
  for (int i = 0; i < n; ++i) lsr.series.push_back({fmt::format("planet {}", i + 1), {}, {}});
  for (const auto& r : results) {
    if (!r.converged) continue;
    const double deg = geometry::Deg(r.carrier_angle);
    for (int i = 0; i < n; ++i) {
      lsr.series[i].x.push_back(deg);
      lsr.series[i].y.push_back(r.load_sharing[i]);
    }
    te_s.x.push_back(deg);
    te_s.y.push_back(r.transmission_error * 1e6);
    path_s.x.push_back(r.sun_displacement.x() * 1e6);
    path_s.y.push_back(r.sun_displacement.y() * 1e6);
  }
  te.series.push_back(te_s);
  path.series.push_back(path_s);
  WriteTextFile(base + "_lsr.svg", RenderSvg(lsr));
  WriteTextFile(base + "_te.svg", RenderSvg(te));
  WriteTextFile(base + "_sun_path.svg", RenderSvg(path));
  std::printf(
      "\nwrote %s_positions.csv, _pairs.csv, _summary.json, _lsr.svg, _te.svg, _sun_path.svg\n",
      base.c_str());
  if (!a.dump.empty()) std::printf("wrote the contact problems to %s\n", a.dump.c_str());
  if (failed > 0)
    throw ComputationFailed(
        fmt::format("{} of {} positions failed (listed above)", failed, angles.size()));
}

}  // namespace

void RegisterQuasiStaticCommands(CLI::App& app) {
  static QuasiStaticArgs a;
  auto* cmd = app.add_subcommand(
      "quasistatic", "Quasi-static load sharing of a stage over a sweep of carrier positions");
  cmd->add_option("scene", a.scene, "Scene file (TOML) of a stage")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--positions", a.positions,
                  "Positions of the sweep (default 36 over a mesh cycle, 360 otherwise)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--range", a.range,
                  "Sweep one mesh cycle, one planet revolution relative to the carrier (the "
                  "period of a planet's run-out), or one carrier revolution")
      ->check(CLI::IsMember({"cycle", "planet", "revolution"}));
  cmd->add_option("--start-deg", a.start_deg, "Carrier angle of the first position [deg]");
  cmd->add_option("--angles-deg", a.angles_deg, "A given list of carrier angles [deg]");
  cmd->add_option("--sun", a.sun, "Override the scene's sun support")
      ->check(CLI::IsMember({"fixed", "floating"}));
  cmd->add_option("--threads", a.threads,
                  "Worker threads: the positions in contiguous chunks, one per thread (0: one "
                  "per core)")
      ->check(CLI::Range(0, 4096));
  cmd->add_flag("--cold", a.cold,
                "Start every position from its kinematic poses and zero forces (no warm start "
                "from the neighbour)");
  cmd->add_option("--backend", a.backend, "Contact back end (newton, ipopt, nlopt-slsqp, ...)");
  cmd->add_option("--out", a.out, "Output folder (CSV, JSON, SVG)");
  cmd->add_option("--dump-problems", a.dump, "Also write every position's contact problem here");
  cmd->add_option("--cache", a.cache, "Influence-table cache folder (default: ~/.cache/epicycle)");
  cmd->add_flag("--no-cache", a.no_cache, "Build the influence tables in memory only");
  cmd->add_flag("--no-local", a.no_local, "Structural compliance only (no local contact term)");
  cmd->add_flag("--quiet", a.quiet, "No progress bar");
  cmd->callback([] { RunQuasiStatic(a); });
}

}  // namespace epicycle::app
