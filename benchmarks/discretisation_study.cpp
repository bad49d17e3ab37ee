// The model's own discretisation against its cost (issue 10, "error against run time" item 3;
// docs/quasistatic.md, "Choosing the discretisation"). On the paper's stage with planet 1's 20 µm
// run-out (scenes/paper_stage_runout.toml), three knobs are varied one at a time around the default
// (refinement 1, each body's default join depth h, gap window 100 µm):
//   - the FE mesh refinement of every gear body ([model] mesh_refinement), 1 … R;
//   - the join depth h ([model] join_depth_factor: × 0.5 … 1.5 of each body's default; × 2 would
//     put h past the tooth centre line of the thin sun tooth and is refused by the tables);
//   - the gap window ([contact] gap_window_um), × 0.1 … 4 of 100 µm.
// For each setting it measures
//   - the load-sharing ratios LSR_i and the loaded transmission error TE over one planet revolution
//     (the period of the run-out), fixed and floating sun, N positions;
//   - the mesh stiffness k over a mesh cycle (60 positions) of the sun–planet 1 and planet 1–ring
//     pairs (transmission::ComputeMeshStiffness, the `epicycle stiffness` driver);
//   - the cost: the CPU time of building the three influence tables (their own build figures, which
//     survive the disk cache), their size on disk, and the CPU time of one quasi-static position
//     (the mean over the fixed-sun sweep, tables loaded).
// The change of each result is taken against the knob's reference setting: the finest refinement,
// the widest window, and for h the default h (no h is "finest": with the layer term the model is
// h-independent to first order, so the change measures what is left of the join's h-sensitivity).
// Writes <out>/discretisation_study.csv (one row per knob and setting) and
// <out>/discretisation_study.svg (change against cost, log-log, one series per knob).
//
//   build/benchmarks/discretisation_study [--out DIR] [--max-refinement R] [--positions N]
//                                         [--cache DIR]
// (tools/discretisation_study.sh runs it into docs/figures/.)
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "epicycle/compliance/influence_cache.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/scene.hpp"

