// The cost of slices of the face width (docs/face_width.md, "Cost"): the paper stage with planet
// 1's pin tilted radially by 20 µm over the face (scenes/paper_stage_pin_tilt.toml), fixed sun,
// at S = 1, 2, 5, 10, 20 slices: one quasi-static position (search, compliance, slices, contact
// solve, geometric iterations) against the plane model (S = 1); bench_dynamics's
// BM_FaceWidthEvaluation times the dynamic evaluation of the same scenes. Counters: the contacts
// of the problem; after the loop, Σ LSR_i = 1 (the torque carried).
//
// The contact back ends at the sliced sizes (docs/solvers.md §12): the contact problem of the
// same position at S = 1, 2, 5, 10, 20, 40 (uncoupled slices and a Pasternak coupling of
// λ = 5 mm), solved (validation included) by the active-set Newton on the dense matrix (the
// problem without its Kronecker terms), by the Newton with them (the structured path), by Ipopt
// and by NLopt's SLSQP and AUGLAG, each judged by the driver's one residual, all from a cold
// start; the two Newton paths and Ipopt also warm, from the answer at the previous position of a
// sweep (0.29 mesh cycles). The table after the run gives the crossover and the Ipopt/Newton
// ratio, cold and warm.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "recording_reporter.hpp"

#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace {

using namespace epicycle;

transmission::FeComplianceOptions Cache() {
  transmission::FeComplianceOptions o;
  o.cache_directory = (std::filesystem::temp_directory_path() / "epicycle-bench-ilt").string();
  return o;
}

// The pin-tilt scene with S slices.
transmission::Scene TiltScene(std::int64_t slices) {
  auto s = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_pin_tilt.toml");
  s.face_width.slices = static_cast<int>(slices);
  return s;
}

void BM_FaceWidthPosition(benchmark::State& state) {
  const transmission::Scene scene = TiltScene(state.range(0));
  const geometry::Stage stage(scene.stage);
  const transmission::FeStageCompliance compliance(scene, stage, Cache());
  const transmission::StageModel model(stage, compliance, transmission::SetupFromScene(scene));
  const double angle = 0.3 * stage.mesh_cycle();
  transmission::PositionResult r;
  for (auto _ : state) {
    r = transmission::SolvePosition(model, angle, scene.loads, {});
    benchmark::DoNotOptimize(r.solution.force.data());
  }
  double sum = 0;
  for (double v : r.load_sharing) sum += v;
  state.counters["lsr_sum_error"] = std::abs(sum - 1);
  state.counters["contacts"] = static_cast<double>(r.problem.contacts.size());
  state.counters["converged"] = r.converged ? 1 : 0;
}
BENCHMARK(BM_FaceWidthPosition)->Arg(1)->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

// One contact problem of the sliced stage and its tight reference.
struct SliceCase {
  std::string name;  // "none/S10"
  int slices = 1;
  solvers::ContactProblemData data;  // with its Kronecker terms
  solvers::ContactSolution reference;
  // The answer at the previous position of a sweep (0.29 mesh cycles, the driver's Newton), the
  // warm start of the "-warm" paths; empty if that position's problem has another size.
  solvers::ContactSolution previous;
};

constexpr double kSolveTolerance = 1e-9;
constexpr double kPasternakLength = 5e-3;  // λ [m], a fifth of the 25 mm face

SliceCase BuildSliceCase(int slices, transmission::FaceCoupling coupling) {
  transmission::Scene scene = TiltScene(slices);
  scene.face_width.coupling = coupling;
  scene.face_width.coupling_length =
      coupling == transmission::FaceCoupling::kPasternak ? kPasternakLength : 0.0;
  const geometry::Stage stage(scene.stage);
  const transmission::FeStageCompliance compliance(scene, stage, Cache());
  const transmission::StageModel model(stage, compliance, transmission::SetupFromScene(scene));
  const transmission::PositionResult r =
      transmission::SolvePosition(model, 0.3 * stage.mesh_cycle(), scene.loads, {});
  SliceCase c;
  c.slices = slices;
  c.name = std::string(coupling == transmission::FaceCoupling::kNone ? "none" : "pasternak") +
           "/S" + std::to_string(slices);
  c.data = r.problem.data;
  const transmission::PositionResult before =
      transmission::SolvePosition(model, 0.29 * stage.mesh_cycle(), scene.loads, {});
  if (before.problem.data.compliance.rows() == c.data.compliance.rows() &&
      before.problem.data.equality_matrix.rows() == c.data.equality_matrix.rows())
    c.previous = before.solution;
  // The reference: the Newton at 1e-12 on the dense matrix (the structure plays no part).
  solvers::ContactProblemData dense = c.data;
  dense.compliance_terms.clear();
  solvers::ContactOptions o;
  o.tolerance = 1e-12;
  solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton)
      ->Solve(solvers::ContactProblem(std::move(dense)), o, &c.reference);
  return c;
}

