// Error against run time of the dynamic model (issue 10, "Error against run time" 1 and 2), on
// the paper's stage with planet 1's 20 µm run-out (scenes/paper_stage_runout.toml), fixed sun,
// the scene's 1500 rpm, from the quasi-static solution at carrier angle 0, 20 outputs per mesh
// cycle. Two studies, one command each:
//
//   dynamic_work_precision integrators [--out DIR] [--cycles N] [--start-cycle K]
//     CVODE BDF with the analytic Jacobian, with CVODE's finite-difference Jacobian, and ARKODE's
//     explicit Dormand–Prince 5(4), each over relative tolerances 1e-3 … 1e-8 in half decades
//     (absolute tolerances scaled with rtol, so that rtol 1e-6 is the default), and, where the
//     studied BDF runs' settings differ from CVODE's own (--nonlinear-convergence, --max-order),
//     the analytic-Jacobian BDF runs again with CVODE's (convergence coefficient 0.1, largest
//     order 5) as a fourth series, against a CVODE BDF
//     reference at rtol 1e-10 with CVODE's settings; the reference's own error is estimated by
//     the same run at 1e-9 and by ARKODE at 1e-10 (an independent method).
//     Default window: 24 mesh cycles, one planet revolution relative to the carrier (75 ms), the
//     period of the run-out's effect: LSR_1's whole swing, planet 1 losing and regaining contact.
//     Writes DIR/dynamic_wp_integrators.csv and .svg and the reference's traces
//     DIR/dynamic_wp_reference_trace.csv (default DIR: docs/figures).
//
//   dynamic_work_precision backends [--out DIR] [--cycles N] [--start-cycle K] [--rtol R]
//                                   [--time-limit S]
//     The same run (CVODE BDF, analytic Jacobian) with the contact back ends newton, ipopt and
//     nlopt-lbfgs over ContactOptions::tolerance 1e-4 … 1e-12, against a tight reference (CVODE
//     BDF at rtol 1e-10, Newton at 1e-12) and against the Newton run at the same rtol with
//     contact tolerance 1e-12, on two windows of 2 mesh cycles (Ipopt costs ~3 ms per solve):
//       cycles 0–2, all planets loaded, at rtol 1e-6 (the production default) and 1e-8 (where
//         the integrator's own error no longer hides the contact solver's);
//       cycles 17–19, at rtol 1e-6: planet 1 loses contact once per mesh cycle (LSR_1 = 0 at
//         cycles 17.6, 18.45, 18.55 in the reference trace), its contact set empties and refills:
//         the hardest event for a warm-started solve.
//     --start-cycle K runs one window from cycle K at rtol 1e-6 and 1e-8, --rtol R runs every
//     window at R only. A run that keeps failing is stopped after S seconds of wall time
//     (default: 400 times the Newton run's, at least 60 s) and counted as failed.
//     Writes DIR/dynamic_wp_backends.csv and .svg (LSR panels; TE in the CSV).
//
//   `integrators` takes --max-order N: CVODE BDF's largest order for the studied BDF runs (the
//   reference keeps 5); its files are then named with "_max_order_N" after the stem. And
//   --nonlinear-convergence C: CVODE's Newton convergence factor for those runs (reference 0.1),
//   files named with "_nonlinear_convergence_C".
//   Both take --rate-scale X [1/s]: SimulationOptions::rate_scale (the rates' absolute tolerance
//   is the position tolerance times X) for every run instead of the library's default; their
//   files are then named with "_rate_scale_X" after the stem (X as given).
//
// Error measures (both against the reference's samples at the same output times):
//   LSR: max over the samples and the planets of |LSR_i − LSR_i,ref| [-] (LSR is a fraction of
//        the input torque, so this is an absolute error of the share);
//   TE:  max over the samples of |TE − TE_ref| divided by the reference's range max TE − min TE.
// A run that stops early is measured over the samples it reached, drawn hollow and counted.
//
// Time: the wall time of Simulate (steady clock) and the process CPU time (std::clock) of the
// same call; the machine is shared, so CPU time is the figure to compare (both are in the CSV).
// One run per point (a dynamic run is long enough not to need repetitions). Every integrator
// count is recorded: steps, right-hand sides, those spent on finite-difference Jacobians,
// analytic Jacobians, failed contact solves, error-test and nonlinear-solver failures, restarts
// of the explicit method. The FE tables come from the cache (EPICYCLE_CACHE_DIR or the default).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "epicycle/config.h"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/io/units.hpp"
#include "log_log_svg.hpp"