namespace {

namespace tr = epicycle::transmission;
namespace geo = epicycle::geometry;
namespace cmp = epicycle::compliance;

// Changes below this are plotted at it (a log axis has no zero; the gap window's changes are
// round-off, 1e-11); the CSV has the values.
constexpr double kChangeFloor = 1e-6;
constexpr int kStiffnessPositions = 60;

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Setting {
  int refinement = 1;
  double h_factor = 1.0;       // × each body's default join depth
  double window_factor = 1.0;  // × the scene's gap window
  auto Key() const { return std::make_tuple(refinement, h_factor, window_factor); }
};

struct SweepData {
  std::vector<bool> converged;
  std::vector<std::vector<double>> lsr;  // [position][planet]
  std::vector<double> te;                // [rad]
  int failed = 0;
  double cpu_per_position = 0;  // [s]
};

struct StiffnessData {
  std::vector<bool> converged;
  std::vector<double> k;  // [N/m] per position
  double mean = 0, min = 0, max = 0;
  int failed = 0;
};

struct Run {
  Setting setting;
  double table_cpu = 0;    // build CPU of the three tables [s] (stored with each table)
  double table_bytes = 0;  // their files [B]
  double table_load = 0;   // wall time to load them from the cache [s] (or build)
  long table_dofs = 0;     // Σ DOF of the three FE models
  std::vector<double> h;   // join depth of sun, ring, planet [m]
  SweepData fixed, floating;
  StiffnessData sun_planet, planet_ring;
};

tr::Scene SceneFor(const tr::Scene& base, const Setting& s) {
  tr::Scene scene = base;
  scene.model.mesh_refinement = s.refinement;
  scene.model.join_depth_factor = s.h_factor;
  scene.gap_window = base.gap_window * s.window_factor;
  return scene;
}

SweepData RunSweep(const tr::Scene& scene, const geo::Stage& stage,
                   const tr::FeStageCompliance& compliance, const std::vector<double>& angles,
                   tr::SunSupport sun) {
  tr::QuasiStaticOptions opt;
  tr::StageSetup setup = tr::SetupFromScene(scene);
  setup.sun = sun;
  const double c0 = CpuSeconds();
  const std::vector<tr::PositionResult> results =
      tr::Sweep(tr::StageModel(stage, compliance, setup), scene.loads, angles, opt);
  SweepData d;
  d.cpu_per_position = (CpuSeconds() - c0) / static_cast<double>(angles.size());
  for (const tr::PositionResult& r : results) {
    d.converged.push_back(r.converged);
    d.lsr.push_back(r.load_sharing);
    d.te.push_back(r.transmission_error);
    if (!r.converged) ++d.failed;
  }
  return d;
}

StiffnessData RunStiffness(const tr::Scene& scene, const geo::Stage& stage, const std::string& mesh,
                           const tr::FeComplianceOptions& fe) {
  const tr::MeshPairSetup setup = tr::MakeMeshPair(scene, &stage, mesh);
  const geo::GearPair pair(setup.spec);
  const tr::FePairCompliance compliance(scene, pair, fe);
  tr::MeshStiffnessOptions opt;
  opt.positions = kStiffnessPositions;
  const tr::MeshStiffnessResult result =
      tr::ComputeMeshStiffness(setup, pair, compliance, opt);
  StiffnessData d;
  for (const tr::MeshSample& s : result.samples) {
    d.converged.push_back(s.converged);
    d.k.push_back(s.mesh_stiffness);
  }
  d.failed = result.failed;
  d.mean = result.mean_stiffness;
  d.min = result.min_stiffness;
  d.max = result.max_stiffness;
  return d;
}

Run Compute(const tr::Scene& base, const Setting& s, const std::vector<double>& angles,
            const std::string& cache) {
  const tr::Scene scene = SceneFor(base, s);
  const geo::Stage stage(scene.stage);
  tr::FeComplianceOptions fe;
  fe.cache_directory = cache;
  Run run;
  run.setting = s;
  const auto t0 = std::chrono::steady_clock::now();
  const tr::FeStageCompliance compliance(scene, stage, fe);
  run.table_load = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The distinct bodies: sun (0), ring (1), planet 1 (2; the run-out moves the planet's centre, the
  // body and its table are the nominal planet's, shared by all planets).
  const std::vector<const geo::Gear*> gears = {&stage.sun(), &stage.ring(), &stage.planet(0)};
  for (int b = 0; b < 3; ++b) {
    const cmp::InfluenceTable& t = compliance.tables().Table(b);
    for (double v : t.build_seconds()) run.table_cpu += v;
    run.table_dofs += t.num_dofs();
    run.h.push_back(t.join_depth());
    cmp::InfluenceTableOptions o;
    o.mesh.refinement = s.refinement;
    o.join_depth_factor = s.h_factor;
    const cmp::ElasticMaterial material{scene.material.youngs_modulus, scene.material.poisson_ratio,
                                        gears[b]->spec().face_width, compliance.tables().plane()};
    const std::string file =
        cmp::InfluenceTableFile(cache, cmp::InfluenceTableKey(gears[b]->spec(), material, o));
    if (!std::filesystem::exists(file))
      throw std::runtime_error(file + ": the table's cache file is missing (key mismatch)");
    run.table_bytes += static_cast<double>(std::filesystem::file_size(file));
  }
  run.fixed = RunSweep(scene, stage, compliance, angles, tr::SunSupport::kFixed);
  run.floating = RunSweep(scene, stage, compliance, angles, tr::SunSupport::kFloating);
  run.sun_planet = RunStiffness(scene, stage, "sun-planet1", fe);
  run.planet_ring = RunStiffness(scene, stage, "planet1-ring", fe);
  return run;
}

// The changes of one run against a reference run of the same positions.
struct Change {
  double lsr_fixed = 0, lsr_floating = 0;         // max |ΔLSR_i| over positions and planets [-]
  double te_fixed = 0, te_floating = 0;           // max |ΔTE| / |TE_ref| over positions [-]
  double k_sp = 0, k_pr = 0;                      // max of |Δ| / ref of mean, min and max k [-]
  double k_sp_pointwise = 0, k_pr_pointwise = 0;  // max |Δk| / k_ref over positions [-]
  int compared = 0;                               // positions converged in both sweeps
};

void Compare(const SweepData& a, const SweepData& ref, double* lsr, double* te, int* count) {
  *lsr = *te = 0;
  *count = 0;
  for (std::size_t p = 0; p < ref.converged.size(); ++p) {
    if (!a.converged[p] || !ref.converged[p]) continue;
    ++*count;
    for (std::size_t i = 0; i < ref.lsr[p].size(); ++i)
      *lsr = std::max(*lsr, std::abs(a.lsr[p][i] - ref.lsr[p][i]));
    *te = std::max(*te, std::abs(a.te[p] - ref.te[p]) / std::abs(ref.te[p]));
  }
}

// Mean, smallest and largest k and the pointwise change, over the positions converged in both
// (a position that failed in one of the two would change the statistics by its absence alone).
void CompareStiffness(const StiffnessData& a, const StiffnessData& ref, double* zone,
                      double* pointwise) {
  double mean_a = 0, mean_r = 0, min_a = 1e300, min_r = 1e300, max_a = 0, max_r = 0;
  int count = 0;
  *pointwise = 0;
  for (std::size_t p = 0; p < ref.k.size(); ++p) {
    if (!a.converged[p] || !ref.converged[p]) continue;
    ++count;
    mean_a += a.k[p];
    mean_r += ref.k[p];
    min_a = std::min(min_a, a.k[p]);
    min_r = std::min(min_r, ref.k[p]);
    max_a = std::max(max_a, a.k[p]);
    max_r = std::max(max_r, ref.k[p]);
    *pointwise = std::max(*pointwise, std::abs(a.k[p] - ref.k[p]) / ref.k[p]);
  }
  *zone = count == 0 ? std::numeric_limits<double>::quiet_NaN()
                     : std::max({std::abs(mean_a - mean_r) / mean_r,
                                 std::abs(min_a - min_r) / min_r, std::abs(max_a - max_r) / max_r});
}

Change Against(const Run& a, const Run& ref) {
  Change c;
  int floating_count = 0;
  Compare(a.fixed, ref.fixed, &c.lsr_fixed, &c.te_fixed, &c.compared);
  Compare(a.floating, ref.floating, &c.lsr_floating, &c.te_floating, &floating_count);
  c.compared = std::min(c.compared, floating_count);
  CompareStiffness(a.sun_planet, ref.sun_planet, &c.k_sp, &c.k_sp_pointwise);
  CompareStiffness(a.planet_ring, ref.planet_ring, &c.k_pr, &c.k_pr_pointwise);
  return c;
}

struct Knob {
  std::string name, label;
  std::vector<Setting> settings;
  Setting reference;
};

// A 2-column grid of log-log panels (table cost, position cost) × quantities, each panel one
// RenderSvg document nested in the figure.
void WriteFigure(const std::string& path, const std::vector<Knob>& knobs,
                 const std::map<std::tuple<int, double, double>, Run>& runs) {
  struct Quantity {
    std::string title, unit;
    double target;  // the accuracy named in the docs' recommendation, dashed
    double Change::*member;
  };
  const std::vector<Quantity> quantities = {
      {"LSR, fixed sun", "max |change of LSR_i|", 1e-3, &Change::lsr_fixed},
      {"LSR, floating sun", "max |change of LSR_i|", 1e-3, &Change::lsr_floating},
      {"loaded TE, fixed sun", "max relative change of TE", 1e-2, &Change::te_fixed},
      {"mesh stiffness sun-planet 1", "relative change of mean/min/max k", 5e-3, &Change::k_sp},
      {"mesh stiffness planet 1-ring", "relative change of mean/min/max k", 5e-3, &Change::k_pr}};
  const double pw = 760, ph = 480;
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} "
      "{1}\">\n",
      2 * pw, ph * static_cast<double>(quantities.size()));
  for (std::size_t q = 0; q < quantities.size(); ++q) {
    for (int col = 0; col < 2; ++col) {
      epicycle::report::LinePlot plot;
      plot.log_x = plot.log_y = true;
      plot.title = quantities[q].title + (col == 0 ? " vs table build" : " vs one position");
      plot.x_label = col == 0 ? "CPU to build the three influence tables [s]"
                              : "CPU per quasi-static position [us]";
      plot.y_label = quantities[q].unit;
      plot.y_references = {quantities[q].target};
      for (const Knob& knob : knobs) {
        // A line in setting order where the knob moves this cost (refinement: both; the window:
        // the position's), points where it does not (h; the window's tables).
        epicycle::report::PlotSeries ser;
        ser.name = knob.label;
        ser.markers = true;
        ser.points = knob.name.starts_with("join_depth") || (knob.name == "gap_window" && col == 0);
        const Run& ref = runs.at(knob.reference.Key());
        for (const Setting& s : knob.settings) {
          if (s.Key() == knob.reference.Key()) continue;
          const Run& r = runs.at(s.Key());
          ser.x.push_back(col == 0 ? r.table_cpu : r.fixed.cpu_per_position * 1e6);
          ser.y.push_back(std::max(Against(r, ref).*quantities[q].member, kChangeFloor));
        }
        plot.series.push_back(ser);
      }
      svg += fmt::format("<svg x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\">\n", col * pw,
                         static_cast<double>(q) * ph, pw, ph);
      std::string panel = epicycle::report::RenderSvg(plot);
      // Drop the panel's own XML root attributes: nested as an <svg> element it keeps its body.
      svg += panel.substr(panel.find('\n') + 1);
    }
  }
  svg += "</svg>\n";
  epicycle::report::WriteTextFile(path, svg);
}

