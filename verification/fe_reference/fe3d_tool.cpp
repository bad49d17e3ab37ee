// `fe_reference fe3d`, `fe3d-plot` and `fe3d-slices` (docs/fe_reference.md, "3D reference across
// the face width"): one 3D run appended to a CSV, one row per axial station; the figure of the
// load per unit width across the face; the slice model against it (docs/face_width.md).
#include "fe3d_tool.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "csv_rows.hpp"
#include "epicycle/transmission/face_width.hpp"
#include "fe3d_slices.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "fe3d.hpp"

namespace epicycle::fe_reference {

namespace {

constexpr const char* kHeader =
    "case,angle_deg,face_width_mm,misalignment_um,layers,refinement,contact_size_um,plane_strain,"
    "nodes,elements,ccx_cpu_s,ccx_wall_s,runs,extrapolated,moment_balance,rotation_urad,"
    "approach_um,total_force_N,k_hbeta,peak_z_mm,stiffness_N_per_mm_um,"
    "middle_stiffness_N_per_mm_um,station,z_lo_mm,z_hi_mm,z_mm,line_load_N_per_mm";

}  // namespace

int Fe3dCommand(const Fe3dCommandArgs& a) {
  const transmission::Scene scene = transmission::ReadScene(a.scene);
  if (scene.kind != transmission::SceneKind::kPair)
    throw std::invalid_argument(a.scene + ": the 3D reference takes a pair scene");
  const transmission::MeshPairSetup setup = transmission::MakeMeshPair(scene, nullptr, "");
  const geometry::GearPair pair(setup.spec);
  if (!(a.plane_k > 0))
    throw std::invalid_argument("--plane-k = " + std::to_string(a.plane_k) + ": must be > 0");
  Fe3dOptions o;
  o.face_width = a.face_width_mm * 1e-3;
  o.layers = a.layers;
  o.misalignment = a.misalignment_um * 1e-6;
  o.plane_strain = a.plane_strain;
  o.mesh.refinement = a.refinement;
  if (a.tooth_size_per_module > 0) o.mesh.tooth_size_per_module = a.tooth_size_per_module;
  if (a.body_size_per_module > 0) o.mesh.body_size_per_module = a.body_size_per_module;
  if (a.grading > 0) o.mesh.grading = a.grading;
  if (a.sector_teeth >= 0) o.sector_teeth = a.sector_teeth;
  if (a.tooth_zone >= 0) o.mesh.tooth_zone = a.tooth_zone;
  if (a.contact_size_um > 0) o.mesh.contact_size = a.contact_size_um * 1e-6;
  if (a.deck_only) {
    const Fe3dDeckInfo d =
        WriteDeck3d(scene, pair, 1.0, a.angle_deg * geometry::kPi / 180.0, {1e-4, 2e-4}, o, a.out);
    std::printf("%s/deck.inp: %d nodes, %d C3D15 (plane: %d nodes, %d triangles), %zu pairs\n",
                a.out.c_str(), d.deck.nodes, d.deck.elements, d.deck.nodes_2d, d.deck.triangles,
                d.deck.pairs.size());
    return 0;
  }
  // A face width of its own keeps the scene's load per unit width: the torque scales with b.
  const double b_pair = geometry::ContactFaceWidth(pair.gear1(), pair.gear2());
  const double torque = setup.torque * (o.face_width > 0 ? o.face_width / b_pair : 1.0);
  const Fe3dRun run = RunFe3d(scene, pair, torque, a.angle_deg * geometry::kPi / 180.0,
                              a.plane_k * 1e9, o, a.out, a.ccx, a.threads);
  const Fe3dLineLoad& r = run.result;
  const bool fresh = !std::filesystem::exists(a.csv);
  std::ofstream f(a.csv, std::ios::app);
  if (!f) throw std::runtime_error(a.csv + ": cannot be written");
  if (fresh) f << kHeader << "\n";
  for (std::size_t l = 0; l < r.z.size(); ++l) {
    char line[1024];
    std::snprintf(line, sizeof line,
                  "%s,%.6f,%.6g,%.6g,%d,%.6g,%.6g,%d,%d,%d,%.2f,%.2f,%d,%d,%.3e,%.9g,%.9g,%.9g,"
                  "%.9g,%.6g,%.9g,%.9g,%zu,%.6g,%.6g,%.6g,%.9g\n",
                  a.name.c_str(), a.angle_deg, r.face_width * 1e3, r.misalignment * 1e6, a.layers,
                  a.refinement, o.mesh.contact_size * 1e6 / a.refinement, a.plane_strain ? 1 : 0,
                  r.nodes, r.elements, run.cpu_seconds, run.wall_seconds, run.runs,
                  r.extrapolated ? 1 : 0, r.moment_balance, r.rotation * 1e6, r.approach * 1e6,
                  r.total_force, r.k_hbeta, r.peak_z * 1e3, r.stiffness_per_width / 1e9,
                  r.middle_stiffness_per_width / 1e9, l, r.z_lo[l] * 1e3, r.z_hi[l] * 1e3,
                  r.z[l] * 1e3, r.line_load[l] / 1e3);
    f << line;
  }
  if (!f) throw std::runtime_error(a.csv + ": write failed");
  std::printf(
      "%s: F_beta %.3g um, %d layers, refinement %.3g: %d nodes, K_Hbeta %.4f, "
      "k %.4f, k_mid %.4f N/(mm um), balance %.1e, ccx %.0f s CPU (%d run%s)\n",
      a.name.c_str(), r.misalignment * 1e6, a.layers, a.refinement, r.nodes, r.k_hbeta,
      r.stiffness_per_width / 1e9, r.middle_stiffness_per_width / 1e9, r.moment_balance,
      run.cpu_seconds, run.runs, run.runs > 1 ? "s" : "");
  return 0;
}

int Fe3dPlot(const std::string& csv, const std::string& svg, int layers, double refinement,
             const std::string& title) {
  using report::LinePlot;
  using report::PlotSeries;
  LinePlot plot{title, "z across the face width [mm]", "load per unit width q [N/mm]", {}, false,
                {}};
  // Each case at the chosen discretisation as a line with markers (the stations' means, drawn
  // at their centres); the other discretisations of the same cases as markers.
  std::map<std::string, PlotSeries> main, other;
  const auto rows = test::ReadCsvRows(csv);
  // The face width of the chosen discretisation's runs: runs of another b are left out.
  std::string width;
  for (const auto& r : rows)
    if (r.size() == 27 && r[7] != "1" && std::stoi(r[4]) == layers &&
        std::stod(r[5]) == refinement && width.empty())
      width = r[2];
  for (const auto& r : rows) {
    if (r.size() != 27 || r[7] == "1" || r[2] != width) continue;
    const bool chosen = std::stoi(r[4]) == layers && std::stod(r[5]) == refinement;
    const std::string key = r[0] + (chosen ? "" : ", " + r[4] + " layers, ref. " + r[5]);
    PlotSeries& s = (chosen ? main : other)[key];
    s.name = chosen ? r[0] + ": F_beta " + r[3] + " um" : key;
    s.markers = chosen;
    s.points = !chosen;
    s.x.push_back(std::stod(r[25]));
    s.y.push_back(std::stod(r[26]));
  }
  if (main.empty())
    throw std::invalid_argument(csv + ": no 3D rows with " + std::to_string(layers) +
                                " layers at refinement " + std::to_string(refinement));
  // One colour per case: its line at the chosen discretisation, its markers at the others.
  std::map<std::string, int> colour_of;
  for (auto& [key, s] : main) {
    const int colour = static_cast<int>(colour_of.size());
    colour_of[key] = colour;
    s.colour = colour;
    plot.series.push_back(s);
  }
  for (auto& [key, s] : other) {
    const auto it = colour_of.find(key.substr(0, key.find(',')));
    s.colour = it == colour_of.end() ? -1 : it->second;
    plot.series.push_back(s);
  }
  plot.x_min = 0;
  plot.x_max = std::stod(width);
  // Uncoupled slices of the aligned face's middle stiffness c′ under each misalignment (dashed):
  // q = c′ (δ − F_β (z/b − 1/2))₊ with δ from SliceApproach.
  double c_mid = 0, force = 0;
  std::map<std::string, double> misalignment_of;
  for (const auto& r : rows) {
    if (r.size() != 27 || r[7] == "1" || r[2] != width || std::stoi(r[4]) != layers ||
        std::stod(r[5]) != refinement)
      continue;
    if (std::stod(r[3]) == 0) c_mid = std::stod(r[21]) * 1e9;
    force = std::stod(r[17]);
    misalignment_of[r[0]] = std::stod(r[3]) * 1e-6;
  }
  const double b = std::stod(width) * 1e-3;
  for (const auto& [name, fbeta] : misalignment_of) {
    if (!(c_mid > 0) || fbeta == 0) continue;
    const double delta = SliceApproach(force, b, c_mid, fbeta);
    PlotSeries s{name + ": uncoupled slices", {}, {}, false};
    s.dashed = true;
    s.colour = colour_of.count(name) ? colour_of[name] : -1;
    for (int i = 0; i <= 200; ++i) {
      const double z = b * i / 200;
      s.x.push_back(z * 1e3);
      s.y.push_back(c_mid * std::max(0.0, delta - fbeta * (z / b - 0.5)) / 1e3);
    }
    plot.series.push_back(s);
  }
  report::WriteTextFile(svg, report::RenderSvg(plot));
  std::printf("wrote %s\n", svg.c_str());
  return 0;
}

int Fe3dSlices(const std::string& scene, const std::string& csv, const std::string& svg,
               int layers, double refinement, double lambda, const std::string& title) {
  using report::PlotSeries;
  transmission::FeComplianceOptions tables;
  tables.cache_directory = transmission::DefaultCacheDirectory();
  const test::Fe3dSlicePair pair(transmission::ReadScene(scene), tables);
  const double b = pair.width(), phi = pair.BodyShare();
  constexpr int kSlices = 40;
  const Eigen::MatrixXd strips =
      transmission::FaceCouplingMatrix(kSlices, b, transmission::FaceCoupling::kNone, 0);
  const Eigen::MatrixXd coupled = transmission::FaceCouplingMatrix(
      kSlices, b, transmission::FaceCoupling::kToothBody, lambda, phi);
  std::printf("body share phi = %.4f, tooth coupling length %.2f mm, C = %.5g m/N\n", phi,
              lambda * 1e3, pair.structural());
  report::LinePlot plot{title, "z across the face width [mm]", "load per unit width q [N/mm]",
                        {}, false, {}};
  int colour = 0;
  for (const auto& [name, f_beta] : {std::pair{"c", 0.0}, std::pair{"a", 20e-6}, std::pair{"b", 80e-6}}) {
    // The 3D stations' means as markers at their centres; the slices as lines.
    PlotSeries ref{std::string(name) + ": 3D stations (dots)", {}, {}, true};
    ref.colour = colour;
    for (const auto& r : test::ReadCsvRows(csv))
      if (r.size() == 27 && r[0] == name && std::stoi(r[4]) == layers &&
          std::stod(r[5]) == refinement && std::stod(r[2]) == b * 1e3) {
        ref.x.push_back(std::stod(r[25]));
        ref.y.push_back(std::stod(r[26]));
      }
    if (ref.x.empty())
      throw std::invalid_argument(csv + ": no case " + name + " with " + std::to_string(layers) +
                                  " layers at refinement " + std::to_string(refinement));
    const test::SliceLoads s = pair.Solve(strips, f_beta), t = pair.Solve(coupled, f_beta);
    PlotSeries line_s{std::string(name) + ": strips (dashed)", {}, {}, false};
    line_s.dashed = true;
    line_s.colour = colour;
    PlotSeries line_t{std::string(name) + ": tooth_body (solid)", {}, {}, false};
    line_t.colour = colour;
    for (int k = 0; k < kSlices; ++k) {
      const double z = (k + 0.5) * b / kSlices * 1e3;
      line_s.x.push_back(z);
      line_s.y.push_back(s.line_load[static_cast<std::size_t>(k)] / 1e3);
      line_t.x.push_back(z);
      line_t.y.push_back(t.line_load[static_cast<std::size_t>(k)] / 1e3);
    }
    const int n = static_cast<int>(ref.x.size());
    const std::vector<double> ss = s.Stations(n), ts = t.Stations(n);
    std::printf("%s (F_beta %.0f um): station, 3D, strips, tooth_body [N/mm]\n", name,
                f_beta * 1e6);
    for (int k = 0; k < n; ++k)
      std::printf("  %5.2f  %7.1f  %7.1f  %7.1f\n", ref.x[static_cast<std::size_t>(k)],
                  ref.y[static_cast<std::size_t>(k)], ss[static_cast<std::size_t>(k)] / 1e3,
                  ts[static_cast<std::size_t>(k)] / 1e3);
    plot.series.push_back(ref);
    plot.series.push_back(line_s);
    plot.series.push_back(line_t);
    ++colour;
  }
  plot.x_min = 0;
  plot.x_max = b * 1e3;
  report::WriteTextFile(svg, report::RenderSvg(plot));
  std::printf("wrote %s\n", svg.c_str());
  return 0;
}

}  // namespace epicycle::fe_reference
