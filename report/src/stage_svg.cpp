#include "epicycle/report/stage_svg.hpp"

#include <stdexcept>

#include <fmt/format.h>

namespace epicycle::report {

using geometry::Vec2;

namespace {

// SVG's y axis points down: flip y so that the drawing is counter-clockwise positive.
std::string Path(const std::vector<Vec2>& pts, const geometry::GearPose& pose) {
  std::string d;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec2 p = pose.geometric_centre + geometry::Rotate(pts[i], pose.rotation);
    d += fmt::format("{}{:.4f},{:.4f} ", i == 0 ? "M" : "L", p.x() * 1e3, -p.y() * 1e3);
  }
  return d + "Z";
}

std::string Circle(const Vec2& c, double r, const std::string& style) {
  return fmt::format("<circle cx=\"{:.4f}\" cy=\"{:.4f}\" r=\"{:.4f}\" {}/>\n", c.x() * 1e3,
                     -c.y() * 1e3, r * 1e3, style);
}

std::string Line(const Vec2& a, const Vec2& b, const std::string& style) {
  return fmt::format("<line x1=\"{:.4f}\" y1=\"{:.4f}\" x2=\"{:.4f}\" y2=\"{:.4f}\" {}/>\n",
                     a.x() * 1e3, -a.y() * 1e3, b.x() * 1e3, -b.y() * 1e3, style);
}

}  // namespace

std::string DrawStage(const geometry::Stage& stage, double carrier_angle, double gap_window) {
  const geometry::StagePoses poses = stage.Poses(carrier_angle);
  const double half = stage.ring().spec().hub_radius * 1e3 * 1.05;
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{0} {0} {1} {1}\" width=\"900\" "
      "height=\"900\">\n<rect x=\"{0}\" y=\"{0}\" width=\"{1}\" height=\"{1}\" fill=\"white\"/>\n",
      -half, 2 * half);
  s += fmt::format("<title>epicycle stage at carrier angle {:.3f} deg</title>\n",
                   geometry::Deg(carrier_angle));
  const std::string gear_style = "fill=\"#dde6f0\" stroke=\"#234\" stroke-width=\"0.08\"";
  s += Circle(poses.ring.geometric_centre, stage.ring().spec().hub_radius,
              "fill=\"#e8e8e8\" stroke=\"#234\" stroke-width=\"0.1\"");
  s += "<path fill=\"white\" stroke=\"#234\" stroke-width=\"0.08\" d=\"" +
       Path(stage.ring().Outline(8), poses.ring) + "\"/>\n";
  s += "<path " + gear_style + " d=\"" + Path(stage.sun().Outline(8), poses.sun) + "\"/>\n";
  for (int i = 0; i < stage.planets(); ++i) {
    s += "<path " + gear_style + " d=\"" + Path(stage.planet(i).Outline(8), poses.planets[i]) +
         "\"/>\n";
    s += Circle(poses.planets[i].rotation_centre, stage.planet(i).spec().hub_radius,
                "fill=\"white\" stroke=\"#234\" stroke-width=\"0.08\"");
  }
  s += Circle(Vec2::Zero(), stage.sun().spec().hub_radius,
              "fill=\"white\" stroke=\"#234\" stroke-width=\"0.08\"");
  const std::string base_style =
      "fill=\"none\" stroke=\"#888\" stroke-width=\"0.05\" stroke-dasharray=\"0.6,0.4\"";
  s += Circle(poses.sun.geometric_centre, stage.sun().base_radius(), base_style);
  s += Circle(poses.ring.geometric_centre, stage.ring().base_radius(), base_style);
  geometry::ContactSearchOptions opt;
  opt.gap_window = gap_window;
  for (int i = 0; i < stage.planets(); ++i) {
    s += Circle(poses.planets[i].geometric_centre, stage.planet(i).base_radius(), base_style);
    const geometry::LineOfAction ls = geometry::MakeLineOfAction(
        stage.Sun(poses), stage.Planet(poses, i), false, stage.sun_mesh_side());
    s += Line(ls.tangent_a, ls.tangent_b, "stroke=\"#c33\" stroke-width=\"0.12\"");
    const geometry::LineOfAction lr = geometry::MakeLineOfAction(
        stage.Planet(poses, i), stage.Ring(poses), true, stage.ring_mesh_planet_side());
    s += Line(lr.tangent_a, lr.tangent_b, "stroke=\"#c33\" stroke-width=\"0.12\"");
    for (geometry::MeshKind kind :
         {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
      for (const geometry::PotentialContact& c : stage.Contacts(poses, i, kind, opt)) {
        const char* colour = c.kind == geometry::ContactKind::kInvolute ? "#0a0" : "#f80";
        s += Circle(c.point, 0.45e-3,
                    fmt::format("fill=\"{}\" fill-opacity=\"{}\"", colour,
                                c.overlap >= -1e-6 ? 1.0 : 0.35));
      }
    }
  }
  s += fmt::format(
      "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"5\" font-family=\"sans-serif\">carrier {:.2f} "
      "deg; "
      "red: loaded lines of action; dots: potential contacts (green on the LOA, orange tip round; "
      "faint: open)</text>\n",
      -half * 0.97, half * 0.97, geometry::Deg(carrier_angle));
  return s + "</svg>\n";
}

