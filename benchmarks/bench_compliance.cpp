// FE core at the size of one gear body: mapped mesh, assembly, one sparse LDLᵀ factorisation and
// many right-hand sides. A full ring a ≤ r ≤ b (four 90° patches, graded toward the outer
// surface, like a flank band) fixed at its bore, loaded by an outer pressure (checked against the
// closed form after the timing loop) and by point forces along the outer edge (the influence-table
// pattern: many load cases, one factorisation). Counters: DOFs, non-zeros of K and of the factor,
// CPU time of each stage, peak resident memory (VmHWM, reset per benchmark where the kernel
// allows).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/influence_cache.hpp"
#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/compliance/mesher.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace {

using namespace epicycle;
using namespace epicycle::compliance;

constexpr double kA = 0.02, kB = 0.06, kPressure = 50e6;

Region Ring(int nr, int nt) {
  Region region;
  for (int q = 0; q < 4; ++q) {
    const double t0 = q * std::numbers::pi / 2, t1 = (q + 1) * std::numbers::pi / 2;
    Patch p;
    p.sides = {StraightLine({kA * std::cos(t0), kA * std::sin(t0)},
                            {kB * std::cos(t0), kB * std::sin(t0)}),
               CircularArc({0.0, 0.0}, kB, t0, t1),
               StraightLine({kA * std::cos(t1), kA * std::sin(t1)},
                            {kB * std::cos(t1), kB * std::sin(t1)}),
               CircularArc({0.0, 0.0}, kA, t0, t1)};
    p.side_names = {"", "outer", "", "bore"};
    p.u = Distribution::Graded(nr, 0.2);  // elements 5× smaller at the outer surface
    p.v = Distribution::Uniform(nt);
    region.patches.push_back(p);
  }
  return region;
}

// u_r(b) for u(a) = 0 and σ_rr(b) = −p, u = A r + B/r with B = −A a², plane-stress-equivalent
// E', ν':  A = −p (1−ν'²) / (E' [(1+ν') + (1−ν') a²/b²]).
double ExactOuterRadialDisplacement(const ElasticMaterial& m) {
  const double e = m.EffectiveModulus(), nu = m.EffectivePoissonRatio();
  const double a = -kPressure * (1 - nu * nu) / (e * ((1 + nu) + (1 - nu) * kA * kA / (kB * kB)));
  return a * (kB - kA * kA / kB);
}

double PeakResidentKiB() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6));
  }
  return -1.0;
}

void ResetPeakResident() {
  std::ofstream clear("/proc/self/clear_refs");
  if (clear) clear << "5";  // Linux ≥ 4.0: reset VmHWM to the current RSS
}

// Stage times are process CPU times: the machine is shared, and wall time would measure the
// neighbours' load as much as ours (everything here is single-threaded).
double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double Seconds(double t0) { return CpuSeconds() - t0; }

