#include "fe_deck.hpp"
#include "fe_deck_detail.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <gmsh.h>
#include "epicycle/io/number_format.hpp"

namespace epicycle::fe_reference {

using namespace detail;

namespace detail {

using geometry::Vec2;

constexpr double kMm = 1e3;  // the deck is in mm, N, MPa

// CalculiX reads at most 20 characters per field: 13 significant digits fit any sign and exponent.
using io::Num;

// The parameter t of `seg` (t0 <= t <= t1) where the radius |p(t)| is `radius` (bisection; the
// involute's radius grows with t), clamped to the segment.
double ParameterAtRadius(const geometry::Segment& seg, double radius) {
  double lo = seg.t0, hi = seg.t1;
  if (seg.Point(lo).norm() >= radius) return lo;
  if (seg.Point(hi).norm() <= radius) return hi;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (seg.Point(mid).norm() < radius ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The segment (index into the half profile) and parameter of the point of the fillet (root land
// or fillet, σ = +1 half of tooth 0) nearest `x` (tooth-0 frame, σ = +1 side) [m]: dense sampling,
// then golden-section refinement.
std::pair<int, double> NearestFilletParameter(const geometry::HalfProfile& half, const Vec2& x) {
  int best_seg = -1;
  double best_t = 0, best_d = 1e300;
  for (std::size_t i = 0; i < half.segments.size(); ++i) {
    const geometry::Segment& seg = half.segments[i];
    if (seg.role != geometry::SegmentRole::kRootLand && seg.role != geometry::SegmentRole::kFillet)
      continue;
    constexpr int kSamples = 2000;
    for (int j = 0; j <= kSamples; ++j) {
      const double t = seg.t0 + (seg.t1 - seg.t0) * j / kSamples;
      const double d = (seg.Point(t) - x).norm();
      if (d < best_d) best_seg = static_cast<int>(i), best_t = t, best_d = d;
    }
  }
  if (best_seg < 0) throw std::runtime_error("fe deck: the profile has no fillet");
  const geometry::Segment& seg = half.segments[best_seg];
  const double step = (seg.t1 - seg.t0) / 2000;
  double a = std::max(seg.t0, best_t - step), b = std::min(seg.t1, best_t + step);
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  for (int i = 0; i < 200; ++i) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if ((seg.Point(c) - x).norm() < (seg.Point(d) - x).norm())
      b = d;
    else
      a = c;
  }
  return {best_seg, 0.5 * (a + b)};
}

// The gear's outline as OCC splines through points of the exact profile (per segment, so each
// spline is one analytic piece and the G1 joints are spline ends), closed by the hub circle
// (external: the hole) or the rim circle (internal: the outside). Teeth in `fine_teeth` get
// `fine_points` interpolation points per segment, the others a quarter (the spline error falls as
// (segment length / points)^4, far below the deflections on either).
// A crack splits its fillet segment at the mouth and adds the straight crack curve (to be embedded
// in the surface); a spall splits its involute at the roll range, lowers the middle piece by the
// depth along the inward normal and joins the pieces by straight steps.
// A `sector` (teeth consecutive in the cyclic order) keeps only those teeth: the outline runs from
// the space centre line before the first to the one after the last and closes along the circle
// through those two points (the root circle) about the gear's centre.
GearModel BuildGear(const geometry::Gear& gear, const geometry::GearPose& pose,
                    const std::set<int>& fine_teeth, int fine_points, const FeCrack* crack,
                    const FeSpall* spall, const std::vector<int>* sector) {
  GearModel g;
  const geometry::HalfProfile& half = gear.half_profile();
  auto world = [&](const Vec2& body) {
    const Vec2 w = pose.geometric_centre + geometry::Rotate(body, pose.rotation);
    return Vec2(w.x() * kMm, w.y() * kMm);
  };
  // The crack's mouth on the σ = +1 half of tooth 0 (segment, parameter) and its tip (body).
  int mouth_seg = -1;
  double mouth_t = 0;
  Vec2 tip_body = Vec2::Zero();
  if (crack) {
    const std::vector<Eigen::Vector2d> pts = crack->crack.Points(gear);
    Vec2 mouth0 = geometry::Rotate(Vec2(pts.front().x(), pts.front().y()),
                                   -crack->crack.tooth * gear.pitch_angle());
    if (crack->crack.side < 0) mouth0.y() = -mouth0.y();
    std::tie(mouth_seg, mouth_t) = NearestFilletParameter(half, mouth0);
    const geometry::Segment& seg = half.segments[static_cast<std::size_t>(mouth_seg)];
    const double margin = 1e-6 * std::abs(seg.t1 - seg.t0);
    if (!(mouth_t > std::min(seg.t0, seg.t1) + margin &&
          mouth_t < std::max(seg.t0, seg.t1) - margin))
      throw std::invalid_argument("fe deck: crack start_arc = " + Num(crack->crack.start_arc, 13) +
                                  " m: the mouth falls on a joint of the fillet's segments");
    tip_body = Vec2(pts.back().x(), pts.back().y());
  }
  // The closed outline as pieces (one per non-empty segment), counter-clockwise: per tooth the
  // mirrored half (side −1) root → tip, then the half (side +1) tip → root.
  struct Piece {
    std::vector<Vec2> points;
    int tooth = 0, side = 0;
    bool flank = false, fillet = false;
    bool ends_at_mouth = false;
  };
  std::vector<Piece> pieces;
  const int z = gear.teeth();
  const int count = static_cast<int>(half.segments.size());
  std::vector<int> teeth;
  if (sector) {
    teeth = *sector;
  } else {
    for (int k = 0; k < z; ++k) teeth.push_back(k);
  }
  for (int k : teeth) {
    const double turn = k * gear.pitch_angle();
    const int n = fine_teeth.count(k) ? fine_points : std::max(4, fine_points / 4);
    for (int side : {-1, 1}) {
      for (int i = 0; i < count; ++i) {
        const int si = side < 0 ? i : count - 1 - i;
        const geometry::Segment& seg = half.segments[si];
        if ((seg.Point(seg.t0) - seg.Point(seg.t1)).norm() < 1e-12) continue;  // empty piece
        // Sub-ranges of t (root → tip) with their inward offset [m]; `cut` marks the crack's mouth
        // (the end t of the first sub-range).
        std::vector<std::array<double, 3>> ranges = {{seg.t0, seg.t1, 0.0}};
        bool cut = false;
        if (crack && k == crack->crack.tooth && side == crack->crack.side && si == mouth_seg) {
          ranges = {{seg.t0, mouth_t, 0.0}, {mouth_t, seg.t1, 0.0}};
          cut = true;
        }
        if (spall && k == spall->tooth && side == spall->side &&
            seg.role == geometry::SegmentRole::kInvolute) {
          const double rb = gear.base_radius();
          const double ta = ParameterAtRadius(seg, rb * std::hypot(1.0, spall->roll_from));
          const double tb = ParameterAtRadius(seg, rb * std::hypot(1.0, spall->roll_to));
          if (!(tb > ta))
            throw std::invalid_argument("fe deck: the spall's roll range lies off the involute");
          ranges.clear();
          if (ta > seg.t0) ranges.push_back({seg.t0, ta, 0.0});
          ranges.push_back({ta, tb, spall->depth});
          if (tb < seg.t1) ranges.push_back({tb, seg.t1, 0.0});
        }
        if (side > 0) std::reverse(ranges.begin(), ranges.end());
        for (std::size_t r = 0; r < ranges.size(); ++r) {
          const auto [ra, rb, offset] = ranges[r];
          Piece piece;
          piece.tooth = k;
          piece.side = side;
          piece.flank = seg.role == geometry::SegmentRole::kInvolute ||
                        seg.role == geometry::SegmentRole::kTipRound;
          piece.fillet = seg.role == geometry::SegmentRole::kRootLand ||
                         seg.role == geometry::SegmentRole::kFillet;
          // Side −1 runs root → tip: the mouth ends its first range; side +1 its (reversed) first.
          piece.ends_at_mouth = cut && r == 0;
          const int np = ranges.size() == 1 ? n : std::max(4, n / 2);
          for (int j = 0; j <= np; ++j) {
            const double t = ra + (rb - ra) * (side < 0 ? j : np - j) / np;
            const geometry::CurvePoint cp = seg.Evaluate(t);
            Vec2 p = cp.p;
            if (offset > 0) {
              // Inward normal of the σ = +1 half: the tangent turned toward the centre line.
              Vec2 nrm(cp.d1.y(), -cp.d1.x());
              if (nrm.y() > 0) nrm = -nrm;
              p += offset * nrm.normalized();
            }
            if (side < 0) p.y() = -p.y();
            piece.points.push_back(world(geometry::Rotate(p, turn)));
          }
          pieces.push_back(std::move(piece));
        }
      }
    }
  }
  // Consecutive pieces share their end points (one gmsh point each); the last closes on the first.
  // A piece starting elsewhere than where the last ended (a spall's edge) is joined by a line.
  std::vector<int> outline;
  int first_point = -1, last_point = -1;
  Vec2 last_xy = Vec2::Zero();
  int mouth_point = -1;
  for (std::size_t q = 0; q < pieces.size(); ++q) {
    const Piece& piece = pieces[q];
    if (last_point > 0 && (piece.points.front() - last_xy).norm() > 1e-9) {
      const int start =
          gmsh::model::occ::addPoint(piece.points.front().x(), piece.points.front().y(), 0.0);
      const int c = gmsh::model::occ::addLine(last_point, start);
      outline.push_back(c);
      g.curves.insert(c);
      g.flank_curves[{piece.tooth, piece.side}].push_back(c);
      last_point = start;
    }
    std::vector<int> pts;
    for (std::size_t j = 0; j < piece.points.size(); ++j) {
      if (j == 0 && last_point > 0) {
        pts.push_back(last_point);
      } else if (j + 1 == piece.points.size() && q + 1 == pieces.size() && !sector) {
        pts.push_back(first_point);
      } else {
        pts.push_back(gmsh::model::occ::addPoint(piece.points[j].x(), piece.points[j].y(), 0.0));
      }
    }
    if (first_point < 0) first_point = pts.front();
    last_point = pts.back();
    last_xy = piece.points.back();
    if (piece.ends_at_mouth) mouth_point = last_point;
    const int c = gmsh::model::occ::addSpline(pts);
    outline.push_back(c);
    g.curves.insert(c);
    if (piece.flank) g.flank_curves[{piece.tooth, piece.side}].push_back(c);
    if (piece.fillet) g.fillet_curves[{piece.tooth, piece.side}].push_back(c);
  }
  if (crack) {
    if (mouth_point < 0) throw std::runtime_error("fe deck: the crack's mouth was not placed");
    const Vec2 tip = world(tip_body);
    g.crack_tip = gmsh::model::occ::addPoint(tip.x(), tip.y(), 0.0);
    g.crack_curve = gmsh::model::occ::addLine(mouth_point, g.crack_tip);
    g.curves.insert(g.crack_curve);
    g.tip_xy = tip;
  }
  const Vec2 c = world(Vec2::Zero());
  if (sector) {
    // Counter-clockwise from the last tooth's end back to the first's start, in arcs below π.
    const Vec2 from = last_xy - c, to = pieces.front().points.front() - c;
    const double radius = from.norm();
    if (std::abs(to.norm() - radius) > 1e-6 * radius)
      throw std::runtime_error("fe deck: a sector's ends lie on different circles");
    double span = std::atan2(to.y(), to.x()) - std::atan2(from.y(), from.x());
    while (span <= 0) span += 2 * geometry::kPi;
    const int arcs = static_cast<int>(std::ceil(span / (0.5 * geometry::kPi)));
    const int centre = gmsh::model::occ::addPoint(c.x(), c.y(), 0.0);
    int start = last_point;
    for (int a = 1; a <= arcs; ++a) {
      const Vec2 p = c + geometry::Rotate(from, span * a / arcs);
      const int end = a == arcs ? first_point : gmsh::model::occ::addPoint(p.x(), p.y(), 0.0);
      const int arc = gmsh::model::occ::addCircleArc(start, centre, end);
      outline.push_back(arc);
      g.curves.insert(arc);
      start = end;
    }
  }
  const double r = gear.spec().hub_radius * kMm;
  g.hub_curve = gmsh::model::occ::addCircle(c.x(), c.y(), 0.0, r);
  g.curves.insert(g.hub_curve);
  const int outline_loop = gmsh::model::occ::addCurveLoop(outline);
  const int hub_loop = gmsh::model::occ::addCurveLoop({g.hub_curve});
  g.surface = gear.internal() ? gmsh::model::occ::addPlaneSurface({hub_loop, outline_loop})
                              : gmsh::model::occ::addPlaneSurface({outline_loop, hub_loop});
  return g;
}

// The fillet (root land and fillet) of one tooth side as a dense polyline in the deck's frame
// [mm] with the arc length from the space centre line: where a mesh node on it lies along the
// fillet and the surface tangent there (chords of 1/400 of a segment: the direction within
// κ·chord/2 < 1e-3 rad of the tangent, the arc length within 1e-6 relative).
struct FilletLine {
  int gear = 1, tooth = 0, side = 1;
  std::vector<Vec2> p;    // [mm]
  std::vector<double> s;  // [mm]
  // The nearest point of the polyline to x: arc length [mm], unit tangent, distance [mm].
  void Project(const Vec2& x, double* arc, Vec2* tangent, double* distance) const {
    *distance = 1e300;
    for (std::size_t j = 0; j + 1 < p.size(); ++j) {
      const Vec2 d = p[j + 1] - p[j];
      const double len2 = d.squaredNorm();
      if (!(len2 > 0)) continue;
      const double u = std::clamp((x - p[j]).dot(d) / len2, 0.0, 1.0);
      const double dist = (x - (p[j] + u * d)).norm();
      if (dist < *distance) {
        *distance = dist;
        *arc = s[j] + u * (s[j + 1] - s[j]);
        *tangent = d.normalized();
      }
    }
  }
};

FilletLine MakeFilletLine(const geometry::Gear& gear, const geometry::GearPose& pose, int which,
                          int tooth, int side) {
  FilletLine line;
  line.gear = which;
  line.tooth = tooth;
  line.side = side;
  constexpr int kPoints = 400;
  for (const geometry::Segment& seg : gear.half_profile().segments) {
    if (seg.role != geometry::SegmentRole::kRootLand && seg.role != geometry::SegmentRole::kFillet)
      break;  // the half profile starts at the space centre line: root land, fillet, involute ...
    for (int j = line.p.empty() ? 0 : 1; j <= kPoints; ++j) {
      Vec2 q = seg.Point(seg.t0 + (seg.t1 - seg.t0) * j / kPoints);
      if (side < 0) q.y() = -q.y();
      const Vec2 w =
          pose.geometric_centre +
          geometry::Rotate(geometry::Rotate(q, tooth * gear.pitch_angle()), pose.rotation);
      const Vec2 mm(w.x() * kMm, w.y() * kMm);
      line.s.push_back(line.p.empty() ? 0.0 : line.s.back() + (mm - line.p.back()).norm());
      line.p.push_back(mm);
    }
  }
  return line;
}

}  // namespace detail

void FeMeshOptions::Validate() const {
  auto positive = [](const char* key, double v) {
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument(std::string("fe mesh: ") + key + " = " + Num(v, 13) +
                                  ": must be > 0");
  };
  positive("contact_size", contact_size);
  positive("contact_radius", contact_radius);
  positive("grading", grading);
  positive("tooth_size_per_module", tooth_size_per_module);
  positive("body_size_per_module", body_size_per_module);
  positive("fillet_size_per_module", fillet_size_per_module);
  positive("refinement", refinement);
  if (points_per_segment < 4)
    throw std::invalid_argument(
        "fe mesh: points_per_segment = " + std::to_string(points_per_segment) + ": must be >= 4");
  if (tooth_zone < 0)
    throw std::invalid_argument("fe mesh: tooth_zone = " + std::to_string(tooth_zone) +
                                ": must be >= 0");
  if (fillet_zone < 0 || fillet_zone > tooth_zone)
    throw std::invalid_argument("fe mesh: fillet_zone = " + std::to_string(fillet_zone) +
                                ": must be in [0, tooth_zone]");
}

void FeDeckInfo::Write(const std::string& path) const {
  std::ofstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be written");
  f.precision(17);
  f << "thickness_m " << thickness << "\nface_width_m " << face_width << "\ntorque_Nm " << torque
    << "\nbase_radius1_m " << base_radius1 << "\nangle_rad " << angle << "\nnodes " << nodes
    << "\nelements " << elements << "\nnodes_2d " << nodes_2d << "\ntriangles " << triangles
    << "\nstraightened " << straightened << "\ncrack_nodes " << crack_nodes << "\n";
  for (double r : rotations) f << "rotation_rad " << r << "\n";
  for (const FeToothPair& p : pairs)
    f << "pair " << p.tooth1 << " " << p.tooth2 << " " << p.slave << " " << p.master << " "
      << p.rigid_gap << "\n";
  for (std::size_t i = 0; i < hub_nodes.size(); ++i)
    f << "hub " << hub_nodes[i] << " " << hub_x[i] << " " << hub_y[i] << "\n";
  for (const FeFilletNode& n : fillet_nodes)
    f << "fillet " << n.gear << " " << n.tooth << " " << n.side << " " << n.node << " "
      << n.arc_length << " " << n.tx << " " << n.ty << "\n";
}

FeDeckInfo FeDeckInfo::Read(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read");
  FeDeckInfo info;
  std::string line;
  int number = 0;
  while (std::getline(f, line)) {
    ++number;
    std::istringstream s(line);
    std::string key;
    s >> key;
    bool ok = true;
    if (key == "thickness_m")
      ok = static_cast<bool>(s >> info.thickness);
    else if (key == "face_width_m")
      ok = static_cast<bool>(s >> info.face_width);
    else if (key == "torque_Nm")
      ok = static_cast<bool>(s >> info.torque);
    else if (key == "base_radius1_m")
      ok = static_cast<bool>(s >> info.base_radius1);
    else if (key == "angle_rad")
      ok = static_cast<bool>(s >> info.angle);
    else if (key == "nodes")
      ok = static_cast<bool>(s >> info.nodes);
    else if (key == "elements")
      ok = static_cast<bool>(s >> info.elements);
    else if (key == "nodes_2d")
      ok = static_cast<bool>(s >> info.nodes_2d);
    else if (key == "triangles")
      ok = static_cast<bool>(s >> info.triangles);
    else if (key == "straightened")
      ok = static_cast<bool>(s >> info.straightened);
    else if (key == "crack_nodes")
      ok = static_cast<bool>(s >> info.crack_nodes);
    else if (key == "rotation_rad") {
      double r = 0;
      ok = static_cast<bool>(s >> r);
      info.rotations.push_back(r);
    } else if (key == "pair") {
      FeToothPair p;
      ok = static_cast<bool>(s >> p.tooth1 >> p.tooth2 >> p.slave >> p.master >> p.rigid_gap);
      info.pairs.push_back(p);
    } else if (key == "hub") {
      int id = 0;
      double x = 0, y = 0;
      ok = static_cast<bool>(s >> id >> x >> y);
      info.hub_nodes.push_back(id);
      info.hub_x.push_back(x);
      info.hub_y.push_back(y);
    } else if (key == "fillet") {
      FeFilletNode n;
      ok = static_cast<bool>(s >> n.gear >> n.tooth >> n.side >> n.node >> n.arc_length >> n.tx >>
                             n.ty);
      info.fillet_nodes.push_back(n);
    } else if (!key.empty()) {
      ok = false;
    }
    if (!ok)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": cannot read '" + line +
                               "'");
  }
  return info;
}

namespace detail {

// The deck's inputs: mesh options, rotations of one sign, a torque, and the damage it meshes (a
// straight crack, an external gear's spall). @throws std::invalid_argument naming the value.
void CheckDeckInput(const geometry::GearPair& pair, double torque,
                    const std::vector<double>& rotations, const FeMeshOptions& mesh,
                    const FeDamage& damage) {
  const geometry::Gear& g1 = pair.gear1();
  const geometry::Gear& g2 = pair.gear2();
  const FeCrack* crack = damage.crack ? &*damage.crack : nullptr;
  const FeSpall* spall = damage.spall ? &*damage.spall : nullptr;
  mesh.Validate();
  if (rotations.empty())
    throw std::invalid_argument("fe deck: rotations: at least one step is needed");
  for (double r : rotations) {
    if (!(r * rotations.front() > 0) || !std::isfinite(r))
      throw std::invalid_argument("fe deck: rotation = " + Num(r, 13) +
                                  ": every step's rotation must be non-zero and of one sign");
  }
  if (torque == 0) throw std::invalid_argument("fe deck: torque = 0: must be non-zero");
  if (crack) {
    if (crack->gear != 1 && crack->gear != 2)
      throw std::invalid_argument("fe deck: crack gear = " + std::to_string(crack->gear) +
                                  ": must be 1 or 2");
    if (crack->crack.path.size() != 1)
      throw std::invalid_argument(
          "fe deck: crack path: " + std::to_string(crack->crack.path.size()) +
          " segments: the deck meshes a straight crack (one segment)");
    if (!(crack->tip_size > 0) || !(crack->face_size_per_module > 0) || !(crack->tip_grading > 0))
      throw std::invalid_argument(
          "fe deck: crack tip_size, face_size_per_module, tip_grading: "
          "must be > 0");
    crack->crack.Validate(crack->gear == 1 ? g1 : g2);
  }
  if (spall) {
    const geometry::Gear& g = spall->gear == 1 ? g1 : g2;
    if ((spall->gear != 1 && spall->gear != 2) || g.internal())
      throw std::invalid_argument("fe deck: spall gear = " + std::to_string(spall->gear) +
                                  ": must be 1 or 2, an external gear");
    if (spall->tooth < 0 || spall->tooth >= g.teeth() || (spall->side != 1 && spall->side != -1))
      throw std::invalid_argument("fe deck: spall tooth " + std::to_string(spall->tooth) +
                                  " side " + std::to_string(spall->side) +
                                  ": tooth in [0, z), side ±1");
    if (!(spall->depth > 0) || !(spall->roll_to > spall->roll_from) || !(spall->roll_from >= 0))
      throw std::invalid_argument("fe deck: spall depth " + Num(spall->depth, 13) + " m, roll " +
                                  Num(spall->roll_from, 13) + ".." + Num(spall->roll_to, 13) +
                                  " rad: depth > 0 and 0 <= roll_from < roll_to");
  }
}

LoadedContacts FindLoadedContacts(const geometry::GearPair& pair, const geometry::PairPoses& poses,
                                  const FeContactOptions& contact) {
  LoadedContacts lc;
  auto& by_teeth = lc.by_teeth;
  auto& points_of = lc.points_of;
  auto& contact_points = lc.contact_points;
  auto& teeth1 = lc.teeth1;
  auto& teeth2 = lc.teeth2;
  geometry::ContactSearchOptions search;
  search.gap_window = contact.gap_window;
  search.both_sides = false;
  search.side_a = pair.loaded_side();
  const std::vector<geometry::PotentialContact> contacts = pair.Contacts(poses, search);
  if (contacts.empty())
    throw std::invalid_argument("fe deck: no tooth pair within the gap window at this position");
  for (const geometry::PotentialContact& c : contacts) {
    auto [it, fresh] = by_teeth.try_emplace({c.tooth_a, c.tooth_b});
    FeToothPair& p = it->second;
    if (fresh) {
      p.tooth1 = c.tooth_a;
      p.tooth2 = c.tooth_b;
      p.slave = "G1T" + std::to_string(c.tooth_a);
      p.master = "G2T" + std::to_string(c.tooth_b);
      p.rigid_gap = -c.overlap;
    }
    p.rigid_gap = std::min(p.rigid_gap, -c.overlap);
    contact_points.emplace_back(c.point.x() * kMm, c.point.y() * kMm);
    points_of[{c.tooth_a, c.tooth_b}].push_back(contact_points.back());
    teeth1.insert(c.tooth_a);
    teeth2.insert(c.tooth_b);
    lc.side1 = c.side_a;
    lc.side2 = c.side_b;
  }
  return lc;
}

// The size field's view of each fillet: every 10th polyline point and the bounding box.
struct FilletZone {
  int gear = 1;
  std::vector<Vec2> points;
  Vec2 lo, hi;
};

std::vector<FilletZone> FilletZones(const std::vector<FilletLine>& fillet_lines) {
  std::vector<FilletZone> fillet_zones;
  for (const FilletLine& line : fillet_lines) {
    FilletZone z;
    z.gear = line.gear;
    z.lo = z.hi = line.p.front();
    for (std::size_t j = 0; j < line.p.size(); ++j) {
      if (j % 10 != 0 && j + 1 != line.p.size()) continue;
      z.points.push_back(line.p[j]);
      z.lo = z.lo.cwiseMin(line.p[j]);
      z.hi = z.hi.cwiseMax(line.p[j]);
    }
    fillet_zones.push_back(std::move(z));
  }
  return fillet_zones;
}

// The straight crack's axis in the mesh [mm]: its mouth, its unit direction toward the tip and
// its length.
struct CrackAxis {
  Vec2 mouth = Vec2::Zero(), dir = Vec2::Zero();
  double length = 0;
};

// Embeds the crack's curve in its gear's surface (the mesh keeps it as element sides).
CrackAxis EmbedCrack(const GearModel& cracked) {
  CrackAxis axis;
  Vec2& mouth_xy = axis.mouth;
  gmsh::model::mesh::embed(1, {cracked.crack_curve}, 2, cracked.surface);
  double xmin = 0, ymin = 0, zmin = 0, xmax = 0, ymax = 0, zmax = 0;
  // The mouth: the curve's end other than the tip.
  std::vector<std::pair<int, int>> ends;
  gmsh::model::getBoundary({{1, cracked.crack_curve}}, ends, false, false, false);
  for (const auto& [dim, tag] : ends) {
    if (std::abs(tag) == cracked.crack_tip) continue;
    gmsh::model::getBoundingBox(0, std::abs(tag), xmin, ymin, zmin, xmax, ymax, zmax);
    mouth_xy = Vec2(xmin, ymin);
  }
  axis.length = (cracked.tip_xy - mouth_xy).norm();
  axis.dir = (cracked.tip_xy - mouth_xy) / axis.length;
  return axis;
}

DeckMesh ReadDeckMesh(const GearModel& m1, const GearModel& m2) {
  DeckMesh dm;
  auto& index = dm.index;
  auto& xy = dm.xy;
  auto& tris = dm.tris;
  auto& edge_of = dm.edge_of;
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, param;
  gmsh::model::mesh::getNodes(node_tags, coords, param, -1, -1, true, false);
  std::map<std::size_t, Vec2> position;
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    position[node_tags[i]] = Vec2(coords[3 * i], coords[3 * i + 1]);
  for (int surface : {m1.surface, m2.surface}) {
    std::vector<std::size_t> elem_tags, elem_nodes;
    gmsh::model::mesh::getElementsByType(9, elem_tags, elem_nodes, surface);
    for (std::size_t tag : elem_nodes) {
      if (index.try_emplace(tag, static_cast<int>(xy.size())).second)
        xy.push_back(position.at(tag));
    }
  }

  // Triangles (6-node, gmsh type 9), counter-clockwise.
  for (int body = 0; body < 2; ++body) {
    std::vector<std::size_t> elem_tags, elem_nodes;
    gmsh::model::mesh::getElementsByType(9, elem_tags, elem_nodes,
                                         body == 0 ? m1.surface : m2.surface);
    for (std::size_t e = 0; e < elem_tags.size(); ++e) {
      Tri t;
      t.body = body;
      for (int j = 0; j < 6; ++j) t.n[j] = index.at(elem_nodes[6 * e + j]);
      const double area = geometry::Cross(xy[t.n[1]] - xy[t.n[0]], xy[t.n[2]] - xy[t.n[0]]);
      if (area < 0) t.n = {t.n[0], t.n[2], t.n[1], t.n[5], t.n[4], t.n[3]};
      const int id = static_cast<int>(tris.size());
      for (int j = 0; j < 3; ++j) {
        const int a = t.n[j], b = t.n[(j + 1) % 3];
        edge_of[{std::min(a, b), std::max(a, b)}] = {id, j};
      }
      tris.push_back(t);
    }
  }
  if (tris.empty()) throw std::runtime_error("fe deck: gmsh produced no triangles");
  return dm;
}

// An element larger than a tip round (0.08–0.21 mm radius under m/4 or 2 m elements) can turn
// inside out when its mid-side node goes onto the arc. Such an element (det J below 2 % of the
// straight triangle's anywhere at its six nodes) gets straight sides: the tip corner it cuts
// carries no load (the contacts have 40 µm elements), its sagitta is below the round's radius.
// Returns how many were straightened.
int StraightenInvertedTriangles(DeckMesh& dm) {
  std::vector<Vec2>& xy = dm.xy;
  int straightened = 0;
  for (const Tri& t : dm.tris) {
    const Vec2 a = xy[t.n[0]], b = xy[t.n[1]], c = xy[t.n[2]];
    const double area2 = geometry::Cross(b - a, c - a);
    // det J of the quadratic map at the corners and mid-sides (ξ, η) ∈ {0, ½, 1}.
    bool bad = false;
    const double pts[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
    for (const auto& q : pts) {
      const double xi = q[0], eta = q[1], l0 = 1 - xi - eta;
      // Shape-function derivatives of the 6-node triangle (corners 0..2, mid-sides 01, 12, 20).
      const double dxi[6] = {-(4 * l0 - 1), 4 * xi - 1, 0, 4 * (l0 - xi), 4 * eta, -4 * eta};
      const double deta[6] = {-(4 * l0 - 1), 0, 4 * eta - 1, -4 * xi, 4 * xi, 4 * (l0 - eta)};
      Vec2 jx = Vec2::Zero(), je = Vec2::Zero();
      for (int j = 0; j < 6; ++j) {
        jx += dxi[j] * xy[t.n[j]];
        je += deta[j] * xy[t.n[j]];
      }
      if (geometry::Cross(jx, je) < 0.02 * area2) bad = true;
    }
    if (!bad) continue;
    for (int j = 0; j < 3; ++j) xy[t.n[3 + j]] = 0.5 * (xy[t.n[j]] + xy[t.n[(j + 1) % 3]]);
    ++straightened;
  }

  return straightened;
}

// The crack's faces: every node on the crack curve but the tip's gets a copy, taken by the
// elements on the left of the path (mouth → tip); the faces are then free surfaces (open).
// `body`: the cracked gear's (0 or 1). Returns the number of copies.
int OpenCrack(const GearModel& cracked, int body, const CrackAxis& axis, DeckMesh& dm) {
  std::vector<Vec2>& xy = dm.xy;
  const Vec2& mouth_xy = axis.mouth;
  const Vec2& crack_dir = axis.dir;
  const double crack_len = axis.length;
  std::vector<std::size_t> tags;
  std::vector<double> c, u;
  gmsh::model::mesh::getNodes(tags, c, u, 1, cracked.crack_curve, true, false);
  std::map<int, int> copy_of;
  for (std::size_t tag : tags) {
    const int i = dm.index.at(tag);
    if ((xy[i] - cracked.tip_xy).norm() < 1e-9 * std::max(1.0, crack_len)) continue;
    if (copy_of.count(i)) continue;
    copy_of[i] = static_cast<int>(xy.size());
    xy.push_back(xy[i]);
  }
  if (copy_of.size() < 3)
    throw std::runtime_error("fe deck: the crack has " + std::to_string(copy_of.size()) +
                             " mesh nodes: it was not embedded in the mesh");
  for (Tri& t : dm.tris) {
    if (t.body != body) continue;
    bool touches = false;
    for (int j = 0; j < 6; ++j) touches = touches || copy_of.count(t.n[j]);
    if (!touches) continue;
    const Vec2 centroid = (xy[t.n[0]] + xy[t.n[1]] + xy[t.n[2]]) / 3.0;
    if (geometry::Cross(crack_dir, centroid - mouth_xy) <= 0) continue;
    for (int j = 0; j < 6; ++j) {
      const auto it = copy_of.find(t.n[j]);
      if (it != copy_of.end()) t.n[j] = it->second;
    }
  }
  dm.edge_of.clear();
  for (std::size_t id = 0; id < dm.tris.size(); ++id)
    for (int j = 0; j < 3; ++j) {
      const int a = dm.tris[id].n[j], b = dm.tris[id].n[(j + 1) % 3];
      dm.edge_of[{std::min(a, b), std::max(a, b)}] = {static_cast<int>(id), j};
    }
  return static_cast<int>(copy_of.size());
}

// The slab of the plane mesh, 1 mm thick: node ids bottom i+1, top n2+i+1, mid-thickness
// 2·n2+i+1 (corner nodes only).
struct Slab {
  int n2 = 0;
  std::vector<char> corner;
  int bottom(int i) const { return i + 1; }
  int top(int i) const { return n2 + i + 1; }
  int middle(int i) const { return 2 * n2 + i + 1; }
  // The slab nodes above plane node i.
  void Each(int i, const std::function<void(int)>& emit) const {
    emit(bottom(i));
    emit(top(i));
    if (corner[i]) emit(middle(i));
  }
};

// The *NODE and *ELEMENT blocks (C3D15 wedges over the triangles, one ELSET per gear). Returns
// the number of nodes.
int WriteNodesAndElements(std::ostream& f, const DeckMesh& dm, const Slab& slab, double t_mm) {
  const std::vector<Vec2>& xy = dm.xy;
  auto bottom = [&](int i) { return slab.bottom(i); };
  auto top = [&](int i) { return slab.top(i); };
  auto middle = [&](int i) { return slab.middle(i); };
  int nodes = 0;
  for (int i = 0; i < slab.n2; ++i) {
    f << bottom(i) << ", " << xy[i].x() << ", " << xy[i].y() << ", 0\n";
    f << top(i) << ", " << xy[i].x() << ", " << xy[i].y() << ", " << t_mm << "\n";
    nodes += 2;
    if (slab.corner[i]) {
      f << middle(i) << ", " << xy[i].x() << ", " << xy[i].y() << ", " << 0.5 * t_mm << "\n";
      ++nodes;
    }
  }
  for (int body = 0; body < 2; ++body) {
    f << "*ELEMENT, TYPE=C3D15, ELSET=GEAR" << body + 1 << "\n";
    for (std::size_t e = 0; e < dm.tris.size(); ++e) {
      const Tri& t = dm.tris[e];
      if (t.body != body) continue;
      const auto& n = t.n;
      f << e + 1 << ", " << bottom(n[0]) << ", " << bottom(n[1]) << ", " << bottom(n[2]) << ", "
        << top(n[0]) << ", " << top(n[1]) << ", " << top(n[2]) << ", " << bottom(n[3]) << ", "
        << bottom(n[4]) << ", " << bottom(n[5]) << ",\n"
        << top(n[3]) << ", " << top(n[4]) << ", " << top(n[5]) << ", " << middle(n[0]) << ", "
        << middle(n[1]) << ", " << middle(n[2]) << "\n";
    }
  }
  return nodes;
}

// The plane nodes on a gear's hub curve, sorted, each once.
std::vector<int> HubNodes(const GearModel& g, const DeckMesh& dm) {
  std::vector<std::size_t> tags;
  std::vector<double> c, u;
  gmsh::model::mesh::getNodes(tags, c, u, 1, g.hub_curve, true, false);
  std::vector<int> out;
  for (std::size_t tag : tags) out.push_back(dm.index.at(tag));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// A *NSET block, ten ids a line.
void WriteNodeSet(std::ostream& f, const std::string& name, const std::vector<int>& ids) {
  f << "*NSET, NSET=" << name << "\n";
  for (std::size_t i = 0; i < ids.size(); ++i)
    f << ids[i] << (i + 1 == ids.size() || i % 10 == 9 ? "\n" : ", ");
}

// Fillet nodes (corner and mid-side nodes of the fillet curves, z = 0 layer): their place along
// the fillet and the surface tangent, from the exact profile (the nodes lie on the splines
// through it, within a micrometre), appended to info.fillet_nodes. Returns their slab ids,
// sorted, each once.
std::vector<int> FilletNodes(const std::vector<FilletLine>& fillet_lines, const GearModel& m1,
                             const GearModel& m2, const DeckMesh& dm, const Slab& slab,
                             FeDeckInfo& info) {
  const std::vector<Vec2>& xy = dm.xy;
  std::vector<int> fillet_ids;
  for (const FilletLine& line : fillet_lines) {
    const GearModel& g = line.gear == 1 ? m1 : m2;
    std::set<int> seen;
    for (int curve : g.fillet_curves.at({line.tooth, line.side})) {
      std::vector<std::size_t> tags;
      std::vector<double> c, u;
      gmsh::model::mesh::getNodes(tags, c, u, 1, curve, true, false);
      for (std::size_t tag : tags) {
        const int i = dm.index.at(tag);
        if (!seen.insert(i).second) continue;
        FeFilletNode n;
        n.gear = line.gear;
        n.tooth = line.tooth;
        n.side = line.side;
        n.node = slab.bottom(i);
        double arc = 0, distance = 0;
        Vec2 t = Vec2::Zero();
        line.Project(xy[i], &arc, &t, &distance);
        if (distance > 1e-3)
          throw std::runtime_error("fe deck: fillet node " + std::to_string(n.node) + " lies " +
                                   Num(distance, 13) + " mm off its fillet");
        n.arc_length = arc / kMm;
        n.tx = t.x();
        n.ty = t.y();
        info.fillet_nodes.push_back(n);
        fillet_ids.push_back(n.node);
      }
    }
  }
  std::sort(fillet_ids.begin(), fillet_ids.end());
  fillet_ids.erase(std::unique(fillet_ids.begin(), fillet_ids.end()), fillet_ids.end());
  if (fillet_ids.empty()) throw std::runtime_error("fe deck: no fillet node");
  return fillet_ids;
}

// Contact surfaces: the triangle edges (triangle, edge) on the flank curves within `reach` of
// the pair's rigid contact points (the Hertzian half-width is ~0.1 mm and the contact moves
// less than that under load; the whole flank as slave makes CalculiX's contact search drop
// far-off contact elements a few per iteration, tens of iterations per step).
std::vector<std::pair<int, int>> FlankFaces(const std::string& name, const std::vector<int>& curves,
                                            const std::vector<Vec2>& near, double reach,
                                            const DeckMesh& dm) {
  const std::vector<Vec2>& xy = dm.xy;
  std::vector<std::pair<int, int>> faces;
  for (int curve : curves) {
    std::vector<std::size_t> tags, en;
    gmsh::model::mesh::getElementsByType(8, tags, en, curve);
    for (std::size_t e = 0; e < tags.size(); ++e) {
      const int a = dm.index.at(en[3 * e]), b = dm.index.at(en[3 * e + 1]);
      const Vec2 mid = 0.5 * (xy[a] + xy[b]);
      double d = 1e300;
      for (const Vec2& c : near) d = std::min(d, (mid - c).norm());
      if (d > reach) continue;
      const auto it = dm.edge_of.find({std::min(a, b), std::max(a, b)});
      if (it == dm.edge_of.end())
        throw std::runtime_error("fe deck: a flank edge of " + name + " has no triangle");
      faces.push_back(it->second);
    }
  }
  if (faces.empty()) throw std::runtime_error("fe deck: surface " + name + " has no faces");
  return faces;
}

// The wedge faces over FlankFaces (the slab's elements are numbered as the triangles).
void WriteSurface(std::ostream& f, const std::string& name, const std::vector<int>& curves,
                  const std::vector<Vec2>& near, double reach, const DeckMesh& dm) {
  f << "*SURFACE, NAME=" << name << ", TYPE=ELEMENT\n";
  for (const auto& [tri, edge] : FlankFaces(name, curves, near, reach, dm))
    f << tri + 1 << ", S" << edge + 3 << "\n";
}

ToothZone MakeToothZone(const geometry::Gear& gear, const geometry::GearPose& pose,
                        const std::set<int>& loaded, const FeMeshOptions& mesh) {
  const double m = gear.module() * kMm;
  ToothZone zone;
  zone.centre = pose.geometric_centre * kMm;
  zone.rotation = pose.rotation;
  zone.pitch = gear.pitch_angle();
  zone.half_width = (mesh.tooth_zone + 0.5) * gear.pitch_angle();
  zone.teeth.assign(loaded.begin(), loaded.end());
  const double root = gear.root_radius() * kMm, tip = gear.tip_radius() * kMm;
  zone.r_in = gear.internal() ? tip : root - 2 * m;
  zone.r_out = gear.internal() ? root + 2 * m : tip;
  return zone;
}

void SetPlaneMeshOptions() {
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm", 6);
  gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);
}

// The material, the surface interaction and one frictionless contact pair per entry of `pairs`.
void WriteMaterialAndPairs(std::ostream& f, const transmission::Scene& scene,
                           const FeContactOptions& contact, const std::vector<FeToothPair>& pairs) {
  const transmission::Material& mat = scene.material;
  f << "*MATERIAL, NAME=STEEL\n*ELASTIC\n"
    << Num(mat.youngs_modulus / 1e6, 13) << ", " << Num(mat.poisson_ratio, 13) << "\n"
    << "*SOLID SECTION, ELSET=GEAR1, MATERIAL=STEEL\n"
    << "*SOLID SECTION, ELSET=GEAR2, MATERIAL=STEEL\n"
    << "*SURFACE INTERACTION, NAME=FLANKS\n"
    << "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
    << Num(contact.penalty, 13) << ", " << Num(contact.tension, 13) << "\n";
  for (const FeToothPair& p : pairs)
    f << "*CONTACT PAIR, INTERACTION=FLANKS, TYPE=SURFACE TO SURFACE\n"
      << p.slave << ", " << p.master << "\n";
}

// A step's start (one fixed increment: each step starts from the last, near its answer; ccx's
// automatic stepping would add a spurious 1e-6 increment at the end of the step) and gear 1's hub
// turned rigidly by θ about c_1 in the plane.
void WriteStepAndHubRotation(std::ostream& f, double theta, const FeDeckInfo& info) {
  f << "*STEP, INC=1000\n*STATIC, DIRECT\n1., 1.\n*BOUNDARY\n";
  for (std::size_t i = 0; i < info.hub_nodes.size(); ++i)
    f << info.hub_nodes[i] << ", 1, 1, " << Num(-theta * info.hub_y[i], 13) << "\n"
      << info.hub_nodes[i] << ", 2, 2, " << Num(theta * info.hub_x[i], 13) << "\n";
}

// The step's outputs: the hub reactions, `more` (further output requests), every pair's contact
// force; then its end.
void WriteStepOutputAndEnd(std::ostream& f, const FeDeckInfo& info, const char* more) {
  f << "*NODE PRINT, NSET=HUB1\nRF\n" << more;
  for (const FeToothPair& p : info.pairs)  // CF needs the pair named (ccx 2.20)
    f << "*CONTACT PRINT, SLAVE=" << p.slave << ", MASTER=" << p.master << "\nCF\n";
  f << "*END STEP\n";
}

// The material, the contact pairs, the plane-strain boundary and one step per rotation of gear 1's
// hub (gear 2 held at its hub; ring: rim).
void WriteSteps(std::ostream& f, const transmission::Scene& scene, const FeContactOptions& contact,
                const std::vector<double>& rotations, const FeDeckInfo& info) {
  WriteMaterialAndPairs(f, scene, contact, info.pairs);
  // Plane strain: u_z = 0 everywhere; gear 2 held at its hub (ring: rim).
  f << "*BOUNDARY\nNALL, 3, 3\nHUB2, 1, 2\n";
  for (double theta : rotations) {
    WriteStepAndHubRotation(f, theta, info);
    WriteStepOutputAndEnd(f, info, "*EL FILE, NSET=FILLETS\nS\n");
  }
}

}  // namespace detail

FeDeckInfo WriteDeck(const transmission::Scene& scene, const geometry::GearPair& pair,
                     double torque, double angle, const std::vector<double>& rotations,
                     const FeMeshOptions& mesh, const FeContactOptions& contact,
                     const std::string& directory, const FeDamage& damage) {
  CheckDeckInput(pair, torque, rotations, mesh, damage);
  const geometry::Gear& g1 = pair.gear1();
  const geometry::Gear& g2 = pair.gear2();
  const geometry::PairPoses poses = pair.Poses(angle);
  const FeCrack* crack = damage.crack ? &*damage.crack : nullptr;
  const FeSpall* spall = damage.spall ? &*damage.spall : nullptr;

  // The tooth pairs in or near contact on the loaded flanks.
  const LoadedContacts lc = FindLoadedContacts(pair, poses, contact);
  const auto& contact_points = lc.contact_points;
  const auto& teeth1 = lc.teeth1;
  const auto& teeth2 = lc.teeth2;
  const double m = g1.module() * kMm;
  const double h_c = mesh.contact_size * kMm / mesh.refinement;
  const double r0 = mesh.contact_radius * kMm;
  const double h_tooth = mesh.tooth_size_per_module * m / mesh.refinement;
  const double h_body = mesh.body_size_per_module * m / mesh.refinement;
  const ToothZone zone1 = MakeToothZone(g1, poses.gear1, teeth1, mesh);
  const ToothZone zone2 = MakeToothZone(g2, poses.gear2, teeth2, mesh);
  auto fine_of = [&](const geometry::Gear& g, const std::set<int>& loaded) {
    std::set<int> fine;
    for (int k : loaded)
      for (int d = -mesh.tooth_zone - 1; d <= mesh.tooth_zone + 1; ++d)
        fine.insert(((k + d) % g.teeth() + g.teeth()) % g.teeth());
    return fine;
  };

  // The fillets whose stress is read: both sides of the loaded teeth and their fillet_zone
  // neighbours, meshed at h_f (the stress peaks there; the contact and tooth sizes do not reach
  // it).
  const double h_f = mesh.fillet_size_per_module * m / mesh.refinement;
  std::vector<FilletLine> fillet_lines;
  auto add_fillets = [&](const geometry::Gear& g, const geometry::GearPose& pose, int which,
                         const std::set<int>& loaded) {
    std::set<int> teeth;
    for (int k : loaded)
      for (int d = -mesh.fillet_zone; d <= mesh.fillet_zone; ++d)
        teeth.insert(((k + d) % g.teeth() + g.teeth()) % g.teeth());
    for (int k : teeth)
      for (int side : {-1, 1}) fillet_lines.push_back(MakeFilletLine(g, pose, which, k, side));
  };
  add_fillets(g1, poses.gear1, 1, teeth1);
  add_fillets(g2, poses.gear2, 2, teeth2);
  const std::vector<FilletZone> fillet_zones = FilletZones(fillet_lines);

  GmshSession session;
  const GearModel m1 = BuildGear(g1, poses.gear1, fine_of(g1, teeth1), mesh.points_per_segment,
                                 crack && crack->gear == 1 ? crack : nullptr,
                                 spall && spall->gear == 1 ? spall : nullptr, nullptr);
  const GearModel m2 = BuildGear(g2, poses.gear2, fine_of(g2, teeth2), mesh.points_per_segment,
                                 crack && crack->gear == 2 ? crack : nullptr,
                                 spall && spall->gear == 2 ? spall : nullptr, nullptr);
  gmsh::model::occ::synchronize();
  // The crack: its curve embedded in its gear's surface (the mesh keeps it as element sides).
  const GearModel* cracked = crack ? (crack->gear == 1 ? &m1 : &m2) : nullptr;
  const CrackAxis axis = cracked ? EmbedCrack(*cracked) : CrackAxis{};
  const Vec2& mouth_xy = axis.mouth;
  const Vec2& crack_dir = axis.dir;
  const double crack_len = axis.length;
  const double h_tip = crack ? crack->tip_size * kMm / mesh.refinement : 0.0;
  const double h_crack = crack ? crack->face_size_per_module *
                                     (crack->gear == 1 ? g1 : g2).module() * kMm / mesh.refinement
                               : 0.0;
  SetPlaneMeshOptions();
  // Size: the smallest of the contact refinement, the tooth zone of the entity's gear and h_body.
  gmsh::model::mesh::setSizeCallback([&](int dim, int tag, double x, double y, double) {
    double s = h_body;
    for (const Vec2& c : contact_points)
      s = std::min(s, h_c + mesh.grading * std::max(0.0, std::hypot(x - c.x(), y - c.y()) - r0));
    const bool on1 = (dim == 2 && tag == m1.surface) || (dim == 1 && m1.curves.count(tag));
    const bool on2 = (dim == 2 && tag == m2.surface) || (dim == 1 && m2.curves.count(tag));
    if (cracked && (cracked == &m1 ? on1 || !on2 : on2 || !on1)) {
      // h_tip at the tip growing by tip_grading with the distance; h_crack along the faces.
      const Vec2 p(x, y);
      const double u = std::clamp((p - mouth_xy).dot(crack_dir), 0.0, crack_len);
      const double to_path = (p - (mouth_xy + u * crack_dir)).norm();
      s = std::min({s, h_tip + crack->tip_grading * (p - cracked->tip_xy).norm(),
                    h_crack + mesh.grading * to_path});
    }
    if (on1 || !on2) s = std::min(s, h_tooth + mesh.grading * zone1.Distance(x, y));
    if (on2 || !on1) s = std::min(s, h_tooth + mesh.grading * zone2.Distance(x, y));
    for (const FilletZone& z : fillet_zones) {
      if ((z.gear == 1 && on2 && !on1) || (z.gear == 2 && on1 && !on2)) continue;
      const double bx = std::max({0.0, z.lo.x() - x, x - z.hi.x()});
      const double by = std::max({0.0, z.lo.y() - y, y - z.hi.y()});
      if (h_f + mesh.grading * std::hypot(bx, by) >= s) continue;
      for (const Vec2& q : z.points)
        s = std::min(s, h_f + mesh.grading * std::hypot(x - q.x(), y - q.y()));
    }
    return s;
  });
  gmsh::model::mesh::generate(2);
  gmsh::model::mesh::setOrder(2);

  // Nodes of the triangles, compacted to 0-based indices, and the triangles.
  DeckMesh dm = ReadDeckMesh(m1, m2);
  const int straightened = StraightenInvertedTriangles(dm);
  const int crack_nodes = cracked ? OpenCrack(*cracked, cracked == &m1 ? 0 : 1, axis, dm) : 0;
  const int n2 = static_cast<int>(dm.xy.size());
  const std::vector<Vec2>& xy = dm.xy;

  // Slab node ids: bottom i+1, top n2+i+1, mid-thickness 2·n2+i+1 (corner nodes only).
  Slab slab;
  slab.n2 = n2;
  slab.corner.assign(n2, 0);
  for (const Tri& t : dm.tris)
    for (int j = 0; j < 3; ++j) slab.corner[t.n[j]] = 1;
  const double t_mm = 1.0;  // slab thickness: 1 mm, forces per mm of face width

  FeDeckInfo info;
  info.thickness = t_mm / kMm;
  info.face_width = geometry::ContactFaceWidth(g1, g2);
  info.torque = torque;
  info.base_radius1 = g1.base_radius();
  info.angle = angle;
  info.rotations = rotations;
  info.nodes_2d = n2;
  info.triangles = static_cast<int>(dm.tris.size());
  info.straightened = straightened;
  info.crack_nodes = crack_nodes;
  for (auto& [key, p] : lc.by_teeth) info.pairs.push_back(p);

  std::filesystem::create_directories(directory);
  const std::string deck_path = directory + "/deck.inp";
  std::ofstream f(deck_path);
  if (!f) throw std::runtime_error(deck_path + ": cannot be written");
  f.precision(13);
  f << "** epicycle FE contact reference (verification/fe_reference): " << scene.name << "\n"
    << "** gear-1 angle " << Num(geometry::Deg(angle), 13) << " deg, torque on gear 1 "
    << Num(torque, 13) << " N m over b = " << Num(info.face_width * kMm, 13)
    << " mm; slab t = 1 mm; units mm, N, MPa\n"
    << "*NODE, NSET=NALL\n";
  info.nodes = WriteNodesAndElements(f, dm, slab, t_mm);
  info.elements = static_cast<int>(dm.tris.size());

  // Hub node sets: every slab node above a hub-curve node.
  const Vec2 c1 = poses.gear1.rotation_centre * kMm;
  for (int i : HubNodes(m1, dm)) {
    slab.Each(i, [&](int id) {
      info.hub_nodes.push_back(id);
      info.hub_x.push_back(xy[i].x() - c1.x());
      info.hub_y.push_back(xy[i].y() - c1.y());
    });
  }
  WriteNodeSet(f, "HUB1", info.hub_nodes);
  std::vector<int> hub2_ids;
  for (int i : HubNodes(m2, dm)) slab.Each(i, [&](int id) { hub2_ids.push_back(id); });
  WriteNodeSet(f, "HUB2", hub2_ids);
  WriteNodeSet(f, "FILLETS", FilletNodes(fillet_lines, m1, m2, dm, slab, info));

  for (const FeToothPair& p : info.pairs) {
    const std::vector<Vec2>& near = lc.points_of.at({p.tooth1, p.tooth2});
    WriteSurface(f, p.slave, m1.flank_curves.at({p.tooth1, lc.side1}), near,
                 contact.slave_reach * kMm, dm);
    WriteSurface(f, p.master, m2.flank_curves.at({p.tooth2, lc.side2}), near,
                 contact.master_reach * kMm, dm);
  }
  WriteSteps(f, scene, contact, rotations, info);
  if (!f) throw std::runtime_error(deck_path + ": write failed");
  info.Write(directory + "/deck.info");
  return info;
}

}  // namespace epicycle::fe_reference

namespace epicycle::fe_reference {

std::optional<FeSpall> SpallOfScene(const transmission::Scene& scene) {
  const std::vector<transmission::Pit>& pits = scene.damage.pits;
  if (pits.empty()) return std::nullopt;
  if (pits.size() > 1)
    throw std::invalid_argument("fe deck: damage.pit: " + std::to_string(pits.size()) +
                                " pits: the deck takes one");
  const transmission::Pit& p = pits.front();
  if (p.width_fraction < 1)
    throw std::invalid_argument(p.where + ": width_fraction = " + Num(p.width_fraction, 13) +
                                ": the plane-strain deck takes a spall over the whole face (1)");
  if (p.gear != "gear1" && p.gear != "gear2")
    throw std::invalid_argument(p.where + ": gear = '" + p.gear + "': must be gear1 or gear2");
  FeSpall s;
  s.gear = p.gear == "gear1" ? 1 : 2;
  s.tooth = p.tooth;
  s.side = p.flank;
  s.roll_from = p.roll_from;
  s.roll_to = p.roll_to;
  s.depth = p.depth;
  return s;
}

double IsoRootChord(const geometry::Gear& gear) {
  compliance::RootCrack c;
  c.start_arc = compliance::IsoCriticalFilletArc(gear);
  return 2.0 * std::abs(c.Points(gear).front().y());
}

}  // namespace epicycle::fe_reference
