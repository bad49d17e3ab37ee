#include "epicycle/compliance/gear_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "epicycle/compliance/gmsh_mesher.hpp"
#include "epicycle/compliance/q8_element.hpp"

namespace epicycle::compliance {
namespace {

using geometry::SegmentRole;

constexpr int kArcTable = 128;  // arc-length table intervals per segment

std::string Str(double x) {
  std::ostringstream s;
  s.precision(9);
  s << x;
  return s.str();
}

std::string Pt(const Eigen::Vector2d& x) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << x.x() * 1e3 << ", " << x.y() * 1e3 << ") mm";
  return s.str();
}

Eigen::Vector2d Mirror(const Eigen::Vector2d& x) { return {x.x(), -x.y()}; }

// ds/dθ of a piece: |dx/dt| · |t1 − t0|.
double Speed(const geometry::Segment& seg, double theta) {
  const double t = seg.t0 + theta * (seg.t1 - seg.t0);
  return seg.Evaluate(t).d1.norm() * std::abs(seg.t1 - seg.t0);
}

double GaussArc(const geometry::Segment& seg, double a, double b) {
  const GaussRule g = GaussLegendre(5);
  double sum = 0.0;
  for (int k = 0; k < g.size; ++k) {
    sum += g.weights[k] * Speed(seg, 0.5 * (a + b) + 0.5 * (b - a) * g.points[k]);
  }
  return 0.5 * (b - a) * sum;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
ProfilePath::ProfilePath(const geometry::Gear& gear) : sign_(gear.internal() ? -1 : 1) {
  for (const auto& seg : gear.half_profile().segments) {
    Piece p;
    p.segment = &seg;
    p.s0 = total_;
    p.table.resize(kArcTable + 1, 0.0);
    for (int k = 0; k < kArcTable; ++k) {
      p.table[k + 1] = p.table[k] + GaussArc(seg, static_cast<double>(k) / kArcTable,
                                             static_cast<double>(k + 1) / kArcTable);
    }
    p.length = p.table.back();
    if (!(p.length > 0.0)) continue;  // a degenerate segment carries no arc
    total_ += p.length;
    pieces_.push_back(std::move(p));
  }
  if (pieces_.empty()) {
    throw std::invalid_argument("ProfilePath: gear '" + gear.name() + "' has an empty profile");
  }
}

bool ProfilePath::HasRole(SegmentRole role) const {
  return std::any_of(pieces_.begin(), pieces_.end(),
                     [&](const Piece& p) { return p.segment->role == role; });
}

double ProfilePath::RoleStart(SegmentRole role) const {
  for (const auto& p : pieces_) {
    if (p.segment->role == role) return p.s0;
  }
  throw std::invalid_argument("ProfilePath: the profile has no " + geometry::RoleName(role));
}

double ProfilePath::RoleEnd(SegmentRole role) const {
  for (auto it = pieces_.rbegin(); it != pieces_.rend(); ++it) {
    if (it->segment->role == role) return it->s0 + it->length;
  }
  throw std::invalid_argument("ProfilePath: the profile has no " + geometry::RoleName(role));
}

double ProfilePath::ArcWithin(const Piece& p, double theta) const {
  const double pos = std::clamp(theta, 0.0, 1.0) * kArcTable;
  const int k = std::min(static_cast<int>(pos), kArcTable - 1);
  return p.table[k] + GaussArc(*p.segment, static_cast<double>(k) / kArcTable, theta);
}

void ProfilePath::Locate(double s, int* piece, double* theta) const {
  s = std::clamp(s, 0.0, total_);
  int i = 0;
  while (i + 1 < static_cast<int>(pieces_.size()) && s > pieces_[i].s0 + pieces_[i].length) ++i;
  const Piece& p = pieces_[i];
  const double local = std::clamp(s - p.s0, 0.0, p.length);
  const auto it = std::upper_bound(p.table.begin(), p.table.end(), local);
  const int k = std::clamp(static_cast<int>(it - p.table.begin()) - 1, 0, kArcTable - 1);
  // Start from linear interpolation in the table, then Newton on s(θ) = local.
  const double span = p.table[k + 1] - p.table[k];
  double th = (k + (span > 0.0 ? (local - p.table[k]) / span : 0.0)) / kArcTable;
  for (int it2 = 0; it2 < 8; ++it2) {
    const double r = ArcWithin(p, th) - local;
    const double v = Speed(*p.segment, th);
    if (!(v > 0.0)) break;
    const double step = r / v;
    th = std::clamp(th - step, 0.0, 1.0);
    if (std::abs(step) < 1e-15) break;
  }
  *piece = i;
  *theta = th;
}

Eigen::Vector2d ProfilePath::Point(double s) const {
  int i;
  double th;
  Locate(s, &i, &th);
  const auto& seg = *pieces_[i].segment;
  return seg.Point(seg.t0 + th * (seg.t1 - seg.t0));
}

Eigen::Vector2d ProfilePath::Tangent(double s) const {
  int i;
  double th;
  Locate(s, &i, &th);
  const auto& seg = *pieces_[i].segment;
  const Eigen::Vector2d d = seg.Evaluate(seg.t0 + th * (seg.t1 - seg.t0)).d1;
  return (seg.t1 >= seg.t0 ? 1.0 : -1.0) * d.normalized();
}

Eigen::Vector2d ProfilePath::Normal(double s) const {
  const Eigen::Vector2d t = Tangent(s);
  return sign_ * Eigen::Vector2d(-t.y(), t.x());
}

double ProfilePath::Project(const Eigen::Vector2d& q, double s_lo, double s_hi, double* distance,
                            int scan) const {
  // Coarse scan, then Gauss–Newton along the arc (the curve is G1 and its pieces are smooth).
  const int n = std::max(1, scan);
  double best = s_lo, best_d = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= n; ++k) {
    const double s = s_lo + (s_hi - s_lo) * k / n;
    const double d = (Point(s) - q).norm();
    if (d < best_d) {
      best_d = d;
      best = s;
    }
  }
  double s = best;
  for (int it = 0; it < 30; ++it) {
    const double step = (q - Point(s)).dot(Tangent(s));
    const double next = std::clamp(s + step, s_lo, s_hi);
    const bool done = std::abs(next - s) < 1e-16 + 1e-13 * total_;
    s = next;
    if (done) break;
  }
  if (distance != nullptr) *distance = (Point(s) - q).norm();
  return s;
}

// ---------------------------------------------------------------------------------------------
void GearMeshOptions::Validate() const {
  auto fail = [](const std::string& field, const std::string& value, const std::string& rule) {
    throw std::invalid_argument("GearMeshOptions." + field + " = " + value + ": " + rule);
  };
  auto count = [&](const char* field, int v, int lo) {
    if (v < lo || v > 1000)
      fail(field, std::to_string(v), "must be in [" + std::to_string(lo) + ", 1000]");
  };
  count("involute_elements", involute_elements, 1);
  count("tip_round_elements", tip_round_elements, 1);
  count("tip_land_elements", tip_land_elements, 1);
  count("fillet_elements", fillet_elements, 1);
  count("band_layers", band_layers, 1);
  count("rim_layers", rim_layers, 1);
  count("refinement", refinement, 1);
  if (!(band_grading >= 1.0 && band_grading <= 100.0))
    fail("band_grading", Str(band_grading), "must be in [1, 100]");
  if (!(rim_grading >= 1.0 && rim_grading <= 100.0))
    fail("rim_grading", Str(rim_grading), "must be in [1, 100]");
  if (!(band_depth_fraction >= 0.1 && band_depth_fraction <= 0.6))
    fail("band_depth_fraction", Str(band_depth_fraction), "must be in [0.1, 0.6]");
  if (!(root_block_depth > 0.0 && root_block_depth < 2.0))
    fail("root_block_depth", Str(root_block_depth), "must be in (0, 2) modules");
  if (mesher != "mapped" && mesher != "gmsh")
    fail("mesher", "'" + mesher + "'", "must be \"mapped\" or \"gmsh\"");
  if (mesher == "gmsh" && !GmshMesher::Available()) {
    fail("mesher", "'gmsh'",
         "this build has no gmsh mesher (it was configured with EPICYCLE_WITH_GMSH=OFF; "
         "reconfigure with -DEPICYCLE_WITH_GMSH=ON, or use \"mapped\")");
  }
}

namespace {

// Everything that defines the upper half sector of tooth 0.
struct SectorPlan {
  double s_root = 0, s_j = 0, s_form = 0, s_t1 = 0, s_t2 = 0,
         s_tip = 0;  // arc lengths along the path
  int n_inv = 0, n_tr = 0, n_tl = 0, n_fil = 0, n_band = 0, n_rim = 0;
  std::vector<double> grid_s;  // path arc lengths of the flank grid points
  Eigen::Vector2d r0, f, t1, c, g, k, d, b, s_pt;
  double r_m = 0, r_hub = 0, half_pitch = 0;
};

SectorPlan Plan(const geometry::Gear& gear, const ProfilePath& path, const GearMeshOptions& o) {
  const std::string who = "gear mesh of '" + gear.name() + "': ";
  SectorPlan p;
  const int m = o.refinement;
  p.n_inv = o.involute_elements * m;
  p.n_tr =
      gear.has_tip_round() && path.HasRole(SegmentRole::kTipRound) ? o.tip_round_elements * m : 0;
  p.n_tl = o.tip_land_elements * m;
  p.n_fil = o.fillet_elements * m;
  p.n_band = o.band_layers * m;
  p.n_rim = o.rim_layers * m;
  p.half_pitch = gear.pitch_angle() / 2.0;
  p.s_root = 0.0;
  p.s_form = path.RoleStart(SegmentRole::kInvolute);
  p.s_j = path.HasRole(SegmentRole::kRootLand) ? path.RoleEnd(SegmentRole::kRootLand) : 0.0;
  p.s_t1 = path.RoleEnd(SegmentRole::kInvolute);
  p.s_t2 = p.n_tr > 0 ? path.RoleEnd(SegmentRole::kTipRound) : p.s_t1;
  p.s_tip = path.length();
  if (!(p.s_form > 0.0)) {
    throw std::invalid_argument(who +
                                "the involute starts at the space centre line (no root "
                                "land or fillet): the mapped mesh needs a fillet block");
  }
  if (!(p.s_tip > p.s_t2)) {
    throw std::invalid_argument(who + "the profile has no tip land: the mapped mesh needs one");
  }
  for (int i = 0; i <= 2 * p.n_inv; ++i) {
    p.grid_s.push_back(p.s_form + (p.s_t1 - p.s_form) * i / (2.0 * p.n_inv));
  }
  for (int i = 1; i <= 2 * p.n_tr; ++i) {
    p.grid_s.push_back(p.s_t1 + (p.s_t2 - p.s_t1) * i / (2.0 * p.n_tr));
  }
  p.r0 = path.Point(0.0);
  p.f = path.Point(p.s_form);
  p.t1 = path.Point(p.s_t1);
  p.c = path.Point(p.s_tip);
  const int kappa = gear.internal() ? -1 : 1;
  // Rim corner B on the axis below (ring: above) the root circle; G on the cut F→B.
  p.r_m = gear.root_radius() - kappa * o.root_block_depth * gear.module();
  p.r_hub = gear.spec().hub_radius;
  if (!gear.internal() && !(p.r_hub > 0.0 && p.r_hub < p.r_m - 0.5 * gear.module())) {
    throw std::invalid_argument(
        who + "hub_radius = " + Str(p.r_hub * 1e3) + " mm: the rule is 0 < hub radius < r_f − (" +
        Str(o.root_block_depth) + " + 0.5)·m = " + Str((p.r_m - 0.5 * gear.module()) * 1e3) +
        " mm (room for the rim below the fillet block)");
  }
  if (gear.internal() && !(p.r_hub > p.r_m + 0.5 * gear.module())) {
    throw std::invalid_argument(who + "rim radius (hub_radius) = " + Str(p.r_hub * 1e3) +
                                " mm: the rule is rim radius > r_f + (" + Str(o.root_block_depth) +
                                " + 0.5)·m = " + Str((p.r_m + 0.5 * gear.module()) * 1e3) + " mm");
  }
  p.b = Eigen::Vector2d(p.r_m, 0.0);
  p.s_pt = p.r_m * Eigen::Vector2d(std::cos(p.half_pitch), std::sin(p.half_pitch));
  p.g = p.f + o.band_depth_fraction * (p.b - p.f);
  const Eigen::Vector2d n1 = path.Normal(p.s_t1);
  if (!(n1.y() > 0.05)) {
    throw std::invalid_argument(who + "the flank normal at the tip-round tangency " + Pt(p.t1) +
                                " does not face away from the tooth centre line (n_y = " +
                                Str(n1.y()) + "); cannot place the tip band");
  }
  p.k = p.t1 - o.band_depth_fraction * (p.t1.y() / n1.y()) * n1;
  p.d = Eigen::Vector2d(p.k.x(), 0.0);
  // Sanity of the construction: D between B and C on the axis, K inside the tip.
  const double along_bd = kappa * (p.d.x() - p.b.x());
  const double along_dc = kappa * (p.c.x() - p.d.x());
  if (!(along_bd > 0.0 && along_dc > 0.0 && p.k.y() > 0.0 && p.g.y() > 0.0)) {
    throw std::invalid_argument(who + "cannot place the tooth core: B = " + Pt(p.b) +
                                ", D = " + Pt(p.d) + ", C = " + Pt(p.c) + ", G = " + Pt(p.g) +
                                ", K = " + Pt(p.k) +
                                " (the rule: B, D, C in this order along the axis, G "
                                "and K above it); try another band_depth_fraction");
  }
  return p;
}

// The path between arc lengths a and b as a patch side: t ∈ [0, 1] ↦ x(a + t (b − a)).
Curve PathCurve(const ProfilePath* path, double a, double b) {
  return [path, a, b](double t) -> Eigen::Vector2d { return path->Point(a + t * (b - a)); };
}

Curve MirroredCurve(Curve c) {
  return [c = std::move(c)](double t) -> Eigen::Vector2d { return Mirror(c(t)); };
}

std::vector<double> Fractions(const std::vector<double>& s) {
  std::vector<double> t(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) t[k] = (s[k] - s.front()) / (s.back() - s.front());
  t.front() = 0.0;
  t.back() = 1.0;
  return t;
}

std::vector<double> Reverse(const std::vector<double>& t) {
  std::vector<double> r(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) r[k] = 1.0 - t[t.size() - 1 - k];
  r.front() = 0.0;
  r.back() = 1.0;
  return r;
}

// Element boundaries along root land + fillet: the root-land/fillet junction J is one of them (no
// element straddles the curvature jump), equal arc lengths on either side.
std::vector<double> FilletBreaks(const SectorPlan& p) {
  std::vector<double> s;
  const int n_land =
      p.s_j > 0.0 ? std::max(1, static_cast<int>(std::lround(p.n_fil * p.s_j / p.s_form))) : 0;
  const int n_rest = std::max(1, p.n_fil - n_land);
  for (int e = 0; e <= n_land; ++e) s.push_back(p.s_j * e / std::max(1, n_land));
  if (n_land == 0) s.assign(1, 0.0);
  for (int e = 1; e <= n_rest; ++e) s.push_back(p.s_j + (p.s_form - p.s_j) * e / n_rest);
  return Fractions(s);
}

// The five patches of the upper half sector of tooth 0 (flank side names "flank").
std::vector<Patch> UpperHalf(const SectorPlan& p, const ProfilePath* path) {
  // Band along the involute: u at the flank grid's element corners (even grid points).
  std::vector<double> band_s;
  for (int e = 0; e <= p.n_inv; ++e) band_s.push_back(p.grid_s[2 * e]);
  const std::vector<double> band_u = Fractions(band_s);
  // Tip band: tip round at the grid's element corners, then the tip land equally.
  std::vector<double> tip_s;
  for (int e = 0; e <= p.n_tr; ++e) tip_s.push_back(p.grid_s[2 * (p.n_inv + e)]);
  for (int e = 1; e <= p.n_tl; ++e) tip_s.push_back(p.s_t2 + (p.s_tip - p.s_t2) * e / p.n_tl);
  const std::vector<double> tip_u = Fractions(tip_s);

  std::vector<Patch> out;
  Patch band;
  band.name = "band";
  band.sides = {PathCurve(path, p.s_form, p.s_t1), StraightLine(p.t1, p.k), StraightLine(p.g, p.k),
                StraightLine(p.f, p.g)};
  band.side_names = {"flank", "", "", ""};
  band.u.breaks = band_u;
  out.push_back(band);

  Patch tip;
  tip.name = "band";
  tip.sides = {PathCurve(path, p.s_t1, p.s_tip), StraightLine(p.c, p.d), StraightLine(p.k, p.d),
               StraightLine(p.t1, p.k)};
  tip.side_names = {"flank", "", "", ""};
  tip.u.breaks = tip_u;
  out.push_back(tip);

  Patch core;
  core.name = "core";
  core.sides = {StraightLine(p.b, p.d), StraightLine(p.d, p.k), StraightLine(p.g, p.k),
                StraightLine(p.b, p.g)};
  core.u.breaks = band_u;
  core.v.breaks = Reverse(tip_u);
  out.push_back(core);

  Patch fillet;
  fillet.name = "fillet";
  fillet.sides = {PathCurve(path, 0.0, p.s_form), StraightLine(p.f, p.b),
                  CircularArc({0.0, 0.0}, p.r_m, p.half_pitch, 0.0), StraightLine(p.r0, p.s_pt)};
  fillet.side_names = {"fillet", "", "", ""};
  fillet.u.breaks = FilletBreaks(p);
  out.push_back(fillet);

  Patch rim;
  rim.name = "rim";
  rim.sides = {CircularArc({0.0, 0.0}, p.r_hub, p.half_pitch, 0.0),
               StraightLine({p.r_hub, 0.0}, p.b), CircularArc({0.0, 0.0}, p.r_m, p.half_pitch, 0.0),
               StraightLine(p.r_hub * p.s_pt / p.r_m, p.s_pt)};
  rim.side_names = {"hub", "", "", ""};
  rim.u.breaks = FilletBreaks(p);
  out.push_back(rim);
  return out;
}

}  // namespace

FlankGrid MakeFlankGrid(const geometry::Gear& gear, const GearMeshOptions& options) {
  options.Validate();
  const ProfilePath path(gear);
  const SectorPlan p = Plan(gear, path, options);
  FlankGrid grid;
  grid.form_arc = p.s_form;
  for (double s : p.grid_s) {
    grid.arc_length.push_back(s - p.s_form);
    grid.position.push_back(path.Point(s));
    grid.normal.push_back(path.Normal(s));
  }
  grid.arc_length.front() = 0.0;
  return grid;
}

GearBodyMesh BuildGearMesh(const geometry::Gear& gear, const GearMeshOptions& options) {
  options.Validate();
  const ProfilePath path(gear);
  const SectorPlan p = Plan(gear, path, options);
  const std::string who = "gear mesh of '" + gear.name() + "': ";

  // Layer distributions: band graded toward the surface; the cut F→B carries the band layers
  // (F→G) then the core's layers (G→B), which are the tip band's u breaks reversed.
  const Distribution band_v = Distribution::Graded(p.n_band, options.band_grading);
  const std::vector<double> band_t = band_v.Parameters(who + "band layers");
  std::vector<Patch> half = UpperHalf(p, &path);
  Patch& band = half[0];
  Patch& tip = half[1];
  Patch& core = half[2];
  Patch& fillet = half[3];
  Patch& rim = half[4];
  band.v = band_v;
  tip.v = band_v;
  const double fg = (p.g - p.f).norm(), fb = (p.b - p.f).norm();
  std::vector<double> cut;
  for (double t : band_t) cut.push_back(t * fg / fb);
  const std::vector<double> core_v = core.v.breaks;  // B (0) → G (1)
  for (auto it = core_v.rbegin() + 1; it != core_v.rend(); ++it) {
    cut.push_back((fg + (1.0 - *it) * (fb - fg)) / fb);
  }
  cut.back() = 1.0;
  fillet.v.breaks = cut;
  // Rim: layers graded toward the root block (v = 1 at r_m).
  rim.v = Distribution::Graded(p.n_rim, 1.0 / options.rim_grading);

  // Lower half (mirror), then all teeth (rotations).
  std::vector<Patch> sector = half;
  for (const Patch& q : half) {
    Patch m = q;
    for (int s = 0; s < 4; ++s) m.sides[s] = MirroredCurve(q.sides[s]);
    for (auto& name : m.side_names) {
      if (name == "flank" || name == "fillet") name += "-";
    }
    sector.push_back(m);
  }
  for (int s = 0; s < 5; ++s) {
    for (auto& name : sector[s].side_names) {
      if (name == "flank" || name == "fillet") name += "+";
    }
  }
  Region region;
  const int z = gear.teeth();
  for (int k = 0; k < z; ++k) {
    for (const Patch& q : sector) {
      Patch r = Rotated(q, k * gear.pitch_angle());
      for (auto& name : r.side_names) {
        if (name == "flank+" || name == "flank-" || name == "fillet+" || name == "fillet-") {
          name = name.substr(0, name.size() - 1) + std::to_string(k) + name.back();
        }
      }
      region.patches.push_back(r);
    }
  }
  GearBodyMesh out;
  try {
    out.mesh = options.mesher == "gmsh" ? GmshMesher().BuildMesh(region)
                                        : MappedMesher().BuildMesh(region);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(who + "the " + options.mesher + " mesher failed: " + e.what());
  }
  out.teeth = z;
  out.grid = MakeFlankGrid(gear, options);

  // Grid nodes: the node of each flank set at the grid point's position.
  const double tol = 1e-9 * gear.tip_radius();
  out.grid_nodes.resize(z);
  for (int k = 0; k < z; ++k) {
    const double a = k * gear.pitch_angle();
    const Eigen::Matrix2d rot = Eigen::Rotation2Dd(a).toRotationMatrix();
    for (int f = 0; f < 2; ++f) {
      const std::string set = "flank" + std::to_string(k) + (f == 0 ? "+" : "-");
      const std::vector<int>& nodes = out.mesh.NodeSet(set);
      for (const Eigen::Vector2d& x0 : out.grid.position) {
        const Eigen::Vector2d x = rot * (f == 0 ? x0 : Mirror(x0));
        int found = -1;
        double best = std::numeric_limits<double>::infinity();
        for (int v : nodes) {
          const double d = (out.mesh.nodes[v] - x).norm();
          if (d < best) {
            best = d;
            found = v;
          }
        }
        if (!(best <= tol)) {
          throw std::invalid_argument(who + "flank grid point " + Pt(x) + " of set '" + set +
                                      "' is not a mesh node (nearest at " + Str(best) + " m)");
        }
        out.grid_nodes[k][f].push_back(found);
      }
    }
  }

  out.min_jacobian_ratio = MinJacobianRatio(out.mesh);
  return out;
}

double MinJacobianRatio(const Mesh& mesh) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  const GaussRule g = GaussLegendre(3);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const Q8Coordinates x = mesh.ElementCoordinates(e);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        double det = 0.0;
        Q8StrainDisplacement(x, g.points[i], g.points[j], &det);
        lo = std::min(lo, det);
        hi = std::max(hi, det);
      }
    }
  }
  return lo / hi;
}

double OutlineArea(const geometry::Gear& gear, int per_segment) {
  const std::vector<geometry::Vec2> pts = gear.Outline(per_segment);
  double a2 = 0.0;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const auto& a = pts[k];
    const auto& b = pts[(k + 1) % pts.size()];
    a2 += a.x() * b.y() - a.y() * b.x();
  }
  const double enclosed = std::abs(0.5 * a2);
  const double r = gear.spec().hub_radius;
  const double disc = geometry::kPi * r * r;
  return gear.internal() ? disc - enclosed : enclosed - disc;
}

double MeshArea(const Mesh& mesh) {
  const GaussRule g = GaussLegendre(3);
  double area = 0.0;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const Q8Coordinates x = mesh.ElementCoordinates(e);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        double det = 0.0;
        Q8StrainDisplacement(x, g.points[i], g.points[j], &det);
        area += g.weights[i] * g.weights[j] * det;
      }
    }
  }
  return area;
}

}  // namespace epicycle::compliance