void BM_GearSizedModel(benchmark::State& state) {
  const int nr = static_cast<int>(state.range(0));
  const int nt = static_cast<int>(state.range(1));
  const int num_rhs = static_cast<int>(state.range(2));
  const ElasticMaterial steel{206e9, 0.3, 0.025, PlaneAssumption::kPlaneStrain};
  ResetPeakResident();
  double t_mesh = 0, t_assemble = 0, t_factor = 0, t_solve = 0, error = 0;
  long dofs = 0, nnz_k = 0, nnz_l = 0;
  for (auto _ : state) {
    double t0 = CpuSeconds();
    Mesh mesh = MappedMesher().BuildMesh(Ring(nr, nt));
    t_mesh += Seconds(t0);
    t0 = CpuSeconds();
    LinearElasticModel model(std::move(mesh), steel);
    t_assemble += Seconds(t0);
    model.FixNodeSet("bore");
    t0 = CpuSeconds();
    model.Factorize();
    t_factor += Seconds(t0);
    // Load cases: outer pressure, then point forces (radial) spread along the outer edge.
    Eigen::MatrixXd f = Eigen::MatrixXd::Zero(model.num_dofs(), num_rhs);
    Eigen::VectorXd pressure = model.ZeroLoads();
    model.AddEdgeTraction(
        "outer",
        [](const Eigen::Vector2d&, const Eigen::Vector2d& n) { return (-kPressure * n).eval(); },
        &pressure);
    f.col(0) = pressure;
    const int edges = static_cast<int>(model.mesh().EdgeSet("outer").size());
    for (int j = 1; j < num_rhs; ++j) {
      Eigen::VectorXd fj = model.ZeroLoads();
      const EdgePoint at{(j * 7919) % edges, -0.3};
      model.AddEdgePointForce("outer", at, -1000.0 * model.mesh().EdgeNormal("outer", at), &fj);
      f.col(j) = fj;
    }
    t0 = CpuSeconds();
    const Eigen::MatrixXd u = model.SolveMany(f);
    t_solve += Seconds(t0);
    benchmark::DoNotOptimize(u.data());
    // Check: the outer surface's radial displacement under the pressure.
    const double exact = ExactOuterRadialDisplacement(steel);
    error = 0.0;
    for (int v : model.mesh().NodeSet("outer")) {
      const Eigen::Vector2d x = model.mesh().nodes[v];
      error = std::max(
          error, std::abs(model.NodeDisplacement(u.col(0), v).dot(x.normalized()) / exact - 1.0));
    }
    dofs = model.num_dofs();
    nnz_k = static_cast<long>(model.stiffness().nonZeros());
    nnz_l = model.factor_nonzeros();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["dofs"] = static_cast<double>(dofs);
  state.counters["rhs"] = num_rhs;
  state.counters["nnz_K"] = static_cast<double>(nnz_k);
  state.counters["nnz_L"] = static_cast<double>(nnz_l);
  state.counters["mesh_ms"] = 1e3 * t_mesh / n;
  state.counters["assemble_ms"] = 1e3 * t_assemble / n;
  state.counters["factor_ms"] = 1e3 * t_factor / n;
  state.counters["solve_all_ms"] = 1e3 * t_solve / n;
  state.counters["solve_per_rhs_ms"] = 1e3 * t_solve / n / num_rhs;
  state.counters["peak_rss_MiB"] = PeakResidentKiB() / 1024.0;
  state.counters["rel_error_lame"] = error;
}

BENCHMARK(BM_GearSizedModel)
    ->Args({12, 30, 60})
    ->Args({24, 60, 60})
    ->Args({32, 80, 60})
    ->Args({32, 80, 120})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);

// Influence tables of the paper's stage (scenes/paper_stage.toml) at the default density: sun,
// planet, ring. Counters: DOFs, CPU time of mesh, assembly + factorisation, solves + extraction,
// peak resident memory of the build; the check after the loop is the Maxwell–Betti asymmetry of
// the raw table (round-off when the build is right).
void BM_GearInfluenceTable(benchmark::State& state) {
  const transmission::Scene scene =
      transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
  const int which = static_cast<int>(state.range(0));
  const geometry::GearSpec& spec =
      which == 0 ? scene.stage.sun : (which == 1 ? scene.stage.planet : scene.stage.ring);
  const geometry::Gear gear(spec);
  const ElasticMaterial steel{scene.material.youngs_modulus, scene.material.poisson_ratio,
                              spec.face_width, PlaneAssumption::kPlaneStrain};
  ResetPeakResident();
  double total = 0, asym = 0;
  std::array<double, 3> stages{};
  long dofs = 0;
  int points = 0;
  for (auto _ : state) {
    const double t0 = CpuSeconds();
    const InfluenceTable table = InfluenceTable::Build(gear, steel);
    total += Seconds(t0);
    for (int k = 0; k < 3; ++k) stages[k] += table.build_seconds()[k];
    asym = table.raw_asymmetry();
    dofs = table.num_dofs();
    points = table.grid().num_points();
  }
  const double n = static_cast<double>(state.iterations());
  state.SetLabel(spec.name);
  state.counters["dofs"] = static_cast<double>(dofs);
  state.counters["grid_points"] = points;
  state.counters["rhs"] = 4.0 * points;
  state.counters["mesh_s"] = stages[0] / n;
  state.counters["factor_s"] = stages[1] / n;
  state.counters["solve_s"] = stages[2] / n;
  state.counters["build_cpu_s"] = total / n;
  state.counters["peak_rss_MiB"] = PeakResidentKiB() / 1024.0;
  state.counters["betti_asymmetry"] = asym;
}

BENCHMARK(BM_GearInfluenceTable)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1);