namespace {

using namespace epicycle;
using bench::LogPanel;
using bench::LogPoint;
using bench::LogSeries;

constexpr int kOutputsPerCycle = 20;
constexpr double kReferenceRtol = 1e-10;
constexpr double kReferenceContactTolerance = 1e-12;
// CVODE's own Newton convergence coefficient (CVodeSetNonlinConvCoef's default): the reference's,
// and the comparison series' of the integrators study.
constexpr double kCvodeNonlinearConvergence = 0.1;

// The sampled traces a run is judged by.
struct Trace {
  std::vector<double> time;
  std::vector<std::vector<double>> lsr;  // [sample][planet]
  std::vector<double> te;                // [rad]
};

struct Run {
  std::string series;  // integrator (and Jacobian) or back end
  double start_cycle = 0, rtol = 0, contact_tolerance = 0;
  bool completed = false;
  std::string message;
  int samples = 0, outputs = 0;
  double wall = 0, cpu = 0;
  dynamics::SimulationStats stats;
  double lsr_error = 0, te_error = 0;            // against the tight reference
  double lsr_vs_newton = -1, te_vs_newton = -1;  // backends: against Newton at the same rtol
  Trace trace;
};

// Absolute tolerances scaled with rtol; at rtol 1e-6 they are SimulationOptions' defaults
// (1e-10 m, 1e-9 rad, 1e-6 J), so that tightening rtol tightens the whole error test.
// --rate-scale: SimulationOptions::rate_scale for every run (0: the library's default), and the
// value as given, which names the output files (the default run's files are not written over).
double rate_scale_option = 0;
std::string rate_scale_text;
// --max-order: CVODE BDF's largest order (SimulationOptions::max_order) for the studied BDF runs;
// the reference and its checks keep the default 5. 0: the default.
int max_order_option = 0;
// --nonlinear-convergence: SimulationOptions::nonlinear_convergence for the studied BDF runs (the
// reference keeps CVODE's 0.1), and the value as given, which names the files. Empty: the default.
double nonlinear_option = 0;
std::string nonlinear_text;

// The output file `stem` + `extension`, with "_rate_scale_X" after the stem under --rate-scale X
// and "_max_order_N" under --max-order N.
std::string OutputName(const std::string& stem, const std::string& extension) {
  return stem + (rate_scale_text.empty() ? "" : "_rate_scale_" + rate_scale_text) +
         (max_order_option > 0 ? "_max_order_" + std::to_string(max_order_option) : "") +
         (nonlinear_text.empty() ? "" : "_nonlinear_convergence_" + nonlinear_text) + extension;
}

dynamics::SimulationOptions Options(dynamics::Integrator integrator, double rtol) {
  dynamics::SimulationOptions o;
  if (rate_scale_option > 0) o.rate_scale = rate_scale_option;
  o.integrator = integrator;
  o.rtol = rtol;
  o.atol_length = 1e-4 * rtol;
  o.atol_angle = 1e-3 * rtol;
  o.atol_energy = rtol;
  return o;
}

// The reference and its checks run with CVODE's own Newton settings (convergence coefficient 0.1,
// largest order 5), whatever the library's defaults, so that a study of those settings never
// moves its reference.
dynamics::SimulationOptions ReferenceOptions(dynamics::Integrator integrator, double rtol) {
  dynamics::SimulationOptions o = Options(integrator, rtol);
  o.nonlinear_convergence = kCvodeNonlinearConvergence;
  o.max_order = 5;
  return o;
}

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

Run Simulate(const dynamics::DynamicModel& model, const dynamics::SimulationOptions& o,
             const Eigen::VectorXd& d0, const std::vector<double>& times, std::string series) {
  Run r;
  r.series = std::move(series);
  r.rtol = o.rtol;
  r.contact_tolerance = o.contact.tolerance;
  r.outputs = static_cast<int>(times.size());
  const double cpu0 = CpuSeconds();
  const dynamics::SimulationResult result =
      dynamics::Simulate(model, o, d0, Eigen::VectorXd::Zero(model.size()), times);
  r.cpu = CpuSeconds() - cpu0;
  r.wall = result.stats.wall_seconds;
  r.stats = result.stats;
  r.completed = result.completed();
  r.message = result.message;
  r.samples = static_cast<int>(result.samples.size());
  for (const dynamics::DynamicSample& s : result.samples) {
    r.trace.time.push_back(s.time);
    r.trace.lsr.push_back(s.load_sharing);
    r.trace.te.push_back(s.transmission_error);
  }
  return r;
}

// {max |ΔLSR|, max |ΔTE| / range(TE_ref)} over the samples both traces have.
std::pair<double, double> Difference(const Trace& a, const Trace& ref) {
  const std::size_t n = std::min(a.time.size(), ref.time.size());
  double lsr = 0, te = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (a.time[k] != ref.time[k]) throw std::logic_error("traces sampled at different times");
    for (std::size_t i = 0; i < ref.lsr[k].size(); ++i)
      lsr = std::max(lsr, std::abs(a.lsr[k][i] - ref.lsr[k][i]));
    te = std::max(te, std::abs(a.te[k] - ref.te[k]));
  }
  const auto [lo, hi] = std::minmax_element(ref.te.begin(), ref.te.end());
  return {lsr, ref.te.empty() ? 0.0 : te / (*hi - *lo)};
}

