#include "epicycle/compliance/root_crack.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/io/number_format.hpp"

namespace epicycle::compliance {
namespace {

constexpr double kPi = 3.14159265358979323846;

using io::Num;

std::string Mm(const Eigen::Vector2d& x) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << x.x() * 1e3 << ", " << x.y() * 1e3 << ") mm";
  return s.str();
}

// The outline of tooth 0's body sector as a closed polygon (body frame), each edge labelled by the
// part of the body it bounds.
struct Outline {
  std::vector<Eigen::Vector2d> point;
  std::vector<std::string> part;  // part[i]: the edge point[i] → point[i + 1]
};

Outline SectorOutline(const geometry::Gear& gear, const ProfilePath& path) {
  constexpr int kProfilePoints = 600;
  const double hp = gear.pitch_angle() / 2.0, r_hub = gear.spec().hub_radius;
  const std::string hub = gear.internal() ? "outer rim" : "hub";
  const std::string space = "space centre line (neighbouring tooth)";
  const double s_form = path.RoleStart(geometry::SegmentRole::kInvolute);
  Outline o;
  auto add = [&](const Eigen::Vector2d& x, const std::string& part) {
    o.point.push_back(x);
    o.part.push_back(part);
  };
  add(r_hub * Eigen::Vector2d(std::cos(hp), std::sin(hp)), space);
  auto label = [&](double s, int sigma) {
    return std::string(s < s_form ? "fillet" : "flank") + (sigma > 0 ? " +" : " -");
  };
  for (int k = 0; k < kProfilePoints; ++k) {
    const double s = path.length() * k / kProfilePoints;
    add(path.Point(s), label(s, 1));
  }
  for (int k = kProfilePoints; k > 0; --k) {
    const double s = path.length() * k / kProfilePoints;
    const Eigen::Vector2d x = path.Point(s);
    add({x.x(), -x.y()}, label(s, -1));
  }
  const Eigen::Vector2d r0 = path.Point(0.0);
  add({r0.x(), -r0.y()}, space);
  constexpr int kArc = 64;
  for (int k = 0; k < kArc; ++k) {
    const double a = -hp + 2.0 * hp * k / kArc;
    add(r_hub * Eigen::Vector2d(std::cos(a), std::sin(a)), hub);
  }
  return o;
}

bool Inside(const Outline& o, const Eigen::Vector2d& q) {
  bool in = false;
  const std::size_t n = o.point.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& a = o.point[i];
    const Eigen::Vector2d& b = o.point[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

double Distance(const Outline& o, const Eigen::Vector2d& q, std::string* part) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = o.point.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = o.point[i];
    const Eigen::Vector2d e = o.point[(i + 1) % n] - a;
    const double t = std::clamp((q - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const double d = (a + t * e - q).norm();
    if (d < best) {
      best = d;
      *part = o.part[i];
    }
  }
  return best;
}

[[noreturn]] void Fail(const std::string& field, const std::string& value,
                       const std::string& rule) {
  throw std::invalid_argument("RootCrack." + field + " = " + value + ": " + rule);
}

}  // namespace

double RootCrack::depth() const {
  double q = 0.0;
  for (const CrackSegment& s : path) q += s.length;
  return q;
}

std::vector<Eigen::Vector2d> RootCrack::Points(const geometry::Gear& gear) const {
  const ProfilePath profile(gear);
  const double kappa = gear.internal() ? -1.0 : 1.0;
  const double sigma = side > 0 ? 1.0 : -1.0;
  Eigen::Vector2d x = profile.Point(start_arc);
  x.y() *= sigma;
  std::vector<Eigen::Vector2d> out = {x};
  for (const CrackSegment& s : path) {
    const Eigen::Vector2d d(-kappa * std::cos(s.angle), -sigma * std::sin(s.angle));
    x += s.length * d;
    out.push_back(x);
  }
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(tooth * gear.pitch_angle()).toRotationMatrix();
  for (Eigen::Vector2d& p : out) p = (r * p).eval();
  return out;
}

void RootCrack::Validate(const geometry::Gear& gear) const {
  const int z = gear.teeth();
  if (tooth < 0 || tooth >= z)
    Fail("tooth", std::to_string(tooth),
         "must be in [0, " + std::to_string(z) + ") (the teeth of '" + gear.name() + "')");
  if (side != 1 && side != -1) Fail("side", std::to_string(side), "must be +1 or -1");
  const ProfilePath profile(gear);
  const double s_form = profile.RoleStart(geometry::SegmentRole::kInvolute);
  if (!(std::isfinite(start_arc) && start_arc > 0.0 && start_arc < s_form))
    Fail("start_arc", Num(start_arc, 9) + " m",
         "must be in (0, " + Num(s_form, 9) +
             ") m, the fillet from the space centre line to the form point of '" + gear.name() +
             "'");
  if (path.empty() || static_cast<int>(path.size()) > kMaxSegments)
    Fail("path", std::to_string(path.size()) + " segments",
         "must have 1 to " + std::to_string(kMaxSegments) + " segments");
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string at = "path[" + std::to_string(i) + "]";
    if (!(std::isfinite(path[i].length) && path[i].length > 0.0))
      Fail(at + ".length", Num(path[i].length, 9) + " m", "must be finite and > 0");
    if (!(std::isfinite(path[i].angle) && path[i].angle > 0.0 && path[i].angle < kPi))
      Fail(at + ".angle", Num(path[i].angle, 9) + " rad",
           "must be in (0, pi): the crack runs across the tooth (angle to its centre line)");
  }
  // The path inside tooth 0's sector (the points turned back from tooth k).
  const Outline outline = SectorOutline(gear, profile);
  const Eigen::Matrix2d back = Eigen::Rotation2Dd(-tooth * gear.pitch_angle()).toRotationMatrix();
  const std::vector<Eigen::Vector2d> pts = Points(gear);
  const double clearance = kClearance * gear.module();
  double travelled = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector2d a = back * pts[i], b = back * pts[i + 1];
    const int samples = std::max(16, static_cast<int>(std::ceil(4.0 * path[i].length / clearance)));
    for (int k = (i == 0 ? 1 : 0); k <= samples; ++k) {
      const double t = static_cast<double>(k) / samples;
      const Eigen::Vector2d q = a + t * (b - a);
      const double ell = travelled + t * path[i].length;
      std::string part;
      const double d = Distance(outline, q, &part);
      const double need = std::min(ell * std::sin(kMinMouthAngle), clearance);
      if (!Inside(outline, q) || d < need) {
        std::ostringstream rule;
        rule << "the crack leaves the body of tooth " << tooth << " of '" << gear.name()
             << "' or comes too near its outline: the point " << Mm(q) << " (tooth 0's frame) at "
             << ell * 1e3 << " mm along the path is " << (Inside(outline, q) ? "" : "outside, ")
             << d * 1e3 << " mm from the " << part
             << "; the rule is that every point of the path lies inside the tooth's sector, at "
                "least min(l sin 10 deg, "
             << kClearance << " m) = " << need * 1e3
             << " mm from its outline (l the distance along the path; m the module)";
        Fail("path[" + std::to_string(i) + "]",
             "{length " + Num(path[i].length, 9) + " m, angle " + Num(path[i].angle, 9) + " rad}",
             rule.str());
      }
    }
    travelled += path[i].length;
  }
}