// Loading a cached table (the ring, the largest): the file is written once before the loop (in a
// temporary directory), then each iteration reads and checks it. The check after the loop: the
// loaded table's compliance equals the built one's.
void BM_GearTableCachedLoad(benchmark::State& state) {
  const transmission::Scene scene =
      transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
  const geometry::Gear gear(scene.stage.ring);
  const ElasticMaterial steel{scene.material.youngs_modulus, scene.material.poisson_ratio,
                              scene.stage.ring.face_width, PlaneAssumption::kPlaneStrain};
  const std::string dir = (std::filesystem::temp_directory_path() / "epicycle-bench-ilt").string();
  CacheReport report;
  const InfluenceTable built = LoadOrBuildInfluenceTable(gear, steel, {}, dir, &report);
  double error = 0.0;
  for (auto _ : state) {
    const InfluenceTable loaded = LoadOrBuildInfluenceTable(gear, steel, {}, dir, &report);
    if (report.outcome != CacheOutcome::kLoaded) state.SkipWithError(report.message.c_str());
    const FlankPosition a{0, 1, 0.4 * built.arc_length_max()},
        b{3, -1, 0.6 * built.arc_length_max()};
    error = (loaded.Influence(a, b) - built.Influence(a, b)).norm();
  }
  state.counters["file_MiB"] =
      static_cast<double>(std::filesystem::file_size(report.file)) / (1024.0 * 1024.0);
  state.counters["error"] = error;
  std::error_code e;
  std::filesystem::remove_all(dir, e);
}

BENCHMARK(BM_GearTableCachedLoad)->Unit(benchmark::kMillisecond)->Iterations(5);

// One structural compliance n_rᵀ Λ n_l between two body-frame points (locating both on the
// profile, then the bicubic interpolation), and the interpolation alone.
void BM_GearTableCompliance(benchmark::State& state) {
  const transmission::Scene scene =
      transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
  const geometry::Gear gear(scene.stage.planet);
  InfluenceTableOptions coarse;
  coarse.mesh.band_layers = 1;
  coarse.mesh.rim_layers = 1;
  const InfluenceTable table = InfluenceTable::Build(
      gear,
      ElasticMaterial{scene.material.youngs_modulus, scene.material.poisson_ratio,
                      scene.stage.planet.face_width, PlaneAssumption::kPlaneStrain},
      coarse);
  const int i = 9, j = 23;
  const Eigen::Vector2d x1 = table.grid().position[i], n1 = table.grid().normal[i];
  const Eigen::Vector2d x2 = table.grid().position[j], n2 = table.grid().normal[j];
  const bool locate = state.range(0) == 1;
  double c = 0.0;
  for (auto _ : state) {
    if (locate) {
      c = table.Compliance(x1, n1, 0, 1, x2, n2, 0, 1);
    } else {
      const FlankPosition a{0, 1, 0.31 * table.arc_length_max()},
          b{4, -1, 0.62 * table.arc_length_max()};
      c = n2.dot(table.Influence(a, b) * n1);
    }
    benchmark::DoNotOptimize(c);
  }
  // Check: at grid nodes the compliance is the table's value.
  const FlankPosition a{0, 1, table.grid().arc_length[i]}, b{0, 1, table.grid().arc_length[j]};
  state.counters["error"] = locate ? std::abs(c - n2.dot(table.Influence(a, b) * n1)) : 0.0;
}

BENCHMARK(BM_GearTableCompliance)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The compliance matrix of the whole paper stage's potential contacts at one carrier position
// (both flanks, every mesh, the gap window of the scene): every contact side located on its body
// once, then the coupled N×N operator (sun and ring couple all planets, each planet its two
// meshes). The tables come from a cache written before the loop. Check after the loop: the
// largest asymmetry of C relative to its largest entry, and the number of contacts.
void BM_StageComplianceMatrix(benchmark::State& state) {
  const transmission::Scene scene =
      transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
  const geometry::Stage stage(scene.stage);
  transmission::FeComplianceOptions fe;
  fe.cache_directory = (std::filesystem::temp_directory_path() / "epicycle-bench-ilt").string();
  const transmission::FeStageCompliance compliance(scene, stage, fe);
  const geometry::StagePoses poses =
      stage.Poses(geometry::Rad(static_cast<double>(state.range(0))));
  const std::vector<transmission::StageContact> contacts =
      transmission::SearchStage(stage, poses, scene.gap_window);
  Eigen::MatrixXd c;
  for (auto _ : state) {
    c = compliance.Matrix(stage, poses, contacts);
    benchmark::DoNotOptimize(c.data());
  }
  state.counters["contacts"] = static_cast<double>(contacts.size());
  state.counters["asymmetry"] = (c - c.transpose()).cwiseAbs().maxCoeff() / c.cwiseAbs().maxCoeff();
}

BENCHMARK(BM_StageComplianceMatrix)->Arg(0)->Arg(3)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