namespace {

// The relieved flanks of the teeth of g inside the window (centre c, half-width w), offset into
// the tooth by relief × scale, as polylines.
std::string ReliefPaths(const geometry::PosedGear& g, const Vec2& c, double w, double scale) {
  if (!g.gear->has_relief()) return "";
  std::string s;
  const geometry::InvoluteFlank& f = g.gear->involute();
  for (int k = 0; k < g.gear->teeth(); ++k) {
    for (int side : {1, -1}) {
      const geometry::WorldInvolute wi = geometry::FlankInWorld(g, k, side);
      std::string d;
      bool inside = false;
      for (int i = 0; i <= 80; ++i) {
        const double u = f.u_min + (f.u_max - f.u_min) * i / 80.0;
        const double relief = g.gear->ReliefAt(u).c;
        const Vec2 p = wi.Point(u) - scale * relief * wi.Normal(u);
        if ((p - c).cwiseAbs().maxCoeff() > w) continue;
        d += fmt::format("{}{:.4f},{:.4f} ", inside ? "L" : "M", p.x() * 1e3, -p.y() * 1e3);
        inside = true;
      }
      if (!d.empty()) {
        s += "<path fill=\"none\" stroke=\"#c0c\" stroke-width=\"0.02\" d=\"" + d + "\"/>\n";
      }
    }
  }
  return s;
}

}  // namespace