void Judge(Run* r, const Trace& ref) {
  std::tie(r->lsr_error, r->te_error) = Difference(r->trace, ref);
}

void Print(const Run& r) {
  std::printf(
      "  %-22s rtol %6.0e ctol %6.0e  %s %4d/%d  LSR err %9.2e  TE err %9.2e  wall %8.2f s  cpu "
      "%8.2f s  steps %7ld  rhs %8ld  fd-rhs %6ld  jac %6ld  failed %5ld  etf %5ld  nlf %5ld  "
      "restarts %ld\n",
      r.series.c_str(), r.rtol, r.contact_tolerance, r.completed ? "ok    " : "FAILED", r.samples,
      r.outputs, r.lsr_error, r.te_error, r.wall, r.cpu, r.stats.steps, r.stats.rhs_evaluations,
      r.stats.fd_rhs_evaluations, r.stats.jacobian_evaluations, r.stats.failed_solves,
      r.stats.error_test_failures, r.stats.nonlinear_failures, r.stats.restarts);
  if (!r.completed) std::printf("      stopped: %s\n", r.message.c_str());
  std::fflush(stdout);
}

// CSV: one row per run, the message last (quoted).
void WriteCsv(const std::filesystem::path& path, const std::vector<Run>& runs,
              const std::string& header_note) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error(path.string() + ": cannot write");
  csv << "# " << header_note << "\n";
  csv << "series,start_cycle,rtol,contact_tolerance,completed,samples,outputs,lsr_error,te_error_"
         "rel_range,"
         "lsr_vs_newton,te_vs_newton_rel_range,wall_s,cpu_s,steps,rhs_evaluations,"
         "fd_rhs_evaluations,jacobians,failed_contact_solves,error_test_failures,"
         "nonlinear_failures,restarts,rhs_cpu_s,jacobian_s,message\n";
  for (const Run& r : runs) {
    std::string message = r.message;
    std::replace(message.begin(), message.end(), '"', '\'');
    char line[1024];
    std::snprintf(
        line, sizeof(line),
        "%s,%g,%.0e,%.0e,%d,%d,%d,%.4e,%.4e,%.4e,%.4e,%.4f,%.4f,%ld,%ld,%ld,%ld,%ld,%ld,%ld,"
        "%ld,%.4f,%.4f,",
        r.series.c_str(), r.start_cycle, r.rtol, r.contact_tolerance, r.completed ? 1 : 0,
        r.samples, r.outputs, r.lsr_error, r.te_error, r.lsr_vs_newton, r.te_vs_newton, r.wall,
        r.cpu, r.stats.steps, r.stats.rhs_evaluations, r.stats.fd_rhs_evaluations,
        r.stats.jacobian_evaluations, r.stats.failed_solves, r.stats.error_test_failures,
        r.stats.nonlinear_failures, r.stats.restarts, r.stats.rhs_seconds,
        r.stats.jacobian_seconds);
    csv << line << '"' << message << "\"\n";
  }
}