// Richardson analysis of a scalar X(r) on the three finest refinements r_a < r_b < r_c, element
// size ∝ 1/r: X(r) = X∞ + C r^−p. The observed order p solves
//   (X_a − X_b)/(X_b − X_c) = (r_a^−p − r_b^−p)/(r_b^−p − r_c^−p),
// whose right side grows monotonically from ln(r_b/r_a)/ln(r_c/r_b) (p → 0); outside that range
// (or with changes of opposite sign) X is not in its asymptotic range and no order is claimed.
struct Richardson {
  bool valid = false;
  double order = 0, limit = 0;
};

Richardson Extrapolate(const std::array<double, 3>& r, const std::array<double, 3>& x) {
  Richardson out;
  const double d1 = x[0] - x[1], d2 = x[1] - x[2];
  if (!(d1 * d2 > 0)) return out;
  const double q = d1 / d2;
  auto f = [&](double p) {
    return (std::pow(r[0], -p) - std::pow(r[1], -p)) / (std::pow(r[1], -p) - std::pow(r[2], -p));
  };
  double lo = 1e-6, hi = 12;
  if (!(q > f(lo) && q < f(hi))) return out;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < q ? lo : hi) = mid;
  }
  out.valid = true;
  out.order = 0.5 * (lo + hi);
  const double c = d2 / (std::pow(r[1], -out.order) - std::pow(r[2], -out.order));
  out.limit = x[2] - c * std::pow(r[2], -out.order);
  return out;
}

