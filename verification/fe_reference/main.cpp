// `fe_reference deck SCENE ...` writes the CalculiX deck of a pair at one position;
// `fe_reference read DIR` reads CalculiX's results back and prints the reference at the scene's
// torque as one CSV row (tools/fe_reference.sh drives both).
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "csv_rows.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "fe3d_tool.hpp"
#include "fe_deck.hpp"

namespace {

using namespace epicycle;

std::vector<double> ParseList(const std::string& text) {
  std::vector<double> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) out.push_back(std::stod(item));
  return out;
}

// --crack "gear,tooth,side,depth_mm,angle_deg[,start_arc_mm]" (start: ISO's 30° point when
// left out) into the deck's crack.
std::optional<fe_reference::FeCrack> ParseCrack(const std::string& text, double tip_size_um,
                                                const geometry::GearPair& pair) {
  if (text.empty()) return std::nullopt;
  const std::vector<double> v = ParseList(text);
  if (v.size() != 5 && v.size() != 6)
    throw std::invalid_argument("--crack '" + text +
                                "': needs gear,tooth,side,depth_mm,angle_deg[,start_arc_mm]");
  fe_reference::FeCrack c;
  c.gear = static_cast<int>(v[0]);
  if (c.gear != 1 && c.gear != 2)
    throw std::invalid_argument("--crack '" + text + "': gear must be 1 or 2");
  const geometry::Gear& gear = c.gear == 1 ? pair.gear1() : pair.gear2();
  c.crack.tooth = static_cast<int>(v[1]);
  c.crack.side = v[2] < 0 ? -1 : 1;
  c.crack.path = {{v[3] * 1e-3, v[4] * geometry::kPi / 180.0}};
  c.crack.start_arc = v.size() == 6 ? v[5] * 1e-3 : compliance::IsoCriticalFilletArc(gear);
  c.tip_size = tip_size_um * 1e-6;
  return c;
}

int Deck(const std::string& scene_path, const std::string& mesh_name, double angle_deg,
         const std::string& rotations_urad, const fe_reference::FeMeshOptions& mesh,
         const fe_reference::FeContactOptions& contact, const std::string& out,
         const std::string& crack, double tip_size_um) {
  const transmission::Scene scene = transmission::ReadScene(scene_path);
  std::optional<geometry::Stage> stage;
  if (scene.kind == transmission::SceneKind::kStage) stage.emplace(scene.stage);
  const transmission::MeshPairSetup setup =
      transmission::MakeMeshPair(scene, stage ? &*stage : nullptr, mesh_name);
  const geometry::GearPair pair(setup.spec);
  std::vector<double> rotations;
  for (double r : ParseList(rotations_urad)) rotations.push_back(r * 1e-6);
  fe_reference::FeDamage damage;
  damage.crack = ParseCrack(crack, tip_size_um, pair);
  damage.spall = fe_reference::SpallOfScene(scene);
  const fe_reference::FeDeckInfo info =
      fe_reference::WriteDeck(scene, pair, setup.torque, angle_deg * geometry::kPi / 180.0,
                              rotations, mesh, contact, out, damage);
  std::printf("%s/deck.inp: %d nodes, %d C3D15 (gmsh: %d nodes, %d triangles), %zu tooth pairs\n",
              out.c_str(), info.nodes, info.elements, info.nodes_2d, info.triangles,
              info.pairs.size());
  if (damage.crack)
    std::printf(
        "crack: gear %d tooth %d side %+d, start arc %.5f mm, q %.5f mm, nu %.3f deg, "
        "%d nodes duplicated\n",
        damage.crack->gear, damage.crack->crack.tooth, damage.crack->crack.side,
        damage.crack->crack.start_arc * 1e3, damage.crack->crack.depth() * 1e3,
        damage.crack->crack.path.front().angle * 180.0 / geometry::kPi, info.crack_nodes);
  if (damage.spall)
    std::printf("spall: gear %d tooth %d side %+d, roll %.4f..%.4f deg, depth %.3f um\n",
                damage.spall->gear, damage.spall->tooth, damage.spall->side,
                damage.spall->roll_from * 180.0 / geometry::kPi,
                damage.spall->roll_to * 180.0 / geometry::kPi, damage.spall->depth * 1e6);
  return 0;
}

