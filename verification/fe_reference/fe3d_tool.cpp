// `fe_reference fe3d`, `fe3d-plot` and `fe3d-slices` (docs/fe_reference.md, "3D reference across
// the face width"): one 3D run appended to a CSV, one row per axial station; the figure of the
// load per unit width across the face; the slice model against it (docs/face_width.md).
#include "fe3d_tool.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "csv_rows.hpp"
#include "epicycle/transmission/face_width.hpp"
#include "fe3d_helical.hpp"
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

constexpr const char* kInfluenceHeader =
    "case,angle_deg,face_width_mm,layers,refinement,plane_strain,nodes,ccx_cpu_s,depth1_um,"
    "depth2_um,i,j,z_i_mm,z_j_mm,compliance_m_per_N";

// The influence deck's run (Fe3dCommandArgs::influence), read at the plane model's joining
// depths of the scene's pair, its G_ij appended to a.csv.
int Fe3dInfluenceCommand(const Fe3dCommandArgs& a, const transmission::Scene& scene,
                         const geometry::GearPair& pair, Fe3dOptions o) {
  transmission::FeComplianceOptions tables;
  tables.cache_directory = transmission::DefaultCacheDirectory();
  // The plane model's FE tables of the scene's pair (any pair: external or internal).
  const transmission::FePairCompliance model(scene, pair, tables);
  o.influence = true;
  o.read_depth[0] = model.JoiningDepth(0);
  o.read_depth[1] = model.JoiningDepth(1);
  const Fe3dInfluenceRun run =
      RunFe3dInfluence(scene, pair, a.angle_deg * geometry::kPi / 180.0, o, a.out, a.ccx,
                       a.threads);
  const bool fresh = !std::filesystem::exists(a.csv);
  std::ofstream f(a.csv, std::ios::app);
  if (!f) throw std::runtime_error(a.csv + ": cannot be written");
  if (fresh) f << kInfluenceHeader << "\n";
  const std::vector<double>& z = run.deck.z_edges;
  const std::size_t n = run.compliance.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      char line[512];
      std::snprintf(line, sizeof line,
                    "%s,%.6f,%.6g,%d,%.6g,%d,%d,%.2f,%.6g,%.6g,%zu,%zu,%.6g,%.6g,%.9e\n",
                    a.name.c_str(), a.angle_deg, (z.back() - z.front()) * 1e3, a.layers,
                    a.refinement, a.plane_strain ? 1 : 0, run.deck.deck.nodes, run.cpu_seconds,
                    o.read_depth[0] * 1e6, o.read_depth[1] * 1e6, i, j,
                    0.5 * (z[i] + z[i + 1]) * 1e3, 0.5 * (z[j] + z[j + 1]) * 1e3,
                    run.compliance[i][j]);
      f << line;
    }
  if (!f) throw std::runtime_error(a.csv + ": write failed");
  // The plane model's structural C at the loaded contact (whole gears and the layer term,
  // docs/model.md §4), for the one-layer plane-strain deck's G_ps to be compared with.
  const geometry::PairPoses poses = pair.Poses(a.angle_deg * geometry::kPi / 180.0);
  geometry::ContactSearchOptions search;
  search.gap_window = o.contact.gap_window;
  search.both_sides = false;  // the loaded flanks, as the deck's (WriteDeck3d)
  search.side_a = pair.loaded_side();
  std::vector<geometry::PotentialContact> nearest;
  for (const geometry::PotentialContact& c : pair.Contacts(poses, search))
    if (nearest.empty() || c.overlap > nearest[0].overlap) nearest = {c};
  const double plane_c = nearest.empty() ? 0.0 : model.Matrix(pair, poses, nearest)(0, 0);
  std::printf(
      "%s: influence, %d layers, refinement %.3g%s: %d nodes, h %.1f/%.1f um, "
      "G_00 %.6e m/N (plane model's C at the contact %.6e m/N), ccx %.0f s CPU, "
      "%.0f s wall\n",
      a.name.c_str(), a.layers, a.refinement, a.plane_strain ? ", plane strain" : "",
      run.deck.deck.nodes, o.read_depth[0] * 1e6, o.read_depth[1] * 1e6, run.compliance[0][0],
      plane_c, run.cpu_seconds, run.wall_seconds);
  return 0;
}

// W as a scene's coupling table (docs/scenes.md, "Face width"): a header, then "i,j,w" rows.
void WriteKernel(const Eigen::MatrixXd& w, const std::string& path) {
  std::string text = "i,j,w\n";
  for (Eigen::Index i = 0; i < w.rows(); ++i)
    for (Eigen::Index j = 0; j < w.cols(); ++j) {
      char line[96];
      std::snprintf(line, sizeof line, "%td,%td,%.12g\n", i, j, w(i, j));
      text += line;
    }
  report::WriteTextFile(path, text);
  std::printf("wrote %s\n", path.c_str());
}

}  // namespace

