// Work-precision study of the contact back ends (issue 3, "must show" 4): every available back end
// over its tolerance settings on two stage-sized problems (the smallest and the largest gear-like
// problem with local terms of verification/data/contact/), each answer compared
// with a tight active-set Newton reference (tolerance 1e-12). Writes
//   docs/figures/contact_work_precision.csv   one row per (problem, back end, tolerance)
//   docs/figures/contact_work_precision.svg   error against CPU time per solve, log-log
// (or into the directory given as the first argument).
//
//   build-backends/benchmarks/work_precision [output-dir]
//
// The tolerance is ContactOptions::tolerance, the driver's residual tolerance, which each back end
// maps onto its own stopping rule (Newton: the residual itself; Ipopt: tol and friends at a tenth;
// NLopt: xtol_rel and the equality tolerance). Time is CPU time per solve (the machine may be
// shared), the mean over enough repetitions to fill ≥ 0.2 s.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_collection.hpp"
#include "epicycle/config.h"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "log_log_svg.hpp"

namespace {

using epicycle::solvers::Backend;
using epicycle::solvers::BackendName;
using epicycle::solvers::ContactOptions;
using epicycle::solvers::ContactProblem;
using epicycle::solvers::ContactReport;
using epicycle::solvers::ContactSolution;
using epicycle::solvers::ContactStatus;
using epicycle::solvers::MakeContactSolver;

constexpr double kReferenceTolerance = 1e-12;
constexpr double kMinSeconds = 0.2;
constexpr double kErrorFloor = 1e-16;  // plotted in place of an exact zero

struct Point {
  std::string problem;
  Backend backend;
  double tolerance = 0;
  ContactStatus status = ContactStatus::kNumericalFailure;
  double residual = 0, error_force = 0, error_multiplier = 0, seconds = 0;
  int iterations = 0, repetitions = 0;
  double error() const { return std::max(error_force, error_multiplier); }
};

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

Point Measure(const ContactProblem& problem, const std::string& name, Backend backend,
              double tolerance, const ContactSolution& reference) {
  auto solver = MakeContactSolver(backend);
  ContactOptions options;
  options.tolerance = tolerance;
  ContactSolution solution;
  ContactReport report;
  int repetitions = 0;
  const double start = CpuSeconds();
  double elapsed = 0;
  do {
    report = solver->Solve(problem, options, &solution);
    ++repetitions;
    elapsed = CpuSeconds() - start;
  } while (elapsed < kMinSeconds && repetitions < 2000);
  Point p;
  p.problem = name;
  p.backend = backend;
  p.tolerance = tolerance;
  p.status = report.status;
  p.residual = report.residual.total;
  const auto diff = epicycle::solvers::CompareSolutions(problem, solution, reference);
  p.error_force = diff.force;
  p.error_multiplier = diff.multiplier;
  p.iterations = report.iterations;
  p.repetitions = repetitions;
  p.seconds = elapsed / repetitions;
  return p;
}

const char* Colour(Backend b) {
  switch (b) {
    case Backend::kActiveSetNewton:
      return "#1b9e77";
    case Backend::kIpopt:
      return "#d95f02";
    case Backend::kNloptSlsqp:
      return "#7570b3";
    case Backend::kNloptLbfgs:
      return "#e7298a";
    case Backend::kNloptAuglag:
      return "#66a61e";
  }
  return "#000000";
}

// The figure: one log-log panel per problem (bench::LogLogSvg), one series per back end from
// loose to tight tolerance, hollow markers where the back end did not converge.
std::string Svg(const std::vector<Point>& points, const std::vector<std::string>& problems) {
  std::vector<epicycle::bench::LogPanel> panels;
  for (const std::string& problem : problems) {
    epicycle::bench::LogPanel panel{
        problem,    "CPU time per solve [s]", "error vs reference (max rel. F, &#955;)", {}, {},
        kErrorFloor};
    std::map<Backend, std::vector<const Point*>> series;
    for (const Point& p : points)
      if (p.problem == problem) series[p.backend].push_back(&p);
    for (auto& [backend, list] : series) {
      std::sort(list.begin(), list.end(),
                [](const Point* a, const Point* b) { return a->tolerance > b->tolerance; });
      epicycle::bench::LogSeries s{BackendName(backend), Colour(backend), {}};
      for (const Point* p : list) {
        std::ostringstream tip;
        tip << BackendName(backend) << " tol " << p->tolerance << ": "
            << epicycle::solvers::StatusName(p->status);
        s.points.push_back(
            {p->seconds, p->error(), p->status == ContactStatus::kConverged, "", tip.str()});
      }
      panel.series.push_back(std::move(s));
    }
    panels.push_back(std::move(panel));
  }
  return epicycle::bench::LogLogSvg(panels, {"filled: converged", "hollow: not converged"});
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out_dir =
      argc > 1 ? std::filesystem::path(argv[1])
               : std::filesystem::path(EPICYCLE_SOURCE_DIR) / "docs" / "figures";
  std::filesystem::create_directories(out_dir);

  // The smallest and the largest stage-sized gear-like problem of the collection
  // (verification/data/contact/), or, without the collection, bench_contact's generated pair.
  std::vector<epicycle::solvers::ContactProblemFile> files;
  const std::filesystem::path dir =
      std::filesystem::path(EPICYCLE_SOURCE_DIR) / "verification" / "data" / "contact";
  if (std::filesystem::is_directory(dir)) {
    std::vector<std::filesystem::path> paths;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() == ".json") paths.push_back(entry.path());
    }
    std::sort(paths.begin(), paths.end());
    std::vector<epicycle::solvers::ContactProblemFile> gear;
    for (const auto& path : paths) {
      epicycle::solvers::ContactProblemFile file;
      try {
        file = epicycle::solvers::ReadContactProblemFile(path.string());
      } catch (const std::invalid_argument&) {
        continue;  // not a problem file (e.g. expected_failures.json)
      }
      const auto n = file.data.overlap.size();
      if (file.category == "gear-like" && n >= 30 && n <= 60 && !file.data.local.empty()) {
        gear.push_back(std::move(file));
      }
    }
    if (!gear.empty()) {
      const auto by_size = [](const auto& a, const auto& b) {
        return a.data.overlap.size() < b.data.overlap.size();
      };
      files.push_back(*std::min_element(gear.begin(), gear.end(), by_size));
      files.push_back(*std::max_element(gear.begin(), gear.end(), by_size));
    }
  }
  if (files.empty()) {
    epicycle::solvers::GearLikeSpec three;
    three.planets = 3;
    three.drive_pairs = 3;
    three.coast_pairs = 2;
    three.seed = 11;
    epicycle::solvers::GearLikeSpec four;
    four.planets = 4;
    four.drive_pairs = 4;
    four.coast_pairs = 3;
    four.seed = 12;
    files.push_back(epicycle::solvers::MakeGearLikeProblem(three, "bench-stage-3p-30c"));
    files.push_back(epicycle::solvers::MakeGearLikeProblem(four, "bench-stage-4p-56c"));
  }
  const std::vector<double> tolerances = {1e-3, 1e-4, 1e-5,  1e-6,  1e-7,
                                          1e-8, 1e-9, 1e-10, 1e-11, 1e-12};

  std::vector<Point> points;
  std::vector<std::string> names;
  for (const auto& file : files) {
    const ContactProblem problem(file.data);
    names.push_back(file.data.name);
    // Reference: the active-set Newton at 1e-12, or Ipopt at 1e-12 should Newton not converge.
    ContactSolution reference;
    ContactOptions ref_options;
    ref_options.tolerance = kReferenceTolerance;
    for (Backend backend : {Backend::kActiveSetNewton, Backend::kIpopt}) {
      const ContactReport ref = MakeContactSolver(backend)->Solve(problem, ref_options, &reference);
      std::printf("%s: N = %d, m = %d, reference %s: %s (residual %.2e)\n", file.data.name.c_str(),
                  problem.num_contacts(), problem.num_equalities(), BackendName(backend).c_str(),
                  epicycle::solvers::StatusName(ref.status).c_str(), ref.residual.total);
      if (ref.status == ContactStatus::kConverged) break;
    }
    for (Backend backend : epicycle::solvers::AvailableBackends()) {
      if (backend == Backend::kNloptLbfgs && problem.num_equalities() > 0) continue;
      for (double tol : tolerances) {
        const Point p = Measure(problem, file.data.name, backend, tol, reference);
        std::printf("  %-13s tol %7.0e  %-20s residual %9.2e  error %9.2e  %9.3e s  (%d it)\n",
                    BackendName(backend).c_str(), tol,
                    epicycle::solvers::StatusName(p.status).c_str(), p.residual, p.error(),
                    p.seconds, p.iterations);
        points.push_back(p);
      }
    }
  }

  std::ofstream csv(out_dir / "contact_work_precision.csv");
  csv << "problem,backend,tolerance,status,residual,error_force,error_multiplier,iterations,"
         "cpu_seconds_per_solve,repetitions\n";
  for (const Point& p : points) {
    char line[512];
    std::snprintf(line, sizeof(line), "%s,%s,%.0e,%s,%.3e,%.3e,%.3e,%d,%.4e,%d\n",
                  p.problem.c_str(), BackendName(p.backend).c_str(), p.tolerance,
                  epicycle::solvers::StatusName(p.status).c_str(), p.residual, p.error_force,
                  p.error_multiplier, p.iterations, p.seconds, p.repetitions);
    csv << line;
  }
  std::ofstream(out_dir / "contact_work_precision.svg") << Svg(points, names);
  std::printf("wrote %s and %s\n", (out_dir / "contact_work_precision.csv").c_str(),
              (out_dir / "contact_work_precision.svg").c_str());
  return 0;
}