// ISO 6336-3's critical fillet point of both gears: its arc length from the space centre line and
// the root chord s_Fn between the two teeth's sides' points [mm].
int Chord(const std::string& scene_path, const std::string& mesh_name) {
  const transmission::Scene scene = transmission::ReadScene(scene_path);
  std::optional<geometry::Stage> stage;
  if (scene.kind == transmission::SceneKind::kStage) stage.emplace(scene.stage);
  const geometry::GearPair pair(
      transmission::MakeMeshPair(scene, stage ? &*stage : nullptr, mesh_name).spec);
  std::printf("gear,iso_arc_mm,s_Fn_mm,loaded_side\n");
  for (int g : {1, 2}) {
    const geometry::Gear& gear = g == 1 ? pair.gear1() : pair.gear2();
    std::printf("%d,%.6f,%.6f,%d\n", g, compliance::IsoCriticalFilletArc(gear) * 1e3,
                fe_reference::IsoRootChord(gear) * 1e3, pair.loaded_side());
  }
  return 0;
}

int Read(const std::string& dir) {
  const fe_reference::FeDeckInfo info = fe_reference::FeDeckInfo::Read(dir + "/deck.info");
  const std::vector<fe_reference::FeStepResult> steps = fe_reference::ReadSteps(dir, info);
  const fe_reference::FeSample s = fe_reference::Interpolate(info, steps);
  const double b_mm = info.face_width * 1e3;
  // angle, rotation, approach, k, Σ F, extrapolated, moment balance, then per pair
  // teeth, force, share.
  std::printf("%.6f,%.9g,%.9g,%.9g,%.9g,%d,%.3e", geometry::Deg(s.angle), s.rotation * 1e6,
              s.approach * 1e6, s.mesh_stiffness / b_mm / 1e6, s.force_sum, s.extrapolated ? 1 : 0,
              s.moment_balance);
  for (std::size_t j = 0; j < info.pairs.size(); ++j)
    std::printf(",%d/%d,%.9g,%.9g", info.pairs[j].tooth1, info.pairs[j].tooth2, s.pair_force[j],
                s.force_sum > 0 ? s.pair_force[j] / s.force_sum : 0.0);
  std::printf("\n");
  return 0;
}

// Per tooth of the fillet nodes of deck.info: gear, tooth, the largest tension [MPa], its side σ
// and arc length from the space centre line [mm], the same of the most negative compression.
int Fillets(const std::string& dir) {
  const fe_reference::FeDeckInfo info = fe_reference::FeDeckInfo::Read(dir + "/deck.info");
  const fe_reference::FeSample s =
      fe_reference::Interpolate(info, fe_reference::ReadSteps(dir, info));
  for (const fe_reference::FeToothFillet& t :
       fe_reference::FilletExtremes(info, s, fe_reference::ReadFilletStresses(dir, info)))
    std::printf("%d,%d,%.6g,%d,%.5f,%.6g,%d,%.5f\n", t.gear, t.tooth, t.tension / 1e6,
                t.tension_side, t.tension_arc * 1e3, t.compression / 1e6, t.compression_side,
                t.compression_arc * 1e3);
  return 0;
}