double IsoCriticalFilletArc(const geometry::Gear& gear) {
  const ProfilePath profile(gear);
  const double s_form = profile.RoleStart(geometry::SegmentRole::kInvolute);
  const double target = (gear.internal() ? 60.0 : 30.0) * kPi / 180.0;
  // Angle between the tangent's line and the centre line (x axis of tooth 0) minus the target:
  // from the form point (small angle on the flank side) toward the root (≈ 90° on the root land).
  auto f = [&](double s) {
    const Eigen::Vector2d t = profile.Tangent(s);
    return std::acos(std::min(1.0, std::abs(t.x()))) - target;
  };
  constexpr int kScan = 400;
  double hi = s_form, f_hi = f(hi);
  for (int k = kScan - 1; k >= 0; --k) {
    const double lo = s_form * k / kScan, f_lo = f(lo);
    if ((f_lo >= 0.0) != (f_hi >= 0.0)) {
      double a = lo, b = hi;
      const bool rising = f_lo > f_hi;  // f(a) ≥ 0 > f(b)
      for (int it = 0; it < 100 && b - a > 1e-14 * s_form; ++it) {
        const double m = 0.5 * (a + b);
        ((f(m) >= 0.0) == rising ? a : b) = m;
      }
      return 0.5 * (a + b);
    }
    hi = lo;
    f_hi = f_lo;
  }
  throw std::invalid_argument("IsoCriticalFilletArc: the fillet of '" + gear.name() +
                              "' has no point whose tangent makes " + Num(target * 180.0 / kPi, 9) +
                              " deg with the tooth centre line");
}

double LargestRootTensionArc(const InfluenceTable& table, const geometry::Gear& gear,
                             const FlankPosition& load, int side) {
  if (!table.has_fillet_stress())
    throw std::invalid_argument(
        "LargestRootTensionArc: the influence table of '" + gear.name() +
        "' was built without fillet stresses (InfluenceTableOptions.fillet_stress = false)");
  if (side != 1 && side != -1)
    throw std::invalid_argument("LargestRootTensionArc: side = " + std::to_string(side) +
                                ": must be +1 or -1");
  const ProfilePath profile(gear);
  const double sigma = load.flank > 0 ? 1.0 : -1.0;
  Eigen::Vector2d n = profile.Normal(table.grid().form_arc + load.arc_length);
  n.y() *= sigma;
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(load.tooth * gear.pitch_angle()).toRotationMatrix();
  const InfluenceTable::DirectedNode node = table.PrepareDirected(load, -(r * n));
  const auto& points = table.fillet_points();
  std::vector<double> s(points.size(), 0.0);
  table.AddFilletStress(node, 1.0, load.tooth, side > 0 ? 0 : 1, s.data());
  const auto it = std::max_element(s.begin(), s.end());
  if (!(*it > 0.0))
    throw std::invalid_argument("LargestRootTensionArc: no point of the fillet of side " +
                                std::to_string(side) + " is in tension under that load");
  const std::size_t m = static_cast<std::size_t>(it - s.begin());
  if (m == 0 || m + 1 >= s.size()) return points[m].arc_length;
  // Vertex of the parabola through (x_{m−1}, s_{m−1}), (x_m, s_m), (x_{m+1}, s_{m+1}).
  const double x0 = points[m - 1].arc_length, x1 = points[m].arc_length,
               x2 = points[m + 1].arc_length;
  const double d01 = (s[m] - s[m - 1]) / (x1 - x0), d12 = (s[m + 1] - s[m]) / (x2 - x1);
  const double curvature = (d12 - d01) / (x2 - x0);
  if (!(curvature < 0.0)) return x1;
  return std::clamp(0.5 * (x0 + x1) - d01 / (2.0 * curvature), x0, x2);
}

double RootCrackStartArc(const geometry::Gear& gear, const InfluenceTable* table,
                         const FlankPosition& load, int side) {
  if (table != nullptr && table->has_fillet_stress())
    return LargestRootTensionArc(*table, gear, load, side);
  return IsoCriticalFilletArc(gear);
}

}  // namespace epicycle::compliance