std::string DrawMeshZoom(const geometry::PosedGear& a, const geometry::PosedGear& b, bool internal,
                         int loaded_side, double gap_window, double relief_scale) {
  const geometry::LineOfAction l = geometry::MakeLineOfAction(a, b, internal, loaded_side);
  // The window: centred on the pitch point, 2.5 modules each way.
  const Vec2 ca = a.pose.geometric_centre, cb = b.pose.geometric_centre;
  const double ra = a.gear->base_radius() / std::cos(l.pressure_angle);
  const Vec2 pitch = ca + ra * (internal ? (ca - cb) : (cb - ca)).normalized();
  const double w = 2.5 * a.gear->module();
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{:.4f} {:.4f} {:.4f} {:.4f}\" "
      "width=\"900\" height=\"900\">\n",
      (pitch.x() - w) * 1e3, (-pitch.y() - w) * 1e3, 2 * w * 1e3, 2 * w * 1e3);
  s += fmt::format(
      "<title>epicycle mesh {}-{}: one tooth pair; magenta: relieved flanks, relief x {:.0f}; "
      "dashed: form circles (start of the active involute); red: line of action</title>\n",
      a.gear->name(), b.gear->name(), relief_scale);
  s += fmt::format(
      "<rect x=\"{:.4f}\" y=\"{:.4f}\" width=\"{:.4f}\" height=\"{:.4f}\" "
      "fill=\"white\"/>\n",
      (pitch.x() - w) * 1e3, (-pitch.y() - w) * 1e3, 2 * w * 1e3, 2 * w * 1e3);
  const std::string gear_style = "fill=\"#dde6f0\" stroke=\"#234\" stroke-width=\"0.015\"";
  for (const geometry::PosedGear* g : {&a, &b}) {
    // The ring's outline is its inner boundary: drawn without fill.
    s += "<path " +
         (g->gear->internal() ? std::string("fill=\"none\" stroke=\"#234\" stroke-width=\"0.015\"")
                              : gear_style) +
         " d=\"" + Path(g->gear->Outline(64), g->pose) + "\"/>\n";
    const std::string dash =
        "fill=\"none\" stroke=\"#555\" stroke-width=\"0.01\" stroke-dasharray=\"0.08,0.05\"";
    s += Circle(g->pose.geometric_centre, g->gear->form_radius(), dash);
    s += Circle(g->pose.geometric_centre, g->gear->base_radius(),
                "fill=\"none\" stroke=\"#999\" stroke-width=\"0.01\"");
    if (g->gear->undercut()) {
      s += Circle(g->pose.geometric_centre, g->gear->undercut_radius(),
                  "fill=\"none\" stroke=\"#d60\" stroke-width=\"0.015\"");
    }
    s += ReliefPaths(*g, pitch, w, relief_scale);
  }
  s += Line(l.tangent_a, l.tangent_b, "stroke=\"#c33\" stroke-width=\"0.015\"");
  geometry::ContactSearchOptions opt;
  opt.gap_window = gap_window;
  for (const geometry::PotentialContact& c : geometry::FindContacts(a, b, internal, opt)) {
    const char* colour = c.kind == geometry::ContactKind::kInvolute ? "#0a0" : "#f80";
    s += Circle(
        c.point, 0.04e-3,
        fmt::format("fill=\"{}\" fill-opacity=\"{}\"", colour, c.overlap >= -1e-6 ? 1.0 : 0.35));
  }
  return s + "</svg>\n";
}

std::string DrawStageMeshZoom(const geometry::Stage& stage, double carrier_angle,
                              const std::string& mesh, double gap_window, double relief_scale) {
  int found = -1;
  for (int m = 0; m < static_cast<int>(stage.meshes().size()); ++m)
    if (stage.meshes()[m].name == mesh) found = m;
  if (found < 0)
    throw std::invalid_argument("--zoom = " + mesh +
                                ": not a mesh of the stage (sun-planet<i>, planet<i>-ring)");
  const geometry::StagePoses p = stage.Poses(carrier_angle);
  const int i = found / 2;  // the meshes are sun-planet i, planet i-ring, in turn
  if (found % 2 == 1)
    return DrawMeshZoom(stage.Planet(p, i), stage.Ring(p), true, stage.ring_mesh_planet_side(),
                        gap_window, relief_scale);
  return DrawMeshZoom(stage.Sun(p), stage.Planet(p, i), false, stage.sun_mesh_side(), gap_window,
                      relief_scale);
}

std::string DrawPairMeshZoom(const geometry::GearPair& pair, double turn, const std::string& mesh,
                             double gap_window, double relief_scale) {
  if (mesh != "gear1-gear2")
    throw std::invalid_argument("--zoom = " + mesh + ": a gear pair has one mesh, gear1-gear2");
  const geometry::PairPoses p = pair.Poses(turn);
  return DrawMeshZoom(pair.A(p), pair.B(p), pair.internal(), pair.loaded_side(), gap_window,
                      relief_scale);
}

}  // namespace epicycle::report