// Figures of docs/fe_reference.md: the hybrid model over its grid (lines) and the FE reference
// (markers, one series per refinement): mesh stiffness, transmission error, tooth-pair shares.
int Plot(const std::string& hybrid_csv, const std::string& fe_csv, const std::string& prefix,
         const std::string& title) {
  using report::LinePlot;
  using report::PlotSeries;
  LinePlot k{title + ": mesh stiffness", "gear-1 angle [deg]", "k / b [N/(mm um)]", {}, false, {}};
  LinePlot te{title + ": loaded transmission error",
              "gear-1 angle [deg]",
              "gear-1 rotation [urad]",
              {},
              false,
              {}};
  LinePlot share{title + ": load share of each tooth pair",
                 "gear-1 angle [deg]",
                 "F_j / sum F",
                 {},
                 false,
                 {}};
  PlotSeries hk{"hybrid model", {}, {}, false}, hte{"hybrid model", {}, {}, false};
  std::map<std::string, PlotSeries> hshare, fshare;
  std::string last;
  for (const auto& r : test::ReadCsvRows(hybrid_csv)) {
    if (r.size() < 13 || r[1] != "1") continue;
    const double a = std::stod(r[0]);
    if (r[0] != last) {
      hk.x.push_back(a);
      hk.y.push_back(std::stod(r[3]));
      hte.x.push_back(a);
      hte.y.push_back(std::abs(std::stod(r[4])));
      last = r[0];
    }
    PlotSeries& p = hshare[r[8]];
    p.name = "hybrid, pair " + r[8];
    p.x.push_back(a);
    p.y.push_back(std::stod(r[12]));
  }
  std::map<std::string, PlotSeries> fk, fte;
  std::map<std::string, std::string> seen;
  for (const auto& r : test::ReadCsvRows(fe_csv)) {
    if (r.size() < 18) continue;
    const std::string level = "FE, refinement " + r[2] + ", K " + r[3];
    const double a = std::stod(r[1]);
    if (seen[level] != r[0]) {
      fk[level].x.push_back(a);
      fk[level].y.push_back(std::stod(r[12]));
      fte[level].x.push_back(a);
      fte[level].y.push_back(std::abs(std::stod(r[10])));
      seen[level] = r[0];
    }
    if (r[2] != "1" || std::stod(r[16]) <= 0) continue;
    PlotSeries& p = fshare[r[14]];
    p.name = "FE, pair " + r[14];
    p.points = true;
    p.x.push_back(a);
    p.y.push_back(std::stod(r[16]));
  }
  k.series.push_back(hk);
  te.series.push_back(hte);
  for (auto& [name, s] : fk) {
    s.name = name;
    s.points = true;
    k.series.push_back(s);
  }
  for (auto& [name, s] : fte) {
    s.name = name;
    s.points = true;
    te.series.push_back(s);
  }
  for (auto& [teeth, s] : hshare) share.series.push_back(s);
  for (auto& [teeth, s] : fshare) share.series.push_back(s);
  report::WriteTextFile(prefix + "_stiffness.svg", report::RenderSvg(k));
  report::WriteTextFile(prefix + "_te.svg", report::RenderSvg(te));
  report::WriteTextFile(prefix + "_share.svg", report::RenderSvg(share));
  std::printf("wrote %s_{stiffness,te,share}.svg\n", prefix.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"FE contact reference of a gear pair (CalculiX deck writer and result reader)"};
  app.require_subcommand(1);
  std::string scene, mesh_name, rotations, out = "fe-out", dir;
  double angle_deg = 0;
  fe_reference::FeMeshOptions mesh;
  fe_reference::FeContactOptions contact;
  double contact_size_um = mesh.contact_size * 1e6;
  CLI::App* deck = app.add_subcommand("deck", "write deck.inp and deck.info");
  deck->add_option("scene", scene, "scene file")->required();
  deck->add_option("--mesh", mesh_name, "a stage scene's mesh (sun-planet1, planet1-ring)");
  deck->add_option("--angle-deg", angle_deg, "gear-1 angle from the cycle start [deg]")->required();
  deck->add_option("--rotations-urad", rotations, "gear-1 rotation of each step [urad], a,b,...")
      ->required();
  deck->add_option("--refinement", mesh.refinement, "divides every mesh size");
  deck->add_option("--contact-size-um", contact_size_um, "element size at the contacts [um]");
  deck->add_option("--penalty", contact.penalty, "contact penalty [MPa/mm]");
  deck->add_option("--fillet-size-per-module", mesh.fillet_size_per_module,
                   "element size on the read fillets per module [-]");
  deck->add_option("--out", out, "output directory");
  std::string crack;
  double tip_size_um = 10.0;
  deck->add_option("--crack", crack,
                   "root crack gear,tooth,side,depth_mm,angle_deg[,start_arc_mm] (start: ISO's "
                   "30 deg point); a pit of the scene is meshed as a spall");
  deck->add_option("--crack-tip-size-um", tip_size_um, "element size at the crack tip [um]");
  CLI::App* chord = app.add_subcommand("chord", "ISO 30-deg fillet points and s_Fn of both gears");
  chord->add_option("scene", scene, "scene file")->required();
  chord->add_option("--mesh", mesh_name, "a stage scene's mesh");
  CLI::App* read = app.add_subcommand("read", "read DIR/deck.dat, print the reference CSV row");
  read->add_option("dir", dir, "directory of deck.inp")->required();
  CLI::App* fillets =
      app.add_subcommand("fillets", "read DIR/deck.frd, print each read tooth's fillet stresses");
  fillets->add_option("dir", dir, "directory of deck.inp")->required();
  std::string hybrid_csv, fe_csv, prefix, title;
  CLI::App* plot = app.add_subcommand("plot", "figures: hybrid model against the FE reference");
  plot->add_option("hybrid", hybrid_csv, "the hybrid model's stiffness CSV")->required();
  plot->add_option("fe", fe_csv, "fe_reference.csv of tools/fe_reference.sh")->required();
  plot->add_option("prefix", prefix, "output path prefix")->required();
  plot->add_option("--title", title, "figure title");
  fe_reference::Fe3dCommandArgs f3;
  CLI::App* fe3d = app.add_subcommand(
      "fe3d", "3D reference across the face width: run one case, append its stations to --csv");
  fe3d->add_option("scene", f3.scene, "pair scene file")->required();
  fe3d->add_option("--name", f3.name, "case name in the CSV");
  fe3d->add_option("--angle-deg", f3.angle_deg, "gear-1 angle from the cycle start [deg]");
  fe3d->add_option("--misalignment-um", f3.misalignment_um,
                   "F_beta: the rigid gap's change from z = 0 to z = b [um]");
  fe3d->add_option("--face-width-mm", f3.face_width_mm,
                   "b [mm] (0: the pair's); the torque scales with b");
  fe3d->add_option("--layers", f3.layers, "wedge layers (axial stations) over b");
  fe3d->add_option("--refinement", f3.refinement, "divides every in-plane mesh size");
  fe3d->add_flag("--plane-strain", f3.plane_strain, "one layer with u_z = 0: plane strain");
  fe3d->add_option("--axial-support", f3.axial_support,
                   "what holds the gears axially: hubs, mid-plane (and u_z = 0 at mid-face inside "
                   "the root circles) or body (u_z = 0 inside the root circles)")
      ->check(CLI::IsMember({"hubs", "mid-plane", "body"}));
  fe3d->add_option("--step-scales", f3.step_scales,
                   "the static steps as multiples of the estimated rotation (two or more, rising)");
  fe3d->add_option("--plane-k", f3.plane_k,
                   "plane model's stiffness per width for the steps' estimate [N/(mm um)]");
  fe3d->add_option("--threads", f3.threads, "ccx threads");
  fe3d->add_option("--tooth-size-per-module", f3.tooth_size_per_module,
                   "in-plane element size on the modelled teeth per module (0: default)");
  fe3d->add_flag("--deck-only", f3.deck_only, "write the deck and stop");
  fe3d->add_flag("--influence", f3.influence,
                 "the structural compliance along the face: unit loads per layer, no contact");
  fe3d->add_option("--body-size-per-module", f3.body_size_per_module,
                   "largest in-plane element size per module (0: default)");
  fe3d->add_option("--sector-teeth", f3.sector_teeth, "teeth modelled either side of the loaded");
  fe3d->add_option("--tooth-zone", f3.tooth_zone, "teeth either side at the tooth size");
  fe3d->add_option("--grading", f3.grading,
                   "growth of the in-plane size with distance (0: default)");
  fe3d->add_option("--contact-size-um", f3.contact_size_um, "in-plane size at the contact [um]");
  fe3d->add_option("--ccx", f3.ccx, "CalculiX program");
  fe3d->add_option("--out", f3.out, "work directory");
  fe3d->add_option("--csv", f3.csv, "CSV to append to");
  int plot_layers = 10;
  double plot_refinement = 1;
  CLI::App* fe3d_plot =
      app.add_subcommand("fe3d-plot", "figure: load per unit width across the face");
  fe3d_plot->add_option("csv", fe_csv, "CSV of fe3d runs")->required();
  fe3d_plot->add_option("svg", prefix, "output SVG")->required();
  fe3d_plot->add_option("--layers", plot_layers, "the discretisation drawn as lines");
  fe3d_plot->add_option("--refinement", plot_refinement, "the discretisation drawn as lines");
  fe3d_plot->add_option("--title", title, "figure title");
  std::string slices_scene;
  std::string influence_csv;
  int influence_layers = 8;
  std::vector<std::string> influence_cases{"free"};
  std::string influence_refinement = "1";
  std::string kernel_csv;
  int slices_layers = 4;
  double slices_refinement = 1.41;
  CLI::App* fe3d_slices = app.add_subcommand(
      "fe3d-slices", "figure: the slice model (strips, tooth_body) against the 3D stations");
  fe3d_slices->add_option("scene", slices_scene, "the pair scene")->required();
  fe3d_slices->add_option("csv", fe_csv, "CSV of fe3d runs")->required();
  fe3d_slices->add_option("svg", prefix, "output SVG")->required();
  fe3d_slices->add_option("--layers", slices_layers, "the 3D discretisation compared");
  fe3d_slices->add_option("--refinement", slices_refinement, "the 3D discretisation compared");
  fe3d_slices->add_option("--influence", influence_csv,
                          "CSV of `fe3d --influence` runs: the 3D structure's kernel");
  fe3d_slices->add_option("--influence-case", influence_cases, "the influence cases drawn");
  fe3d_slices->add_option("--write-kernel", kernel_csv,
                          "write the first influence case's W as a scene's coupling table");
  fe3d_slices->add_option("--influence-refinement", influence_refinement,
                          "the influence runs' in-plane refinement, as written in the CSV");
  fe3d_slices->add_option("--influence-layers", influence_layers,
                          "the influence run's layers (one slice each)");
  fe3d_slices->add_option("--title", title, "figure title");
  std::string kernel_influence, kernel_case = "free", kernel_refinement = "1", kernel_out;
  int kernel_layers = 10;
  CLI::App* fe3d_kernel = app.add_subcommand(
      "fe3d-kernel", "the 3D structure's kernel W of `fe3d --influence` rows as a coupling table");
  fe3d_kernel->add_option("influence", kernel_influence, "CSV of `fe3d --influence` runs")
      ->required();
  fe3d_kernel->add_option("kernel", kernel_out, "the coupling table (CSV i,j,w) to write")
      ->required();
  fe3d_kernel->add_option("--case", kernel_case, "the influence case (its plane_strain row too)");
  fe3d_kernel->add_option("--layers", kernel_layers, "the influence run's layers (one slice each)");
  fe3d_kernel->add_option("--refinement", kernel_refinement,
                          "the influence run's in-plane refinement, as written in the CSV");
  std::string helical_scene;
  std::vector<std::string> helical_cases{"helical"};
  double helical_angle = 13.0;
  int helical_positions = 18, helical_layers = 4;
  CLI::App* fe3d_helical = app.add_subcommand(
      "fe3d-helical", "figure: the helical pair's slices against its 3D stations");
  fe3d_helical->add_option("scene", helical_scene, "the helical pair scene")->required();
  fe3d_helical->add_option("csv", fe_csv, "CSV of fe3d runs of the helical deck")->required();
  fe3d_helical->add_option("svg", prefix, "output SVG")->required();
  fe3d_helical->add_option("--case", helical_cases, "the runs' case names in the CSV");
  fe3d_helical->add_option("--angle-deg", helical_angle, "gear-1 angle of the runs [deg]");
  fe3d_helical->add_option("--positions", helical_positions,
                           "positions of the slices' sweep (the angle one of them)");
  fe3d_helical->add_option("--layers", helical_layers, "the 3D stations compared");
  fe3d_helical->add_option("--title", title, "figure title");
  try {
    app.parse(argc, argv);
    if (*plot) return Plot(hybrid_csv, fe_csv, prefix, title);
    if (*fe3d_helical)
      return fe_reference::Fe3dHelical(helical_scene, fe_csv, prefix, helical_cases, helical_angle,
                                       helical_positions, helical_layers, title);
    if (*fe3d_kernel)
      return fe_reference::Fe3dKernel(kernel_influence, kernel_case, kernel_layers,
                                      kernel_refinement, kernel_out);
    if (*fe3d_slices)
      return fe_reference::Fe3dSlices(slices_scene, fe_csv, prefix, slices_layers,
                                      slices_refinement, influence_csv, influence_layers,
                                      influence_refinement, influence_cases, kernel_csv,
                                      title);
    if (*fe3d) return fe_reference::Fe3dCommand(f3);
    if (*fe3d_plot)
      return fe_reference::Fe3dPlot(fe_csv, prefix, plot_layers, plot_refinement, title);
    mesh.contact_size = contact_size_um * 1e-6;
    if (*deck)
      return Deck(scene, mesh_name, angle_deg, rotations, mesh, contact, out, crack, tip_size_um);
    if (*chord) return Chord(scene, mesh_name);
    if (*fillets) return Fillets(dir);
    return Read(dir);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message; its own codes (105 for a value not in a set, ...) become 2 for
    // bad usage, help stays 0 (the program's rule).
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const std::invalid_argument& e) {  // bad input: exit 2
    std::fprintf(stderr, "fe_reference: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fe_reference: %s\n", e.what());
    return 1;
  }
}