// path: "newton-dense", "newton-structured", or a back end's name (dense matrix); a "-warm"
// suffix starts every solve from the previous position's answer (a sweep's warm start).
void BM_SliceBackend(benchmark::State& state, const SliceCase* c, std::string path) {
  const bool warm = path.size() > 5 && path.compare(path.size() - 5, 5, "-warm") == 0;
  if (warm) path.resize(path.size() - 5);
  const bool structured = path == "newton-structured";
  const solvers::Backend backend = structured || path == "newton-dense"
                                       ? solvers::Backend::kActiveSetNewton
                                       : solvers::BackendFromName(path);
  solvers::ContactProblemData data = c->data;
  if (!structured) data.compliance_terms.clear();
  solvers::ContactOptions o;
  o.tolerance = kSolveTolerance;
  o.time_limit = 120;
  o.warm_start = warm;
  auto solver = solvers::MakeContactSolver(backend);
  solvers::ContactSolution solution;
  solvers::ContactReport report;
  for (auto _ : state) {
    const solvers::ContactProblem problem(data);  // validation is part of the cost
    solution = warm ? c->previous : solvers::ContactSolution{};
    report = solver->Solve(problem, o, &solution);
    benchmark::DoNotOptimize(solution.force.data());
  }
  const solvers::ContactProblem problem(data);
  state.counters["contacts"] = problem.num_contacts();
  state.counters["residual"] = report.residual.total;
  state.counters["force_error"] =
      solution.force.size() == problem.num_contacts()
          ? solvers::CompareSolutions(problem, solution, c->reference).force
          : NAN;
  state.counters["converged"] = report.status == solvers::ContactStatus::kConverged ? 1 : 0;
  state.counters["iterations"] = report.iterations;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const std::vector<int> sizes = {1, 2, 5, 10, 20, 40};
  std::vector<std::unique_ptr<SliceCase>> cases;
  std::vector<std::string> paths = {"newton-dense", "newton-structured"};
  for (solvers::Backend b : solvers::AvailableBackends())
    if (b != solvers::Backend::kActiveSetNewton && b != solvers::Backend::kNloptLbfgs)
      paths.push_back(solvers::BackendName(b));
  // Warm starts: the two Newton paths and Ipopt (its warm_start_init_point is its own option;
  // the start point alone is what every back end is given).
  for (const char* p : {"newton-dense-warm", "newton-structured-warm"}) paths.push_back(p);
  if (solvers::MakeContactSolver(solvers::Backend::kIpopt)->available())
    paths.push_back("ipopt-warm");
  // The cases are built (a position solved at each size) only when a back-end benchmark is
  // asked for: BM_FaceWidthPosition alone runs without them.
  bool want_backends = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--benchmark_filter=", 0) == 0 && a.find("backends") == std::string::npos)
      want_backends = false;
  }
  if (want_backends)
    for (transmission::FaceCoupling coupling :
         {transmission::FaceCoupling::kNone, transmission::FaceCoupling::kPasternak})
      for (int s : sizes) {
        if (coupling == transmission::FaceCoupling::kPasternak && s == 1) continue;
        cases.push_back(std::make_unique<SliceCase>(BuildSliceCase(s, coupling)));
        for (const std::string& path : paths)
          if (path.find("-warm") == std::string::npos || cases.back()->previous.force.size() > 0)
            benchmark::RegisterBenchmark(("backends/" + cases.back()->name + "/" + path).c_str(),
                                       BM_SliceBackend, cases.back().get(), path)
              ->Unit(benchmark::kMicrosecond);
      }
  epicycle::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  if (!cases.empty()) {
    std::printf("\nCPU time per solve [us] (validation included) and its ratios\n");
    std::printf("%-16s", "case");
    for (const std::string& p : paths) std::printf(" %18s", p.c_str());
    std::printf(" %14s %14s %14s\n", "dense/struct", "ipopt/newton", "warm ratio");
    for (const auto& c : cases) {
      std::printf("%-16s", c->name.c_str());
      for (const std::string& p : paths)
        std::printf(" %18.1f", 1e6 * reporter.seconds("backends/" + c->name + "/" + p));
      const double structured = reporter.seconds("backends/" + c->name + "/newton-structured");
      const double dense = reporter.seconds("backends/" + c->name + "/newton-dense");
      const double newton = std::min(structured, dense);
      const double newton_warm =
          std::min(reporter.seconds("backends/" + c->name + "/newton-structured-warm"),
                   reporter.seconds("backends/" + c->name + "/newton-dense-warm"));
      std::printf(" %14.2f %14.1f %14.1f\n", dense / structured,
                  reporter.seconds("backends/" + c->name + "/ipopt") / newton,
                  reporter.seconds("backends/" + c->name + "/ipopt-warm") / newton_warm);
      for (const std::string& p : paths)
        if (!reporter.converged("backends/" + c->name + "/" + p))
          std::printf("  note: %s on %s did not reach the %g residual\n", p.c_str(),
                      c->name.c_str(), kSolveTolerance);
    }
  }
  benchmark::Shutdown();
  return 0;
}