// The reference's traces (for the reader: where the window's events are).
void WriteTrace(const std::filesystem::path& path, const Trace& t) {
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error(path.string() + ": cannot write");
  csv << "time_s";
  for (std::size_t i = 0; i < (t.lsr.empty() ? 0 : t.lsr[0].size()); ++i) csv << ",LSR_" << i + 1;
  csv << ",transmission_error_urad\n";
  char v[32];
  for (std::size_t k = 0; k < t.time.size(); ++k) {
    std::snprintf(v, sizeof(v), "%.9g", t.time[k]);
    csv << v;
    for (double x : t.lsr[k]) {
      std::snprintf(v, sizeof(v), ",%.10g", x);
      csv << v;
    }
    std::snprintf(v, sizeof(v), ",%.10g\n", t.te[k] * 1e6);
    csv << v;
  }
}

std::string Exponent(double v) {
  char s[16];
  std::snprintf(s, sizeof(s), "%.0e", v);
  return s;
}

// Two panels (LSR error, TE error) against CPU time, titled with `prefix`; one series per
// `order` name, its points in the order given, each labelled with its tolerance.
std::vector<LogPanel> Panels(const std::vector<Run>& runs, const std::vector<std::string>& order,
                             const std::vector<std::string>& colours,
                             double (*tolerance)(const Run&), const std::string& what,
                             const std::vector<std::pair<double, std::string>>& lsr_lines,
                             const std::vector<std::pair<double, std::string>>& te_lines,
                             const std::string& prefix) {
  LogPanel lsr{prefix + "LSR: max |LSR − LSR_ref|",
               "CPU time of the run [s]",
               "error of LSR [-]",
               {},
               lsr_lines,
               1e-12};
  LogPanel te{prefix + "TE: max |TE − TE_ref| / range",
              "CPU time of the run [s]",
              "relative error of TE [-]",
              {},
              te_lines,
              1e-12};
  for (std::size_t k = 0; k < order.size(); ++k) {
    LogSeries a{order[k], colours[k % colours.size()], {}}, b = a;
    for (const Run& r : runs) {
      // A run that stopped before its first output has no error to draw (Unplotted lists it).
      if (r.series != order[k] || r.samples == 0) continue;
      const std::string tip = r.series + " " + what + " " + Exponent(tolerance(r)) + ": " +
                              (r.completed ? "completed" : "FAILED: " + r.message);
      // Labels on the decades only (half decades would crowd the figure).
      const double decade = std::log10(tolerance(r));
      const std::string label =
          (std::abs(decade - std::round(decade)) < 1e-9 ? Exponent(tolerance(r)) : "") +
          (r.stats.failed_solves > 0 ? " (" + std::to_string(r.stats.failed_solves) + " failed)"
                                     : "");
      a.points.push_back({r.cpu, r.lsr_error, r.completed, label, tip});
      b.points.push_back({r.cpu, r.te_error, r.completed, label, tip});
    }
    if (!a.points.empty()) {
      lsr.series.push_back(a);
      te.series.push_back(b);
    }
  }
  return {lsr, te};
}

// A window of the motion: t = 0 is `start_cycle` mesh cycles into the reference motion (from the
// quasi-static solution there); `rtols` are the integrator tolerances the back ends run at.
struct Window {
  double start_cycle = 0;
  std::vector<double> rtols;
};

// The figure's note for the runs that stopped before their first output (not drawn): one line
// per series with the tolerances, e.g. "not drawn, stopped at once: nlopt-lbfgs 1e-10 1e-12".
std::vector<std::string> Unplotted(const std::vector<Run>& runs, double (*tolerance)(const Run&)) {
  std::vector<std::pair<std::string, std::string>> seen;  // series, tolerances
  for (const Run& r : runs) {
    if (r.samples > 0) continue;
    const std::string t = Exponent(tolerance(r));
    auto it =
        std::find_if(seen.begin(), seen.end(), [&](const auto& e) { return e.first == r.series; });
    if (it == seen.end()) {
      seen.emplace_back(r.series, t);
    } else if (it->second.find(t) == std::string::npos) {
      it->second += " " + t;
    }
  }
  std::vector<std::string> notes;
  for (const auto& [series, tolerances] : seen)
    notes.push_back("not drawn, stopped at once: " + series + " " + tolerances);
  return notes;
}