int Fe3dKernel(const std::string& influence_csv, const std::string& name, int layers,
               const std::string& refinement, const std::string& kernel_csv) {
  if (layers < 2)
    throw std::invalid_argument("--layers = " + std::to_string(layers) +
                                ": a kernel along the face needs at least 2 layers");
  const Eigen::MatrixXd w = test::StructureKernel(influence_csv, name, layers, refinement);
  // The rows as the docs' tables give them: W_ij and Σ_j W_ij / S (1 for plane strain).
  std::printf("%s, %d layers, refinement %s: W_ij (symmetric part), row sum / S\n", name.c_str(),
              layers, refinement.c_str());
  for (Eigen::Index i = 0; i < w.rows(); ++i) {
    std::printf("  %2td:", i);
    for (Eigen::Index j = 0; j < w.cols(); ++j) std::printf(" %.3f", w(i, j));
    std::printf("  | %.4f\n", w.row(i).sum() / layers);
  }
  if (Eigen::LLT<Eigen::MatrixXd>(w).info() != Eigen::Success)
    throw std::runtime_error(influence_csv + ": case " + name + "'s W is not positive definite");
  WriteKernel(w, kernel_csv);
  return 0;
}

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
  o.axial_support = a.axial_support == "body"        ? AxialSupport::kBody
                    : a.axial_support == "mid-plane" ? AxialSupport::kBodyMidPlane
                                                     : AxialSupport::kHubs;
  o.mesh.refinement = a.refinement;
  if (a.tooth_size_per_module > 0) o.mesh.tooth_size_per_module = a.tooth_size_per_module;
  if (a.body_size_per_module > 0) o.mesh.body_size_per_module = a.body_size_per_module;
  if (a.grading > 0) o.mesh.grading = a.grading;
  if (a.sector_teeth >= 0) o.sector_teeth = a.sector_teeth;
  if (a.tooth_zone >= 0) o.mesh.tooth_zone = a.tooth_zone;
  if (a.contact_size_um > 0) o.mesh.contact_size = a.contact_size_um * 1e-6;
  if (a.influence) return Fe3dInfluenceCommand(a, scene, pair, o);
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
                              a.plane_k * 1e9, o, a.out, a.ccx, a.threads, a.step_scales);
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
  if (o.axial_support != AxialSupport::kHubs)
    std::printf("%s: axial reactions of the held nodes at T: gear 1 %.2f N, gear 2 %.2f N\n",
                a.name.c_str(), r.axial_reaction[0], r.axial_reaction[1]);
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
               int layers, double refinement, const std::string& influence_csv,
               int influence_layers, const std::string& influence_refinement,
               const std::vector<std::string>& influence_cases, const std::string& kernel_csv,
               const std::string& title) {
  using report::PlotSeries;
  transmission::FeComplianceOptions tables;
  tables.cache_directory = transmission::DefaultCacheDirectory();
  const test::Fe3dSlicePair pair(transmission::ReadScene(scene), tables);
  const double b = pair.width();
  constexpr int kSlices = 40;
  struct Kernel {
    std::string name;
    Eigen::MatrixXd w;
    bool dashed, drawn;
  };
  // Strips, the tooth_body kernel of the plane FE's body share φ (printed only) and the 3D
  // structure's kernels.
  const double phi = pair.BodyShare();
  std::vector<Kernel> kernels{
      {"strips", transmission::FaceCouplingMatrix(kSlices, b, transmission::FaceCoupling::kNone, 0),
       true, true},
      {"tooth_body", transmission::FaceCouplingMatrix(
                         kSlices, b, transmission::FaceCoupling::kToothBody, 0, phi),
       false, false}};
  if (!influence_csv.empty()) {
    for (const std::string& name : influence_cases)
      kernels.push_back({name == "free" ? std::string("3D kernel") : name,
                         test::StructureKernel(influence_csv, name, influence_layers,
                                               influence_refinement),
                         false, true});
  }
  std::printf("C = %.5g m/N, body share phi = %.4f\n", pair.structural(), phi);
  if (!kernel_csv.empty()) {
    // The first influence case's W as a scene's coupling table (docs/scenes.md, "Face width").
    if (kernels.size() < 3)
      throw std::invalid_argument("--write-kernel " + kernel_csv + ": needs --influence");
    WriteKernel(kernels[2].w, kernel_csv);
  }
  report::LinePlot plot{title, "z across the face width [mm]", "load per unit width q [N/mm]",
                        {}, false, {}};
  int colour = 0;
  for (const auto& [name, f_beta] :
       {std::pair{"c", 0.0}, std::pair{"a", 20e-6}, std::pair{"b", 80e-6}}) {
    // The 3D stations' means as markers at their centres; the slices as lines.
    PlotSeries ref{std::string(name) + ": 3D contact (dots)", {}, {}, true};
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
    plot.series.push_back(ref);
    const int n = static_cast<int>(ref.x.size());
    std::printf("%s (F_beta %.0f um): station z [mm], 3D", name, f_beta * 1e6);
    for (const Kernel& k : kernels) std::printf(", %s", k.name.c_str());
    std::printf(" [N/mm]\n");
    std::vector<std::vector<double>> stations;
    for (const Kernel& k : kernels) {
      const test::SliceLoads loads = pair.Solve(k.w, f_beta);
      const int slices = static_cast<int>(k.w.rows());
      PlotSeries line{std::string(name) + ": " + k.name + (k.dashed ? " (dashed)" : " (solid)"),
                      {}, {}, false};
      line.dashed = k.dashed;
      line.colour = colour;
      for (int s = 0; s < slices; ++s) {
        line.x.push_back((s + 0.5) * b / slices * 1e3);
        line.y.push_back(loads.line_load[static_cast<std::size_t>(s)] / 1e3);
      }
      if (k.drawn) plot.series.push_back(line);
      stations.push_back(loads.Stations(n));
    }
    for (int s = 0; s < n; ++s) {
      std::printf("  %5.2f  %7.1f", ref.x[static_cast<std::size_t>(s)],
                  ref.y[static_cast<std::size_t>(s)]);
      for (const auto& st : stations) std::printf("  %7.1f", st[static_cast<std::size_t>(s)] / 1e3);
      std::printf("\n");
    }
    ++colour;
  }
  plot.x_min = 0;
  plot.x_max = b * 1e3;
  report::WriteTextFile(svg, report::RenderSvg(plot));
  std::printf("wrote %s\n", svg.c_str());
  return 0;
}