// Mesh-cycle or revolution means and extremes of a run: the scalars of the Richardson table.
struct Scalars {
  std::vector<std::pair<std::string, double>> values;
};

Scalars ScalarsOf(const Run& r) {
  auto mean_of = [](const StiffnessData& d) {
    double sum = 0;
    int n = 0;
    for (std::size_t p = 0; p < d.k.size(); ++p)
      if (d.converged[p]) sum += d.k[p], ++n;
    return sum / n;
  };
  double te_sum = 0, lsr1_max = 0;
  int n = 0;
  for (std::size_t p = 0; p < r.fixed.te.size(); ++p) {
    if (!r.fixed.converged[p]) continue;
    te_sum += r.fixed.te[p];
    lsr1_max = std::max(lsr1_max, r.fixed.lsr[p][0]);
    ++n;
  }
  return {{{"mean k sun-planet 1 [N/m]", mean_of(r.sun_planet)},
           {"mean k planet 1-ring [N/m]", mean_of(r.planet_ring)},
           {"mean TE, fixed sun [rad]", te_sum / n},
           {"largest LSR_1, fixed sun [-]", lsr1_max}}};
}

// A CSV cell: empty when nothing could be computed (no position converged), never "nan".
std::string Cell(double v, const char* format = "{:.3e}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : "";
}

std::string SettingLabel(const std::string& knob, const Setting& s) {
  if (knob == "refinement") return std::to_string(s.refinement);
  if (knob.starts_with("join_depth")) return fmt::format("{:g}", s.h_factor);
  return fmt::format("{:g}", s.window_factor);
}

}  // namespace