struct Setup {
  std::filesystem::path out;
  int cycles = 0;
  std::vector<Window> windows;
  /// Back ends: wall time per run [s]; 0: 400 times the Newton run's at the same settings (a
  /// solve of Ipopt costs ~100 Newton solves), at least 60 s; the machine is shared, wall time runs
  /// ~2.5x the CPU time.
  double time_limit = 0;
};

// The stage, the start and the output times of a window of `cycles` mesh cycles.
struct Case : dynamics::StageDynamics {
  Eigen::VectorXd d0;
  std::vector<double> times;
  double cycle_time = 0;
  Case(int cycles, double start_cycle) : StageDynamics(Scene(), Tables()) {
    // The carrier's reference angle after `start_cycle` mesh cycles (it turns one tooth pitch of
    // the ring per mesh cycle, in the direction of its speed).
    model.SetStartAngle(std::copysign(start_cycle * stage.mesh_cycle(), model.carrier_speed()));
    cycle_time = stage.mesh_cycle() / std::abs(model.carrier_speed());
    for (int i = 1; i <= cycles * kOutputsPerCycle; ++i)
      times.push_back(cycle_time * i / kOutputsPerCycle);
    solvers::ContactOptions contact;
    d0 = model.QuasiStaticStart(contact, solvers::Backend::kActiveSetNewton);
    std::printf(
        "paper stage, planet 1 run-out 20 um, fixed sun, %.0f rpm (mesh cycle %.4f ms), from "
        "mesh cycle %.2f, %d mesh cycles = %.3f ms, %zu outputs, %d DOFs\n",
        io::RadPerSecondToRpm(std::abs(model.sun_speed())), cycle_time * 1e3, start_cycle, cycles,
        cycles * cycle_time * 1e3, times.size(), model.size());
  }
  static transmission::Scene Scene() {
    auto s = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_runout.toml");
    s.supports.sun = transmission::SunSupport::kFixed;
    return s;
  }
  static transmission::FeComplianceOptions Tables() {
    transmission::FeComplianceOptions o;
    o.cache_directory = transmission::DefaultCacheDirectory();
    return o;
  }
};