int Fe3dHelical(const std::string& scene, const std::string& csv, const std::string& svg,
                const std::vector<std::string>& names, double angle_deg, int positions, int layers,
                const std::string& title) {
  using report::PlotSeries;
  transmission::FeComplianceOptions tables;
  tables.cache_directory = transmission::DefaultCacheDirectory();
  const test::HelicalSliceSample model =
      test::HelicalSlicesAt(transmission::ReadScene(scene), tables, angle_deg, positions);
  const double b_mm = model.width * 1e3;
  report::LinePlot plot{title, "z across the face width [mm]",
                        "load per unit length of contact line [N/mm]", {}, false, {}};
  // The 3D runs of the case, one series per (layers, refinement): the stations' means at their
  // centres, as markers (lines for the runs at `layers` stations).
  std::map<std::string, PlotSeries> runs;
  for (const auto& r : test::ReadCsvRows(csv)) {
    if (r.size() != 27 || std::find(names.begin(), names.end(), r[0]) == names.end() ||
        std::abs(std::stod(r[1]) - angle_deg) > 1e-9 || std::abs(std::stod(r[2]) - b_mm) > 1e-9)
      continue;
    const std::string key = r[0] + ", " + r[4] + " layers, refinement " + r[5];
    PlotSeries& s = runs[key];
    s.name = r[0] + " " + r[4] + "x" + r[5];
    s.markers = std::stoi(r[4]) == layers;
    s.points = !s.markers;
    s.x.push_back(std::stod(r[25]));
    s.y.push_back(std::stod(r[26]));
  }
  if (runs.empty())
    throw std::invalid_argument(csv + ": none of the cases at " + std::to_string(angle_deg) +
                                " deg on b = " + std::to_string(b_mm) + " mm");
  int colour = 0;
  for (auto& [key, s] : runs) {
    s.colour = colour++;
    plot.series.push_back(s);
    std::printf("3D %s:", key.c_str());
    for (double q : s.y) std::printf(" %.1f", q);
    std::printf(" N/mm\n");
  }
  const int slices = static_cast<int>(model.line_load.size());
  PlotSeries line{std::to_string(slices) + " slices", {}, {}, false};
  line.colour = colour;
  for (int s = 0; s < slices; ++s) {
    line.x.push_back((s + 0.5) * b_mm / slices);
    line.y.push_back(model.line_load[static_cast<std::size_t>(s)] / 1e3);
  }
  plot.series.push_back(line);
  std::printf("slices, %d-station means:", layers);
  for (double q : model.Stations(layers)) std::printf(" %.1f", q / 1e3);
  std::printf(" N/mm; mean k' %.4f N/(mm um)\n",
              model.force / model.width / model.approach / 1e9);
  plot.x_min = 0;
  plot.x_max = b_mm;
  report::WriteTextFile(svg, report::RenderSvg(plot));
  std::printf("wrote %s\n", svg.c_str());
  return 0;
}

}  // namespace epicycle::fe_reference