int main(int argc, char** argv) try {
  std::string out = "docs/figures", cache;
  int max_refinement = 4, positions = 2880;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto value = [&]() -> std::string {
      if (k + 1 >= argc) throw std::invalid_argument(a + ": needs a value");
      return argv[++k];
    };
    if (a == "--out") {
      out = value();
    } else if (a == "--max-refinement") {
      max_refinement = std::stoi(value());
      if (max_refinement < 2 || max_refinement > 4)
        throw std::invalid_argument("--max-refinement " + std::to_string(max_refinement) +
                                    ": must be in [2, 4] (mesh_refinement is 1..4)");
    } else if (a == "--positions") {
      positions = std::stoi(value());
      if (positions < 2)
        throw std::invalid_argument("--positions " + std::to_string(positions) + ": must be >= 2");
    } else if (a == "--cache") {
      cache = value();
    } else {
      throw std::invalid_argument(a +
                                  ": unknown option (--out, --max-refinement, --positions, "
                                  "--cache)");
    }
  }
  if (cache.empty()) cache = tr::DefaultCacheDirectory();
  std::filesystem::create_directories(out);

  const tr::Scene base =
      tr::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_runout.toml");
  const geo::Stage stage(base.stage);
  // One planet revolution relative to the carrier (the period of planet 1's run-out).
  const std::vector<double> angles =
      tr::SweepAngles(0.0, tr::CarrierSpan(stage, tr::RunRange::kPlanetRevolution), positions);

  std::vector<Knob> knobs(3);
  knobs[0] = {"refinement", "refinement 1..R", {}, Setting{max_refinement, 1.0, 1.0}};
  for (int r = 1; r <= max_refinement; ++r) knobs[0].settings.push_back({r, 1.0, 1.0});
  knobs[1] = {"join_depth", "h x0.5..1.5 (r1)", {}, Setting{}};
  for (double f : {0.5, 0.75, 1.0, 1.25, 1.5}) knobs[1].settings.push_back({1, f, 1.0});
  knobs[2] = {"gap_window", "gap window x0.1..4", {}, Setting{1, 1.0, 4.0}};
  for (double f : {0.1, 0.25, 0.5, 1.0, 2.0, 4.0}) knobs[2].settings.push_back({1, 1.0, f});
  // h again on the refined mesh: what of h's change is the coarse mesh's shallow read-out.
  knobs.push_back({"join_depth_r2", "h x0.5..1.5 (r2)", {}, Setting{2, 1.0, 1.0}});
  for (double f : {0.5, 0.75, 1.0, 1.25, 1.5}) knobs[3].settings.push_back({2, f, 1.0});

  std::map<std::tuple<int, double, double>, Run> runs;
  for (const Knob& knob : knobs) {
    for (const Setting& s : knob.settings) {
      if (runs.count(s.Key())) continue;
      std::fprintf(stderr, "refinement %d, h x %g, window x %g ...\n", s.refinement, s.h_factor,
                   s.window_factor);
      runs.emplace(s.Key(), Compute(base, s, angles, cache));
    }
  }

  const std::string csv_path = out + "/discretisation_study.csv";
  std::ofstream csv(csv_path);
  csv << "knob,setting,refinement,h_factor,window_factor,h_sun_mm,h_ring_mm,h_planet_mm,"
         "table_dofs,table_cpu_s,table_MiB,table_load_s,position_fixed_us,position_floating_us,"
         "failed_fixed,failed_floating,failed_stiffness,compared_positions,"
         "lsr_fixed,lsr_floating,te_fixed,te_floating,k_sun_planet,k_planet_ring,"
         "k_sun_planet_pointwise,k_planet_ring_pointwise,k_sun_planet_mean_N_per_mm_um,"
         "k_planet_ring_mean_N_per_mm_um\n";
  std::printf(
      "| knob | setting | table CPU [s] | tables [MiB] | position [us] | dLSR fixed | "
      "dLSR floating | dTE fixed | dk sun-planet | dk planet-ring |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  const double b = base.stage.sun.face_width;
  for (const Knob& knob : knobs) {
    const Run& ref = runs.at(knob.reference.Key());
    for (const Setting& s : knob.settings) {
      const Run& r = runs.at(s.Key());
      const Change c = Against(r, ref);
      const bool is_ref = s.Key() == knob.reference.Key();
      const std::string label = SettingLabel(knob.name, s) + (is_ref ? " (ref)" : "");
      csv << fmt::format(
          "{},{},{},{},{},{:.4f},{:.4f},{:.4f},{},{:.3f},{:.2f},{:.3f},{:.1f},{:.1f},{},{},{},{},"
          "{},{},{},{},{},{},{},{},{},{}\n",
          knob.name, label, s.refinement, s.h_factor, s.window_factor, r.h[0] * 1e3, r.h[1] * 1e3,
          r.h[2] * 1e3, r.table_dofs, r.table_cpu, r.table_bytes / 1048576.0, r.table_load,
          r.fixed.cpu_per_position * 1e6, r.floating.cpu_per_position * 1e6, r.fixed.failed,
          r.floating.failed, r.sun_planet.failed + r.planet_ring.failed, c.compared,
          Cell(c.lsr_fixed), Cell(c.lsr_floating), Cell(c.te_fixed), Cell(c.te_floating),
          Cell(c.k_sp), Cell(c.k_pr), Cell(c.k_sp_pointwise), Cell(c.k_pr_pointwise),
          Cell(r.sun_planet.mean / b / 1e9, "{:.4f}"),
          Cell(r.planet_ring.mean / b / 1e9, "{:.4f}"));
      std::printf("| %s | %s | %.1f | %.1f | %.0f | %.2e | %.2e | %.2e | %.2e | %.2e |\n",
                  knob.name.c_str(), label.c_str(), r.table_cpu, r.table_bytes / 1048576.0,
                  r.fixed.cpu_per_position * 1e6, c.lsr_fixed, c.lsr_floating, c.te_fixed, c.k_sp,
                  c.k_pr);
      if (r.fixed.failed + r.floating.failed + r.sun_planet.failed + r.planet_ring.failed > 0) {
        std::printf("  (failed positions: fixed %d, floating %d, stiffness %d)\n", r.fixed.failed,
                    r.floating.failed, r.sun_planet.failed + r.planet_ring.failed);
      }
    }
  }
  csv.close();
  if (!csv) throw std::runtime_error(csv_path + ": cannot be written");
  WriteFigure(out + "/discretisation_study.svg", knobs, runs);

  // Richardson extrapolation over the three finest refinements: the observed order and the error
  // of every level against the extrapolated limit (the change against the finest level
  // understates it by the finest level's own error).
  if (max_refinement < 3) {
    std::printf("(no Richardson table: it needs three refinements)\n");
    return 0;
  }
  const std::array<double, 3> levels = {static_cast<double>(max_refinement - 2),
                                        static_cast<double>(max_refinement - 1),
                                        static_cast<double>(max_refinement)};
  std::vector<Scalars> by_level;
  for (int r = 1; r <= max_refinement; ++r) by_level.push_back(ScalarsOf(runs.at({r, 1.0, 1.0})));
  const std::string rich_path = out + "/discretisation_study_richardson.csv";
  std::ofstream rich(rich_path);
  rich << "quantity,refinement,value,order_observed,extrapolated,error_vs_extrapolated\n";
  std::printf(
      "\n| quantity | observed order (refinement %d, %d, %d) | error against the "
      "extrapolation, refinement 1 … %d |\n|---|---|---|\n",
      max_refinement - 2, max_refinement - 1, max_refinement, max_refinement);
  for (std::size_t q = 0; q < by_level[0].values.size(); ++q) {
    std::array<double, 3> x{};
    for (int k = 0; k < 3; ++k) x[k] = by_level[max_refinement - 3 + k].values[q].second;
    const Richardson rr = Extrapolate(levels, x);
    std::string errors;
    for (int r = 1; r <= max_refinement; ++r) {
      const double v = by_level[r - 1].values[q].second;
      const double e = rr.valid ? (v - rr.limit) / rr.limit : std::nan("");
      rich << fmt::format("{},{},{},{},{},{}\n", by_level[0].values[q].first, r, Cell(v, "{:.10g}"),
                          rr.valid ? fmt::format("{:.3f}", rr.order) : "",
                          rr.valid ? fmt::format("{:.10g}", rr.limit) : "",
                          rr.valid ? fmt::format("{:.3e}", e) : "");
      errors += (r > 1 ? ", " : "") + (rr.valid ? fmt::format("{:+.3f} %", 100 * e) : "-");
    }
    std::printf("| %s | %s | %s |\n", by_level[0].values[q].first.c_str(),
                rr.valid ? fmt::format("{:.2f}", rr.order).c_str() : "not asymptotic",
                errors.c_str());
  }
  rich.close();
  if (!rich) throw std::runtime_error(rich_path + ": cannot be written");
  std::printf("wrote %s and %s/discretisation_study.svg (%d positions per sweep)\n",
              csv_path.c_str(), out.c_str(), positions);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "discretisation_study: %s\n", e.what());
  return 1;
}