void Integrators(const Setup& setup) {
  const Case c(setup.cycles, setup.windows.front().start_cycle);
  using dynamics::Integrator;
  // The reference and the estimates of its own error.
  Run ref = Simulate(c.model, ReferenceOptions(Integrator::kCvodeBdf, kReferenceRtol), c.d0,
                     c.times, "reference cvode-bdf");
  Print(ref);
  if (!ref.completed) throw std::runtime_error("the reference run failed: " + ref.message);
  WriteTrace(setup.out / OutputName("dynamic_wp_reference_trace", ".csv"), ref.trace);
  Run ref9 = Simulate(c.model, ReferenceOptions(Integrator::kCvodeBdf, 1e-9), c.d0, c.times,
                      "check cvode-bdf");
  Judge(&ref9, ref.trace);
  Print(ref9);
  Run ref_erk = Simulate(c.model, ReferenceOptions(Integrator::kArkodeErk, kReferenceRtol), c.d0,
                         c.times, "check arkode-erk");
  Judge(&ref_erk, ref.trace);
  Print(ref_erk);

  // Half decades: 1e-3, 3e-4, 1e-4, ..., 1e-8.
  std::vector<double> rtols;
  for (int k = 6; k <= 16; ++k)
    rtols.push_back((k % 2 == 0 ? 1.0 : 3.0) * std::pow(10.0, -(k + 1) / 2));
  // The stiffest linearised mode bounds an explicit method's step (|λ h| within its stability
  // region): printed to read ERK's step counts against.
  Eigen::MatrixXd mass, stiffness;
  c.model.Linearise(c.model.CarrierAngle(0), &mass, &stiffness);
  const auto modes = dynamics::SolveModes(mass, stiffness, c.model.ModeLayout());
  std::printf("linearised modes [Hz]:");
  for (const auto& mode : modes) std::printf(" %.0f", mode.frequency);
  std::printf("; 1/omega_max = %.2f us\n",
              1e6 / (2 * std::numbers::pi * (modes.empty() ? 1.0 : modes.back().frequency)));
  // The fourth series: the analytic-Jacobian BDF runs with CVODE's own Newton settings
  // (coefficient 0.1, order 5), the comparison for studied settings (docs/dynamic_cost.md,
  // "Error against run time").
  const std::vector<std::string> names = {"cvode-bdf analytic J", "cvode-bdf FD J", "arkode-erk",
                                          "cvode-bdf analytic J (CVODE's 0.1)"};
  std::vector<Run> runs = {ref, ref9, ref_erk};
  // The fourth series only where the studied BDF runs' settings differ from CVODE's own.
  const dynamics::SimulationOptions studied = Options(Integrator::kCvodeBdf, 1e-6);
  const bool cvode_settings = nonlinear_option == 0 && max_order_option == 0 &&
                              studied.nonlinear_convergence == kCvodeNonlinearConvergence &&
                              studied.max_order == 5;
  for (std::size_t m = 0; m < names.size(); ++m) {
    if (m == 3 && cvode_settings) continue;
    for (double rtol : rtols) {
      auto o = m == 3 ? ReferenceOptions(Integrator::kCvodeBdf, rtol)
                      : Options(m == 2 ? Integrator::kArkodeErk : Integrator::kCvodeBdf, rtol);
      o.analytic_jacobian = m == 0 || m == 3;
      if (m < 2 && max_order_option > 0) o.max_order = max_order_option;
      if (m < 2 && nonlinear_option > 0) o.nonlinear_convergence = nonlinear_option;
      Run r = Simulate(c.model, o, c.d0, c.times, names[m]);
      Judge(&r, ref.trace);
      Print(r);
      runs.push_back(std::move(r));
    }
  }
  char note[256];
  std::snprintf(
      note, sizeof(note),
      "paper stage run-out 20 um fixed sun 1500 rpm; from mesh cycle %.2f; %d mesh cycles; "
      "reference cvode-bdf rtol %.0e (contact tolerance 1e-10); rate scale %g 1/s",
      setup.windows.front().start_cycle, setup.cycles, kReferenceRtol,
      Options(Integrator::kCvodeBdf, kReferenceRtol).rate_scale);
  for (Run& r : runs) r.start_cycle = setup.windows.front().start_cycle;
  WriteCsv(setup.out / OutputName("dynamic_wp_integrators", ".csv"), runs, note);
  const std::vector<std::pair<double, std::string>> lsr_lines = {
      {ref9.lsr_error, "BDF 1e-9 vs reference"}, {ref_erk.lsr_error, "ERK 1e-10 vs reference"}};
  const std::vector<std::pair<double, std::string>> te_lines = {
      {ref9.te_error, "BDF 1e-9 vs reference"}, {ref_erk.te_error, "ERK 1e-10 vs reference"}};
  const auto Notes = [&](const std::vector<Run>& all) {
    std::vector<std::string> n = {"labels: rtol (decades)", "atol scaled with rtol",
                                  "hollow: run failed",
                                  std::to_string(setup.cycles) + " mesh cycles, 1500 rpm"};
    const auto missing = Unplotted(all, [](const Run& r) { return r.rtol; });
    n.insert(n.end(), missing.begin(), missing.end());
    return n;
  };
  const std::string svg =
      bench::LogLogSvg(Panels(
                           runs, names, {"#1b9e77", "#d95f02", "#7570b3", "#999999"},
                           [](const Run& r) { return r.rtol; }, "rtol", lsr_lines, te_lines, ""),
                       Notes(runs));
  std::ofstream(setup.out / OutputName("dynamic_wp_integrators", ".svg")) << svg;
  std::printf("wrote %s and %s\n",
              (setup.out / OutputName("dynamic_wp_integrators", ".csv")).c_str(),
              (setup.out / OutputName("dynamic_wp_integrators", ".svg")).c_str());
}

