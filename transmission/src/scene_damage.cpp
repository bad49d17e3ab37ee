// The scene's damage tables, [[damage.pit]] and [[damage.crack]] (docs/scenes.md, "Damage").
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "epicycle/config.h"
#include "epicycle/compliance/cracked_mesh.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/compliance/root_crack.hpp"
#include "epicycle/io/toml_reader.hpp"
#include "scene_internal.hpp"

namespace epicycle::transmission::internal {

using geometry::GearSpec;

namespace {

// Pit depth: a warning beyond 5 % of the module (the tooth's compliance stays the intact
// tooth's), an error beyond a quarter of it.
constexpr double kPitDepthModules[2] = {0.05, 0.25};

// What gmsh can mesh around a crack has no closed form (a short crack's elements, graded to its
// tip, must meet the sector's boundary elements; a sharp turn folds the two faces' elements onto
// each other): the mesher itself is the rule. The crack's tooth is meshed as the table will mesh
// it (from ISO's point for a crack placed at the largest tension), and a crack it cannot mesh is
// refused here under its key, with a depth at which the same path shape meshes (its segments
// doubled while it stays in its tooth) or, if none does, its sharpest turn.
void CheckCrackMeshes(TableReader& t, const std::string& key, const Scene& s,
                      const geometry::Gear& gear, const compliance::RootCrack& k) {
#if EPICYCLE_HAVE_GMSH
  compliance::GearMeshOptions mesh;
  mesh.refinement = s.model.mesh_refinement;
  auto meshes = [&](const compliance::RootCrack& x, std::string* why) {
    try {
      compliance::BuildCrackedGearMesh(gear, x, mesh);
      return true;
    } catch (const std::invalid_argument& e) {
      if (why != nullptr) *why = e.what();
      return false;
    }
  };
  std::string why;
  if (meshes(k, &why)) return;
  std::string rule;
  for (double scale = 2; scale <= 4096; scale *= 2) {
    compliance::RootCrack larger = k;
    for (compliance::CrackSegment& g : larger.path) g.length *= scale;
    try {
      larger.Validate(gear);
    } catch (const std::invalid_argument&) {
      break;  // no longer inside its tooth
    }
    if (meshes(larger, nullptr)) {
      rule = "the same shape meshes at a depth of " + io::Num(larger.depth() / kMm, io::kInputDigits) +
             " mm (its segments " + io::Num(scale, io::kInputDigits) + " times as long)";
      break;
    }
  }
  if (rule.empty()) {
    double turn = 0;
    std::size_t at = 0;
    for (std::size_t i = 1; i < k.path.size(); ++i)
      if (std::abs(k.path[i].angle - k.path[i - 1].angle) > turn) {
        turn = std::abs(k.path[i].angle - k.path[i - 1].angle);
        at = i;
      }
    rule = k.path.size() > 1
               ? "no longer path of this shape meshes either: its sharpest turn, " +
                     io::Num(geometry::Deg(turn), io::kInputDigits) + " deg between segments " +
                     std::to_string(at - 1) + " and " + std::to_string(at) +
                     ", folds the crack's faces onto each other: open it"
               : "no longer crack at this angle that stays in the tooth meshes either";
  }
  t.Fail(key, io::Num(k.depth() / kMm, io::kInputDigits) + " mm",
         "must be a crack the FE mesher (gmsh) can mesh in its tooth: " + rule +
             " (the mesher: " + why + ")");
#else
  (void)t, (void)key, (void)s, (void)gear, (void)k;
#endif
}

// One [[damage.crack]] table (docs/scenes.md, "Damage"). The path is checked against the tooth's
// body here; a crack placed at the largest root tension is checked at ISO's 30° point, the start
// it lies near, and again once the body's table places it (GearTables).
Crack ReadCrack(TableReader& t, const Scene& s,
                const std::vector<std::pair<std::string, const GearSpec*>>& gears) {
  Crack c;
  c.where = t.Where("gear");
  const GearSpec* spec = &NamedGear(t, gears, &c.gear);
  for (const Crack& q : s.damage.cracks)
    if (q.gear == c.gear)
      t.Fail("gear", "\"" + c.gear + "\"",
             "the gear already has the crack of " + q.where + "; one root crack per gear");
  const geometry::Gear gear(*spec);
  compliance::RootCrack& k = c.crack;
  k.tooth = static_cast<int>(
      t.Integer("tooth", Rule::Closed(0, spec->teeth - 1)
                             .Because("a tooth index k of the gear's body frame, 0 <= k < z = " +
                                      std::to_string(spec->teeth))));
  k.side = t.String("side", {"+", "-"}) == "+" ? 1 : -1;
  if (t.Has("start_arc_mm")) {
    if (t.Has("start"))
      t.Fail("start", "\"" + t.String("start") + "\"", "give start or start_arc_mm, not both");
    const double form = compliance::ProfilePath(gear).RoleStart(geometry::SegmentRole::kInvolute);
    k.start_arc = t.Real("start_arc_mm", Rule::Open(0, form / kMm)
                                             .Because("on the fillet: from the space centre line "
                                                      "(0) to the form point")) *
                  kMm;
    c.start = CrackStart::kArc;
  } else {
    c.start =
        t.StringOr("start", "largest_tension", {"largest_tension", "iso_30deg"}) == "iso_30deg"
            ? CrackStart::kIso30
            : CrackStart::kLargestTension;
    try {
      k.start_arc = compliance::IsoCriticalFilletArc(gear);
    } catch (const std::invalid_argument& e) {
      t.Fail(
          "start", c.start == CrackStart::kIso30 ? "\"iso_30deg\"" : "\"largest_tension\"",
          std::string("needs ISO's 30-degree point on the fillet; give start_arc_mm: ") + e.what());
    }
  }
  const Rule angle = Rule::Open(0, 180).Because(
      "the angle to the tooth centre line: below 90 toward the root, 90 straight across");
  const std::string length_rule = "the crack's length along its path";
  std::string depth_key = "depth_mm";
  if (t.Has("path")) {
    depth_key = "path";
    if (t.Has("depth_mm") || t.Has("angle_deg"))
      t.Fail("path", "given with depth_mm/angle_deg",
             "a straight crack is depth_mm and angle_deg, a polyline is path; not both");
    std::vector<TableReader> pieces = t.TableArray("path");
    if (pieces.empty() || static_cast<int>(pieces.size()) > compliance::RootCrack::kMaxSegments)
      t.Fail("path", std::to_string(pieces.size()) + " segments",
             "must have 1 to " + std::to_string(compliance::RootCrack::kMaxSegments));
    for (TableReader& piece : pieces) {
      compliance::CrackSegment g;
      g.length = piece.Real("length_mm", Rule::Positive().Because(length_rule)) * kMm;
      g.angle = geometry::Rad(piece.Real("angle_deg", angle));
      piece.Done();
      k.path.push_back(g);
    }
  } else {
    compliance::CrackSegment g;
    g.length = t.Real("depth_mm", Rule::Positive().Because(length_rule)) * kMm;
    g.angle = geometry::Rad(t.Real("angle_deg", angle));
    k.path.push_back(g);
  }
  try {
    k.Validate(gear);
  } catch (const std::invalid_argument& e) {
    t.Fail(depth_key, io::Num(k.depth() / kMm, io::kInputDigits) + " mm",
           std::string("the crack must stay inside its tooth") +
               (c.start == CrackStart::kLargestTension ? " (checked from ISO's 30-degree point)"
                                                       : "") +
               ": " + e.what());
  }
  CheckCrackMeshes(t, depth_key, s, gear, k);
  t.Done();
  return c;
}

}  // namespace

const GearSpec& NamedGear(TableReader& t,
                         const std::vector<std::pair<std::string, const GearSpec*>>& gears,
                         std::string* name) {
  *name = t.String("gear");
  std::string names;
  for (const auto& [n, g] : gears) {
    if (n == *name) return *g;
    names += (names.empty() ? "\"" : ", \"") + n + "\"";
  }
  t.Fail("gear", "\"" + *name + "\"", "must be one of " + names);
}

// The scene's [[damage.pit]] and [[damage.crack]] tables (docs/scenes.md, "Damage"): `gears` names
// the gears a damage may be on with the spec of each (a stage's planets share one spec), read once
// the radii are final.
void ReadDamage(TableReader& top, Scene& s,
                const std::vector<std::pair<std::string, const GearSpec*>>& gears) {
  auto d = top.OptionalTable("damage");
  if (!d) return;
  for (TableReader& t : d->TableArray("pit")) {
    Pit p;
    p.where = t.Where("gear");
    const GearSpec* spec = &NamedGear(t, gears, &p.gear);
    const geometry::Gear gear(*spec);
    p.tooth = static_cast<int>(
        t.Integer("tooth", Rule::Closed(0, spec->teeth - 1)
                               .Because("a tooth index k of the gear's body frame, 0 <= k < z = " +
                                        std::to_string(spec->teeth))));
    p.flank = t.String("flank", {"+", "-"}) == "+" ? 1 : -1;
    // The region: roll angles (primary) or radii, one form per pit.
    const bool by_roll = t.Has("roll_from_deg") || t.Has("roll_to_deg");
    const bool by_radius = t.Has("radius_from_mm") || t.Has("radius_to_mm");
    if (by_roll == by_radius)
      t.Fail("roll_from_deg", by_roll ? "given with radius_from_mm/radius_to_mm" : "missing",
             std::string("give the region as roll_from_deg and roll_to_deg, or as radius_from_mm "
                         "and radius_to_mm") +
                 (by_roll ? ", not both" : ""));
    const geometry::InvoluteFlank& inv = gear.involute();
    const double rb = gear.base_radius();
    auto radius_at = [&](double u) { return rb * std::hypot(1.0, u) / kMm; };
    const std::string extent =
        "the involute of the flank runs over roll " + io::Num(geometry::Deg(inv.u_min), io::kInputDigits) + ".." +
        io::Num(geometry::Deg(inv.u_max), io::kInputDigits) + " deg (radius " + io::Num(radius_at(inv.u_min), io::kInputDigits) + ".." +
        io::Num(radius_at(inv.u_max), io::kInputDigits) + " mm); a pit lowers the involute only";
    const std::string from = by_roll ? "roll_from_deg" : "radius_from_mm",
                      to = by_roll ? "roll_to_deg" : "radius_to_mm";
    if (by_roll) {
      const Rule rule =
          Rule::Closed(geometry::Deg(inv.u_min), geometry::Deg(inv.u_max)).Because(extent);
      p.roll_from = geometry::Rad(t.Real(from, rule));
      p.roll_to = geometry::Rad(t.Real(to, rule));
    } else {
      const Rule rule = Rule::Closed(radius_at(inv.u_min), radius_at(inv.u_max)).Because(extent);
      p.roll_from = geometry::InvoluteFlank::RollAtRadius(rb, t.Real(from, rule) * kMm);
      p.roll_to = geometry::InvoluteFlank::RollAtRadius(rb, t.Real(to, rule) * kMm);
    }
    if (!(p.roll_to > p.roll_from))
      t.Fail(to, io::Num(by_roll ? geometry::Deg(p.roll_to) : radius_at(p.roll_to), io::kInputDigits),
             "must be greater than " + from + " (the region runs from the root side to the tip)");
    p.width_fraction =
        t.Real("width_fraction",
               Rule{0, 1, true, false, ""}.Because("the share of the face width the pit covers"));
    const double depth_um = t.Real(
        "depth_um", Rule{0, kPitDepthModules[1] * spec->module / kUm, true, false, ""}.Because(
                        "at most a quarter of the module: deeper, the pit takes a large part of "
                        "the tooth's thickness"));
    p.depth = depth_um * kUm;
    if (p.depth > kPitDepthModules[0] * spec->module)
      s.warnings.push_back(t.Warning(
          "depth_um", "deeper than " + io::Num(kPitDepthModules[0] * spec->module / kUm, io::kInputDigits) +
                          " um (5 % of the module): the tooth keeps the compliance of the intact "
                          "tooth, which a pit this deep softens"));
    // Pits on one flank of one tooth must not overlap: the strips of the face width they would
    // share are not defined by the scene.
    for (const Pit& q : s.damage.pits) {
      if (q.gear == p.gear && q.tooth == p.tooth && q.flank == p.flank && p.roll_from < q.roll_to &&
          q.roll_from < p.roll_to)
        t.Fail(from, io::Num(by_roll ? geometry::Deg(p.roll_from) : radius_at(p.roll_from), io::kInputDigits),
               "the region overlaps the pit of " + q.where +
                   " on the same flank of the same tooth; give one pit per region (join them, "
                   "or split the roll range)");
    }
    t.Done();
    s.damage.pits.push_back(p);
  }
  for (TableReader& t : d->TableArray("crack")) s.damage.cracks.push_back(ReadCrack(t, s, gears));
  d->Done();
}

}  // namespace epicycle::transmission::internal