// One window of the back-end study: the tight reference, then per rtol the Newton run at contact
// tolerance 1e-12 and every (back end, tolerance); the runs go to `runs`, the LSR panels (one per
// rtol) to `panels`.
void BackendWindow(const Setup& setup, const Window& window, std::vector<Run>* runs,
                   std::vector<LogPanel>* panels) {
  const Case c(setup.cycles, window.start_cycle);
  using dynamics::Integrator;
  auto ref_options = Options(Integrator::kCvodeBdf, kReferenceRtol);
  ref_options.contact.tolerance = kReferenceContactTolerance;
  Run ref = Simulate(c.model, ref_options, c.d0, c.times, "reference newton");
  ref.start_cycle = window.start_cycle;
  Print(ref);
  if (!ref.completed) throw std::runtime_error("the reference run failed: " + ref.message);
  runs->push_back(ref);

  const std::vector<double> tolerances = {1e-4, 1e-6, 1e-8, 1e-10, 1e-12};
  const std::vector<solvers::Backend> backends = {
      solvers::Backend::kActiveSetNewton, solvers::Backend::kIpopt, solvers::Backend::kNloptLbfgs};
  std::vector<std::string> names;
  for (solvers::Backend b : backends) names.push_back(solvers::BackendName(b));
  for (double rtol : window.rtols) {
    // Newton with the tightest contact tolerance at this rtol: the trajectory every run at this
    // rtol is also compared with (equal integrator settings), and the integrator's own error.
    auto base_options = Options(Integrator::kCvodeBdf, rtol);
    base_options.contact.tolerance = tolerances.back();
    Run base = Simulate(c.model, base_options, c.d0, c.times, names[0]);
    base.start_cycle = window.start_cycle;
    Judge(&base, ref.trace);
    base.lsr_vs_newton = base.te_vs_newton = 0;
    Print(base);
    std::vector<Run> mine;
    for (solvers::Backend b : backends) {
      for (double tol : tolerances) {
        if (b == solvers::Backend::kActiveSetNewton && tol == tolerances.back()) {
          mine.push_back(base);
          continue;
        }
        auto o = base_options;
        o.backend = b;
        o.contact.tolerance = tol;
        // A back end that keeps failing makes CVODE shrink the step without end: a cap on the
        // steps per output interval (a run takes ~70 per interval at rtol 1e-6, ~300 at 1e-8)
        // and a wall-time budget end such a run as failed.
        o.max_steps = 20000;
        o.time_limit = setup.time_limit > 0 ? setup.time_limit : std::max(60.0, 400 * base.wall);
        Run r = Simulate(c.model, o, c.d0, c.times, solvers::BackendName(b));
        r.start_cycle = window.start_cycle;
        Judge(&r, ref.trace);
        std::tie(r.lsr_vs_newton, r.te_vs_newton) = Difference(r.trace, base.trace);
        Print(r);
        mine.push_back(std::move(r));
      }
    }
    char prefix[96];
    std::snprintf(prefix, sizeof(prefix), "cycles %g-%g, rtol %.0e: ", window.start_cycle,
                  window.start_cycle + setup.cycles, rtol);
    const auto both = Panels(
        mine, names, {"#1b9e77", "#d95f02", "#e7298a"},
        [](const Run& r) { return r.contact_tolerance; }, "contact tolerance",
        {{base.lsr_error, "newton 1e-12 (integrator error)"}},
        {{base.te_error, "newton 1e-12 (integrator error)"}}, prefix);
    panels->push_back(both.front());  // LSR; TE is in the CSV
    runs->insert(runs->end(), mine.begin(), mine.end());
  }
}

void Backends(const Setup& setup) {
  std::vector<Run> runs;
  std::vector<LogPanel> panels;
  for (const Window& w : setup.windows) BackendWindow(setup, w, &runs, &panels);
  char note[256];
  std::snprintf(note, sizeof(note),
                "paper stage run-out 20 um fixed sun 1500 rpm; %d mesh cycles per window; "
                "cvode-bdf analytic J; reference cvode-bdf rtol %.0e newton contact tolerance %.0e",
                setup.cycles, kReferenceRtol, kReferenceContactTolerance);
  WriteCsv(setup.out / OutputName("dynamic_wp_backends", ".csv"), runs, note);
  std::vector<std::string> notes = {"labels: contact tolerance",
                                    "(k failed): failed contact solves",
                                    "hollow: run stopped; its error covers",
                                    "  only the samples it reached",
                                    "cvode-bdf, analytic Jacobian",
                                    "LSR error against the tight reference",
                                    "1500 rpm"};
  const auto missing = Unplotted(runs, [](const Run& r) { return r.contact_tolerance; });
  notes.insert(notes.end(), missing.begin(), missing.end());
  const std::string svg = bench::LogLogSvg(panels, notes);
  std::ofstream(setup.out / OutputName("dynamic_wp_backends", ".svg")) << svg;
  std::printf("wrote %s and %s\n", (setup.out / OutputName("dynamic_wp_backends", ".csv")).c_str(),
              (setup.out / OutputName("dynamic_wp_backends", ".svg")).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage =
      "usage: dynamic_work_precision integrators|backends [--out DIR] [--cycles N] [--start-cycle "
      "K] "
      "[--rtol R] [--time-limit S] [--rate-scale X] [--max-order N] [--nonlinear-convergence "
      "C]\n";
  if (argc < 2) {
    std::fputs(usage, stderr);
    return 2;
  }
  const std::string mode = argv[1];
  Setup setup;
  setup.out = std::filesystem::path(EPICYCLE_SOURCE_DIR) / "docs" / "figures";
  setup.cycles = mode == "integrators" ? 24 : 2;
  if (mode == "integrators") {
    setup.windows = {{0, {}}};
  } else {
    setup.windows = {{0, {1e-6, 1e-8}}, {17, {1e-6}}};
  }
  try {
    for (int k = 2; k < argc; ++k) {
      const std::string key = argv[k];
      if (k + 1 >= argc) throw std::invalid_argument(key + ": needs a value");
      const std::string value = argv[++k];
      if (key == "--out") {
        setup.out = value;
      } else if (key == "--cycles") {
        setup.cycles = std::stoi(value);
        if (setup.cycles < 1) throw std::invalid_argument("--cycles = " + value + ": must be >= 1");
      } else if (key == "--rtol") {
        const double rtol = std::stod(value);
        if (!(rtol > 0 && rtol <= 0.1))
          throw std::invalid_argument("--rtol = " + value + ": must lie in (0, 0.1]");
        for (Window& w : setup.windows) w.rtols = {rtol};
      } else if (key == "--rate-scale") {
        rate_scale_option = std::stod(value);
        rate_scale_text = value;
        if (!(rate_scale_option > 0))
          throw std::invalid_argument("--rate-scale = " + value + ": must be > 0 [1/s]");
      } else if (key == "--max-order") {
        max_order_option = std::stoi(value);
        if (max_order_option < 1 || max_order_option > 5)
          throw std::invalid_argument("--max-order = " + value + ": must lie in 1..5");
      } else if (key == "--nonlinear-convergence") {
        nonlinear_option = std::stod(value);
        nonlinear_text = value;
        if (!(nonlinear_option > 0 && nonlinear_option <= 1))
          throw std::invalid_argument("--nonlinear-convergence = " + value +
                                      ": must lie in (0, 1]");
      } else if (key == "--time-limit") {
        setup.time_limit = std::stod(value);
        if (!(setup.time_limit > 0))
          throw std::invalid_argument("--time-limit = " + value + ": must be > 0");
      } else if (key == "--start-cycle") {
        const double start = std::stod(value);
        if (!(start >= 0))
          throw std::invalid_argument("--start-cycle = " + value + ": must be >= 0");
        setup.windows = {{start, setup.windows.front().rtols.empty()
                                     ? std::vector<double>{}
                                     : std::vector<double>{1e-6, 1e-8}}};
      } else {
        throw std::invalid_argument(key + ": unknown option");
      }
    }
    std::filesystem::create_directories(setup.out);
    if (mode == "integrators") {
      Integrators(setup);
    } else if (mode == "backends") {
      Backends(setup);
    } else {
      throw std::invalid_argument("mode = '" + mode + "': not one of integrators, backends");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dynamic_work_precision: %s\n%s", e.what(), usage);
    return 1;
  }
  return 0;
}
