#include "epicycle/geometry/contact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "messages.hpp"

namespace epicycle::geometry {

namespace {

int Mod(long a, int z) {
  const long r = a % z;
  return static_cast<int>(r < 0 ? r + z : r);
}

// Tooth k's involute as if the gear had no pitch deviations.
WorldInvolute NominalFlank(const PosedGear& g, int tooth, int side) {
  const InvoluteFlank& f = g.gear->involute();
  WorldInvolute w;
  w.centre = g.pose.geometric_centre;
  w.base_radius = f.base_radius;
  w.start = g.pose.rotation + tooth * g.gear->pitch_angle() + side * f.start;
  w.hand = side * f.hand;
  w.side = side;
  w.u_min = f.u_min;
  w.u_max = f.u_max;
  return w;
}

// A point of tooth k (turned by its pitch deviation) carried back onto the nominal tooth.
Vec2 NominalTooth(const PosedGear& g, int tooth, const Vec2& p) {
  const double off = g.gear->tooth_offset(tooth);
  if (off == 0.0) return p;
  return g.pose.geometric_centre + Rotate(p - g.pose.geometric_centre, -off);
}

// ⌊x⌋ and ⌈x⌉ as integers without a library call: the conversion truncates exactly (|x| < 2⁶³;
// here a few hundred at most), and one comparison moves it to the floor or the ceiling.
long Floor(double x) {
  const long j = static_cast<long>(x);
  return static_cast<double>(j) > x ? j - 1 : j;
}
long Ceil(double x) {
  const long j = static_cast<long>(x);
  return static_cast<double>(j) < x ? j + 1 : j;
}

// All roll angles u = u0 + j·p inside [lo, hi) (a flank's roll repeats every tooth pitch p).
template <typename F>
void ForEachRoll(double u0, double p, double lo, double hi, F&& f) {
  const long j0 = Ceil((lo - u0) / p);
  const long j1 = Floor((hi - u0) / p);
  for (long j = j0; j <= j1; ++j) {
    const double u = u0 + static_cast<double>(j) * p;
    if (u >= lo && u < hi) f(u, j);
  }
}

// Is direction φ inside the arc of normals from `from` sweeping to `to` (exclusive at `from`,
// where the round joins the flank and the involute contact takes over)?
bool InSpan(double phi, double from, double to) {
  const double sweep = to - from;
  const double rel = WrapAngle(phi - from);
  return sweep >= 0 ? (rel > 0 && rel <= sweep) : (rel < 0 && rel >= sweep);
}

struct ArcHit {
  Vec2 flank_point;
  Vec2 flank_surface;  // the same roll on the nominal tooth's involute (FE table lookup)
  Vec2 flank_normal;   // the flank's outward normal
  double distance;     // from the arc centre to the flank, along its normal
  double roll;
  int tooth;
};

// The foot of the normal from c on a relieved flank x(u) − C(u) n(u) (docs/model.md §3; the relief
// is a few µm, so Newton from the involute's foot u converges in a few steps). With e = e(S + H u),
// e⊥ its left normal and n = σ e⊥:
//   x′ = (r_b u + σH C) e − σ C′ e⊥,
//   x″ = (r_b + 2σH C′) e + (H r_b u + σ C − σ C″) e⊥,
// and f(u) = (x − c)·x′ = 0, f′ = |x′|² + (x − c)·x″.
struct FlankFoot {
  Vec2 point, normal;
  double u;
};
FlankFoot RelievedFoot(const WorldInvolute& w, const Gear& gear, const Vec2& c, double u) {
  const double sh = w.side * w.hand, rb = w.base_radius;
  FlankFoot out{};
  for (int it = 0; it < 30; ++it) {
    const ReliefValue r = gear.ReliefAt(u);
    const double b = w.start + w.hand * u;
    const Vec2 e = Dir(b), ep = DirPerp(b);
    const Vec2 x = w.Point(u) - r.c * w.side * ep;
    const Vec2 d1 = (rb * u + sh * r.c) * e - w.side * r.d1 * ep;
    const Vec2 d2 = (rb + 2.0 * sh * r.d1) * e + (w.hand * rb * u + w.side * (r.c - r.d2)) * ep;
    const Vec2 t = d1.normalized();
    out = {x, w.side * Vec2(-t.y(), t.x()), u};
    const double f = (x - c).dot(d1), df = d1.squaredNorm() + (x - c).dot(d2);
    const double step = f / df;
    u -= step;
    if (std::abs(step) < 1e-14 * std::max(1.0, std::abs(u))) break;
  }
  return out;
}

// Closest points between a circular arc (centre c, radius ρ, outward normals spanning
// [from, to]) and the flanks of side σ of a posed gear: the involute's point whose normal passes
// through c lies on a tangent from c to the base circle; a relieved flank's is refined from it.
// Tooth k's flank is turned by its pitch-deviation offset, which moves its roll by −H·offset.
template <typename F>
void ArcAgainstFlanks(const Vec2& c, double rho, double from, double to, const PosedGear& g,
                      int side, double window, F&& hit) {
  const WorldInvolute f0 = NominalFlank(g, 0, side);
  const Vec2 rel = c - f0.centre;
  const double dist_c = rel.norm();
  if (dist_c <= f0.base_radius) return;
  const double phi = Angle(rel);
  const double cos_open = f0.base_radius / dist_c;
  const double open = std::acos(cos_open), sin_open = std::sqrt(1.0 - cos_open * cos_open);
  const Vec2 unit = rel / dist_c;
  const double p = g.gear->pitch_angle();
  const double margin = g.gear->max_tooth_offset();
  for (int s : {-1, 1}) {
    // Only the tangent with s = H meets flanks of this hand on c's side of its tangent point. On
    // the other, c − x lies along the tangent line with length L + r_b u ≥ L (L = √(|c|² − r_b²),
    // u ≥ 0 on the active flank), so every flank point found there is at least L from c (a relief
    // moves it by micrometres): that tangent is skipped when L is well beyond ρ + window.
    if (s != f0.hand && dist_c * sin_open > 2.0 * (rho + window)) continue;
    const double beta = phi + s * open;
    const double u0 = f0.hand * WrapAngle(beta - f0.start);
    // Dir(β), the unit vector turned by ±open, without a sine and cosine.
    const Vec2 radial(cos_open * unit.x() - s * sin_open * unit.y(),
                      s * sin_open * unit.x() + cos_open * unit.y());
    const Vec2 perp(-radial.y(), radial.x());
    ForEachRoll(u0, p, f0.u_min - margin, f0.u_max + margin, [&](double un, long j) {
      const int tooth = Mod(-f0.hand * j, g.gear->teeth());
      double u = un - f0.hand * g.gear->tooth_offset(tooth);
      if (u < f0.u_min || u >= f0.u_max) return;
      Vec2 point = f0.centre + f0.base_radius * (radial - f0.hand * u * perp);
      Vec2 normal = side * perp;
      Vec2 involute = point;  // the unrelieved flank's point at the contact's roll
      if (g.gear->has_relief()) {
        const WorldInvolute w = FlankInWorld(g, tooth, side);
        const FlankFoot foot = RelievedFoot(w, *g.gear, c, u);
        if (foot.u < f0.u_min || foot.u >= f0.u_max) return;
        point = foot.point;
        normal = foot.normal;
        u = foot.u;
        involute = w.Point(u);
      }
      const double d = (c - point).dot(normal);
      if (d <= 0 || d > rho + window) return;
      if (!InSpan(Angle(-normal), from, to)) return;
      hit(ArcHit{point, NominalTooth(g, tooth, involute), normal, d, u, tooth});
    });
  }
}

// What the search knows of the mate's flanks of one side before it tries tip rounds against them,
// so that a round that cannot touch any of them is dropped without an arccosine or arctangent.
//
// ArcAgainstFlanks looks for flank points on the tangent from the round's centre c to the mate's
// base circle with tangent point T = O + r_b Dir(β) (the one with s = H): c − T = −H L e⊥(β),
// L = √(|c − O|² − r_b²), and tooth k's involute crosses that tangent at roll u with
//   u ≡ H (β − S_0) (mod the pitch p, up to the tooth's offset),  d = h (r_b u − L),
// d the distance from c to that flank point along its normal and h = σH the involute's hand
// (−1 external, +1 internal). A hit needs u in [u_min, u_max) and 0 < d ≤ ρ + window. The
// angle β − S_0 is known at one tangent point, the line of action's (its roll, already found
// there); for another tangent, β differs by the angle Δ between the two tangent points' unit
// vectors, Δ = atan(t) with t = (e_ref × e)/(e_ref · e). For |t| ≤ 1 the alternating series
// brackets it, t − t³/3 + t⁵/5 − t⁷/7 ≤ atan t ≤ t − t³/3 + t⁵/5 (t ≥ 0, odd in t): the rolls
// u ≡ u_ref + HΔ then lie in an interval at most |t|⁷/7 wide, and the round is dropped when no
// roll of the lattice u + j p falls in the window of rolls a hit needs. That window is widened by
// the largest tooth offset, by 1e-9 rad (the two ways of computing u agree to round-off, ~1e-15
// rad), and for a relieved mate by its relief (below). Anything outside the test's reach (c within
// 2(ρ + window) of the base circle along the tangent, where the second tangent is tried too, or Δ
// beyond 45°) goes to the full search: the filter drops only rounds that the full search would
// have dropped, so the contacts found are the same.
struct FlankReach {
  Vec2 centre = Vec2::Zero();     // O, the mate's geometric centre
  Vec2 reference = Vec2::Zero();  // Dir(β_ref), the line of action's tangent point on the mate
  double roll = 0;                // H (β_ref − S_0) [rad]
  double base_radius = 0, pitch = 0;
  double u_min = 0, u_max = 0;
  double widen = 0;           // the largest tooth offset and 1e-9 rad
  double near_base = 0;       // (2(ρ + window))²: L² below it goes to the full search
  double d_lo = 0, d_hi = 0;  // the distances d that can still give a hit
  int hand = 1;               // H
  int flank_hand = -1;        // h
};

FlankReach ReachOf(const PosedGear& g, int side, const Vec2& reference, double reference_angle,
                   double rho, double window) {
  const WorldInvolute f0 = NominalFlank(g, 0, side);
  constexpr double kRollSlack = 1e-9;  // [rad]
  FlankReach r;
  r.centre = f0.centre;
  r.reference = reference;
  r.roll = f0.hand * WrapAngle(reference_angle - f0.start);
  r.base_radius = f0.base_radius;
  r.pitch = g.gear->pitch_angle();
  r.u_min = f0.u_min;
  r.u_max = f0.u_max;
  r.widen = g.gear->max_tooth_offset() + kRollSlack;
  r.near_base = 4.0 * (rho + window) * (rho + window);
  r.hand = f0.hand;
  r.flank_hand = side * f0.hand;
  r.d_lo = 0;
  r.d_hi = rho + window;
  if (g.gear->has_relief()) {
    // The full search takes the foot y(u*) of the normal from c on the relieved flank
    // y = x − C n and keeps it for 0 < d ≤ ρ + window, d = |c − y(u*)|. In the involute's frame at
    // u*, c − x(u*) = (d cos γ − C) n + d sin γ t (γ the relieved normal's tilt), and the involute
    // distance above is 1-Lipschitz in c (the involutes of one base circle are parallel curves), so
    // it lies within d of d cos γ − C: in [−C_max − (ρ + window), 2(ρ + window)], whatever γ.
    const ProfileModification& m = g.gear->spec().modification;
    r.d_lo -= m.tip.amount + m.root.amount + rho + window;
    r.d_hi += rho + window;
  }
  return r;
}

// The interval [u0_lo, u0_hi] that holds the roll lattice's u0 = roll + HΔ, Δ = atan t (the
// alternating series' bracket above, |t| ≤ 1).
void LatticeRolls(const FlankReach& f, double t, double* u0_lo, double* u0_hi) {
  const double a = std::abs(t), a2 = a * a;
  const double atan_hi = a * (1.0 - a2 * (1.0 / 3.0 - a2 / 5.0)),
               atan_lo = atan_hi - a * a2 * a2 * a2 / 7.0;
  const double turn_lo = t < 0 ? -atan_hi : atan_lo, turn_hi = t < 0 ? -atan_lo : atan_hi;
  *u0_lo = f.roll + (f.hand > 0 ? turn_lo : -turn_hi);
  *u0_hi = f.roll + (f.hand > 0 ? turn_hi : -turn_lo);
}

// Whether a roll of the lattice u0 + j p, u0 in [u0_lo, u0_hi], falls where a hit needs it for a
// tangent length L in [l_lo, l_hi]: r_b u = L + h d with d in [d_lo, d_hi] and u in [u_min, u_max],
// widened to where the lattice point u + H·offset of a tooth turned by its offset sits.
bool LatticeMeetsWindow(const FlankReach& f, double u0_lo, double u0_hi, double l_lo, double l_hi) {
  const double rb = f.base_radius;
  const double w_lo =
      std::max((l_lo + (f.flank_hand > 0 ? f.d_lo : -f.d_hi)) / rb, f.u_min) - f.widen;
  const double w_hi =
      std::min((l_hi + (f.flank_hand > 0 ? f.d_hi : -f.d_lo)) / rb, f.u_max) + f.widen;
  // Some j with u0 + j p in [w_lo, w_hi] for some u0 in [u0_lo, u0_hi]: an integer j in
  // [(w_lo − u0_hi)/p, (w_hi − u0_lo)/p], i.e. the upper end's floor at or above the lower end.
  return static_cast<double>(Floor((w_hi - u0_lo) / f.pitch)) >= (w_lo - u0_hi) / f.pitch;
}

// False only if no flank of the mate can come within ρ + window of a round centred at c (above).
bool MayReach(const FlankReach& f, const Vec2& c) {
  const Vec2 rel = c - f.centre;
  const double rb = f.base_radius, l2 = rel.squaredNorm() - rb * rb;
  if (!(l2 > f.near_base)) return true;
  const double l = std::sqrt(l2);
  // Dir(β) ∝ r_b (c − O) + H L (c − O)⊥: c − O turned by ±acos(r_b/|c − O|).
  const Vec2 e = rb * rel + (f.hand * l) * Vec2(-rel.y(), rel.x());
  const double sn = Cross(f.reference, e), cs = f.reference.dot(e);
  if (!(cs > 0) || std::abs(sn) > cs) return true;
  double u0_lo = 0, u0_hi = 0;
  LatticeRolls(f, sn / cs, &u0_lo, &u0_hi);
  return LatticeMeetsWindow(f, u0_lo, u0_hi, l, l);
}

// MayReach for every centre within `eps` of c [m] with the mate turned by at most `turn` [rad]
// (TipRoundReuse): false only if no such centre's round can reach the mate. A hit of lattice
// roll u = u0 + j p needs r_b u = L + h d, d in [d_lo, d_hi], and u in [u_min, u_max] (each
// widened as in MayReach). Written with g = u0 − L/r_b, the first is g + j p in [h d/r_b] and
// the second g + j p + L/r_b in [u_min, u_max]. g = H(ψ − S_0), ψ = β − H L/r_b the start angle of
// the involute of the mate's base circle through c, and |∇ψ| = 1/r_b exactly (radially
// ∂ψ/∂r = −H L/(r r_b), across 1/r, and L² + r_b² = r²): the involutes are parallel curves. So
// over |Δc| ≤ ε (the ball outside the base circle, r − ε > r_b), with the mate turned by Δθ
// (S_0 turns with it), |Δg| ≤ ε/r_b + |Δθ|. For the flank range only, L moves by at most
//   |ΔL| ≤ ε max r/L ≤ ε (r + ε)/L_min,  L_min = √((r − ε)² − r_b²),
// and a centre that could come within 2(ρ + window) of the base circle along the tangent (where
// the full search tries the second tangent) counts as reaching.
bool MayReachWithin(const FlankReach& f, const Vec2& c, double eps, double turn) {
  const Vec2 rel = c - f.centre;
  const double rb = f.base_radius, r = rel.norm();
  if (!(r - eps > rb)) return true;
  const double l = std::sqrt(r * r - rb * rb);
  const double l_min = std::sqrt((r - eps) * (r - eps) - rb * rb);
  const double dl = eps * (r + eps) / l_min;
  if (!(l - dl > 0) || !((l - dl) * (l - dl) > f.near_base)) return true;
  const Vec2 e = rb * rel + (f.hand * l) * Vec2(-rel.y(), rel.x());
  const double sn = Cross(f.reference, e), cs = f.reference.dot(e);
  if (!(cs > 0) || std::abs(sn) > cs) return true;
  double u0_lo = 0, u0_hi = 0;
  LatticeRolls(f, sn / cs, &u0_lo, &u0_hi);
  const double dg = eps / rb + turn;
  const double g_lo = u0_lo - l / rb - dg, g_hi = u0_hi - l / rb + dg;
  // g + j p within the distances a hit needs (h d/r_b, widened), and g + j p + L/r_b within the
  // flank's rolls (widened by |ΔL|/r_b too).
  const double a_lo = (f.flank_hand > 0 ? f.d_lo : -f.d_hi) / rb - f.widen;
  const double a_hi = (f.flank_hand > 0 ? f.d_hi : -f.d_lo) / rb + f.widen;
  const double range_lo = f.u_min - f.widen - dl / rb, range_hi = f.u_max + f.widen + dl / rb;
  const long j_lo = Ceil((a_lo - g_hi) / f.pitch), j_hi = Floor((a_hi - g_lo) / f.pitch);
  for (long j = j_lo; j <= j_hi; ++j) {
    const double shift = static_cast<double>(j) * f.pitch + l / rb;
    if (g_hi + shift >= range_lo && g_lo + shift <= range_hi) return true;
  }
  return false;
}

// The tip round of tooth k, side σ, in the inertial frame: its centre (`rotation` is
// Dir(g.pose.rotation), computed once per search of a mesh) and, for a round that may reach the
// mate, the span of its normals.
Vec2 TipRoundCentre(const PosedGear& g, const Vec2& rotation, int tooth, int side) {
  const TipRound& t = g.gear->tip_round();
  const Vec2 body(t.centre.x(), side * t.centre.y());
  return g.pose.geometric_centre +
         RotateBy(RotateBy(body, g.gear->tooth_direction(tooth)), rotation);
}
struct NormalSpan {
  double from, to;
};
NormalSpan TipRoundNormals(const PosedGear& g, int tooth, int side) {
  const TipRound& t = g.gear->tip_round();
  const double turn = g.pose.rotation + tooth * g.gear->pitch_angle() + g.gear->tooth_offset(tooth);
  return {side * t.normal_from + turn, side * t.normal_to + turn};
}
// The unrelieved round of the nominal tooth (where the FE table reads the contact), only for hits.
Vec2 NominalTipRoundCentre(const PosedGear& g, int tooth, int side) {
  const TipRound& n = g.gear->nominal_tip_round();
  const double nominal_turn = g.pose.rotation + tooth * g.gear->pitch_angle();
  return g.pose.geometric_centre + Rotate(Vec2(n.centre.x(), side * n.centre.y()), nominal_turn);
}

double Lever(const Vec2& point, const Vec2& centre, const Vec2& force_direction) {
  return Cross(point - centre, force_direction);
}

}  // namespace

Vec2 WorldInvolute::Point(double u) const {
  const Vec2 radial = Dir(start + hand * u), perp(-radial.y(), radial.x());
  return centre + base_radius * (radial - static_cast<double>(hand) * u * perp);
}

Vec2 WorldInvolute::Normal(double u) const { return side * DirPerp(start + hand * u); }

WorldInvolute FlankInWorld(const PosedGear& g, int tooth, int side) {
  WorldInvolute w = NominalFlank(g, tooth, side);
  w.start += g.gear->tooth_offset(tooth);
  return w;
}

namespace {

// The base circles' common tangents exist for centres `dist` apart whose base radii sum (external)
// or differ (internal) by k: k/dist < 1.
bool LineOfActionExists(double dist, double k) { return dist > 0 && k / dist < 1.0; }

// What the lines of action on the two flank sides share: the centre line and the pressure angle,
// with its arccosine and the centre line's arctangent (a search makes both lines from one).
struct CentreLine {
  Vec2 dv = Vec2::Zero();  // from A's geometric centre to B's
  double dist = 0, cos_alpha = 0, sin_alpha = 0, alpha = 0, pitch_dir = 0;
};

CentreLine MakeCentreLine(const PosedGear& a, const PosedGear& b, bool internal) {
  CentreLine c;
  c.dv = b.pose.geometric_centre - a.pose.geometric_centre;
  c.dist = c.dv.norm();
  const double rba = a.gear->base_radius(), rbb = b.gear->base_radius();
  const double k = internal ? rbb - rba : rba + rbb;
  if (!LineOfActionExists(c.dist, k)) {
    throw std::invalid_argument("mesh " + a.gear->name() + "-" + b.gear->name() +
                                ": centre distance " + Mm(c.dist) +
                                " mm admits no line of action (base circles " +
                                (internal ? "too far apart" : "overlap") + ")");
  }
  c.cos_alpha = k / c.dist;
  c.alpha = std::acos(c.cos_alpha);
  c.sin_alpha = std::sqrt(1.0 - c.cos_alpha * c.cos_alpha);
  c.pitch_dir = Angle(c.dv) + (internal ? kPi : 0.0);
  return c;
}

LineOfAction LineOnSide(const PosedGear& a, const PosedGear& b, bool internal, const CentreLine& c,
                        int side_a) {
  const double rba = a.gear->base_radius(), rbb = b.gear->base_radius();
  LineOfAction l;
  l.side_a = side_a;
  l.side_b = internal ? -side_a : side_a;
  l.centre_distance = c.dist;
  l.pressure_angle = c.alpha;
  l.base_angle_a = c.pitch_dir - side_a * c.alpha;
  l.base_angle_b = l.base_angle_a + (internal ? 0.0 : kPi);
  // Dir(base_a) = Dir(pitch_dir) turned by −σα, from the unit vectors themselves.
  const Vec2 pitch_unit = (internal ? -1.0 : 1.0) * c.dv / c.dist;
  const Vec2 e = RotateBy(pitch_unit, Vec2(c.cos_alpha, -side_a * c.sin_alpha));
  l.direction = side_a * Vec2(-e.y(), e.x());
  l.tangent_a = a.pose.geometric_centre + rba * e;
  l.tangent_b = b.pose.geometric_centre + (internal ? rbb : -rbb) * e;
  l.length = (l.tangent_b - l.tangent_a).dot(l.direction);
  return l;
}

}  // namespace

LineOfAction MakeLineOfAction(const PosedGear& a, const PosedGear& b, bool internal, int side_a) {
  return LineOnSide(a, b, internal, MakeCentreLine(a, b, internal), side_a);
}

namespace {

// A's flank at roll u_a on the line of action, and B's flank nearest to it there.
struct LoaPair {
  Vec2 xa, xb;
  Vec2 sa, sb;  // on the nominal teeth's involutes
  double ua, ub;
  int ka, kb;
  double overlap;
};

// With `modified`, tooth k of either gear is turned by its pitch-deviation offset (its roll on
// the line of action moves by −H·offset) and each flank's relief is taken off along the line of
// action. An involute's normal where it crosses the line of action is the line's direction, so
// the relieved flank x − C n crosses the line at x − C d: along the line the gap of two relieved
// flanks is exactly the involutes' gap plus C_A(u_A) + C_B(u_B).
// Every flank point this finds lies where its involute crosses the line of action, whose
// generating angle is the line's base angle (mod 2π) for every tooth, offset or not: the point is
// x = O + r_b (e − H u e⊥) with e the unit vector from the centre to the line's tangent point, so
// no sine or cosine is needed per tooth.
Vec2 OnLineOfAction(const PosedGear& g, const Vec2& e, int hand, double u) {
  const double rb = g.gear->base_radius();
  return g.pose.geometric_centre + rb * (e - static_cast<double>(hand) * u * Vec2(-e.y(), e.x()));
}

// What PairOnLoa needs of a line of action for every tooth pair on it, worked out once per line:
// the unit vectors e from the centres to the tangent points, the flank hands, B's tooth-0 roll.
struct LoaFrame {
  Vec2 e_a = Vec2::Zero(), e_b = Vec2::Zero();
  int hand_a = 1, hand_b = 1;
  double base_radius_b = 0;
  double roll_b = 0;  // u of B's nominal tooth-0 flank where it crosses the line (mod 2π)
};

LoaFrame MakeLoaFrame(const PosedGear& a, const PosedGear& b, const LineOfAction& l) {
  const WorldInvolute a0 = NominalFlank(a, 0, l.side_a), b0 = NominalFlank(b, 0, l.side_b);
  LoaFrame f;
  f.e_a = (l.tangent_a - a.pose.geometric_centre) / a.gear->base_radius();
  f.e_b = (l.tangent_b - b.pose.geometric_centre) / b.gear->base_radius();
  f.hand_a = a0.hand;
  f.hand_b = b0.hand;
  f.base_radius_b = b0.base_radius;
  f.roll_b = b0.hand * WrapAngle(l.base_angle_b - b0.start);
  return f;
}

// std::lround without the library call: x − trunc(x) is exact (|x| < 2⁵²), so the comparison
// with ½ is too, and halves go away from zero as there.
long NearestInteger(double x) {
  long j = static_cast<long>(x);
  const double frac = x - static_cast<double>(j);
  if (frac >= 0.5) ++j;
  if (frac <= -0.5) --j;
  return j;
}

LoaPair PairOnLoa(const PosedGear& a, const PosedGear& b, const LineOfAction& l, const LoaFrame& f,
                  double ua, int ka, bool modified) {
  LoaPair r;
  r.ua = ua;
  r.ka = ka;
  r.xa = OnLineOfAction(a, f.e_a, f.hand_a, ua);
  const double sa = (r.xa - l.tangent_a).dot(l.direction);
  // Along d, B's flank point sits at s_B = L + H_B σ_B r_bB u_B from N_A.
  const double target = (sa - l.length) / (f.hand_b * l.side_b * f.base_radius_b);
  const double p = b.gear->pitch_angle();
  const long j = NearestInteger((target - f.roll_b) / p);
  r.kb = Mod(-f.hand_b * j, b.gear->teeth());
  r.ub = f.roll_b + static_cast<double>(j) * p;
  if (modified) r.ub -= f.hand_b * b.gear->tooth_offset(r.kb);
  r.xb = OnLineOfAction(b, f.e_b, f.hand_b, r.ub);
  r.overlap = (r.xa - r.xb).dot(l.direction);
  r.sa = NominalTooth(a, ka, r.xa);
  r.sb = NominalTooth(b, r.kb, r.xb);
  if (modified && (a.gear->has_relief() || b.gear->has_relief())) {
    const double ca = a.gear->ReliefAt(r.ua).c, cb = b.gear->ReliefAt(r.ub).c;
    r.xa -= ca * l.direction;
    r.xb += cb * l.direction;
    r.overlap -= ca + cb;
  }
  return r;
}

}  // namespace

double NearestLoaOverlap(const PosedGear& a, const PosedGear& b, bool internal, int side_a) {
  const LineOfAction l = MakeLineOfAction(a, b, internal, side_a);
  const WorldInvolute a0 = NominalFlank(a, 0, side_a);
  const double ua = a0.hand * WrapAngle(l.base_angle_a - a0.start);
  // Nominal teeth (no relief, no pitch deviations): the reference of the layout (alignment,
  // error projections).
  return PairOnLoa(a, b, l, MakeLoaFrame(a, b, l), ua, 0, false).overlap;
}

std::string KindName(ContactKind kind) {
  switch (kind) {
    case ContactKind::kInvolute:
      return "involute";
    case ContactKind::kTipRoundA:
      return "tip-round-a";
    case ContactKind::kTipRoundB:
      return "tip-round-b";
  }
  return "?";
}

bool HasLineOfAction(const PosedGear& a, const PosedGear& b, bool internal) {
  const double rba = a.gear->base_radius(), rbb = b.gear->base_radius();
  return LineOfActionExists((b.pose.geometric_centre - a.pose.geometric_centre).norm(),
                            internal ? rbb - rba : rba + rbb);
}

std::vector<PotentialContact> FindContacts(const PosedGear& a, const PosedGear& b, bool internal,
                                           const ContactSearchOptions& options) {
  std::vector<PotentialContact> out;
  out.reserve(16);
  AppendContacts(a, b, internal, options, &out);
  return out;
}

namespace {

// Whether the poses lie within the budget of the last refresh, for the same gears and options.
bool WithinBudget(const TipRoundReuse& r, const PosedGear& a, const PosedGear& b, bool internal,
                  const ContactSearchOptions& options) {
  return r.valid && r.gear_a == a.gear && r.gear_b == b.gear && r.internal == internal &&
         r.gap_window == options.gap_window && r.both_sides == options.both_sides &&
         r.side_a == options.side_a &&
         (a.pose.geometric_centre - r.pose_a.geometric_centre).norm() <= r.centre_budget &&
         (b.pose.geometric_centre - r.pose_b.geometric_centre).norm() <= r.centre_budget &&
         std::abs(a.pose.rotation - r.pose_a.rotation) <= r.turn_budget_a &&
         std::abs(b.pose.rotation - r.pose_b.rotation) <= r.turn_budget_b;
}

// The largest distance of a gear's material points from its geometric centre [m].
double OuterRadius(const Gear& g) { return std::max(g.tip_radius(), g.root_radius()); }

// A refresh: notes P0, the options and the budgets in `r`, and sets owner_roll[0], [1] to how far
// a tooth of A, of B may move in roll on the line of action within the budget: the line's base
// angle pitch_dir ∓ α moves with the centre line dv (|Δdv| ≤ 2D): |Δ pitch_dir| ≤ 2D/(a − 2D),
// |Δα| ≤ 2D k/(a_min √(a_min² − k²)) (α = acos(k/a), a_min = a − 2D), and the tooth turns with
// its gear.
void BeginRefresh(TipRoundReuse* keep, const PosedGear& a, const PosedGear& b, bool internal,
                  const ContactSearchOptions& options, const CentreLine& centre_line,
                  double owner_roll[2]) {
  TipRoundReuse& r = *keep;
  ++r.refreshes;
  r.valid = false;
  r.gear_a = a.gear;
  r.gear_b = b.gear;
  r.internal = internal;
  r.gap_window = options.gap_window;
  r.both_sides = options.both_sides;
  r.side_a = options.side_a;
  r.pose_a = a.pose;
  r.pose_b = b.pose;
  const double d = r.budget;
  r.centre_budget = d;
  r.turn_budget_a = d / OuterRadius(*a.gear);
  r.turn_budget_b = d / OuterRadius(*b.gear);
  const double k = centre_line.dist * centre_line.cos_alpha, a_min = centre_line.dist - 2.0 * d;
  const bool bounded = a_min > k && d >= 0;
  const double line_turn =
      bounded ? 2.0 * d / a_min + 2.0 * d * k / (a_min * std::sqrt(a_min * a_min - k * k))
              : INFINITY;
  owner_roll[0] = line_turn + r.turn_budget_a;
  owner_roll[1] = line_turn + r.turn_budget_b;
}

}  // namespace

void AppendContacts(const PosedGear& a, const PosedGear& b, bool internal,
                    const ContactSearchOptions& options, std::vector<PotentialContact>* out,
                    TipRoundReuse* reuse) {
  const double window = options.gap_window;
  const Vec2 oa = a.pose.rotation_centre, ob = b.pose.rotation_centre;
  const double ring_sign = internal ? -1.0 : 1.0;  // B's curvature: a ring's flank is concave
  const int sides[2] = {options.both_sides ? 1 : options.side_a, -1};
  const CentreLine centre_line = MakeCentreLine(a, b, internal);
  const Vec2 rotation_a = Dir(a.pose.rotation), rotation_b = Dir(b.pose.rotation);
  // Tip rounds reused under a pose bound (TipRoundReuse; docs/dynamic_cost.md).
  TipRoundReuse* keep = options.exhaustive_tips ? nullptr : reuse;
  const bool refresh = keep != nullptr && !WithinBudget(*keep, a, b, internal, options);
  double owner_roll[2] = {0, 0};
  if (refresh) {
    BeginRefresh(keep, a, b, internal, options, centre_line, owner_roll);
  } else if (keep != nullptr) {
    ++keep->reuses;
  }
  for (int si = 0; si < (options.both_sides ? 2 : 1); ++si) {
    const int side_a = sides[si];
    const LineOfAction l = LineOnSide(a, b, internal, centre_line, side_a);
    // Involute against involute, on the line of action.
    const WorldInvolute a0 = NominalFlank(a, 0, side_a);
    const double ua0 = a0.hand * WrapAngle(l.base_angle_a - a0.start);
    const double margin = a.gear->max_tooth_offset();
    const LoaFrame frame = MakeLoaFrame(a, b, l);
    ForEachRoll(ua0, a.gear->pitch_angle(), a0.u_min - margin, a0.u_max + margin,
                [&](double un, long j) {
                  const int ka = Mod(-a0.hand * j, a.gear->teeth());
                  const double ua = un - a0.hand * a.gear->tooth_offset(ka);
                  if (ua < a0.u_min || ua >= a0.u_max) return;
                  const LoaPair pr = PairOnLoa(a, b, l, frame, ua, ka, true);
                  const InvoluteFlank& fb = b.gear->involute();
                  if (pr.ub < fb.u_min || pr.ub >= fb.u_max || pr.overlap < -window) return;
                  PotentialContact c;
                  c.kind = ContactKind::kInvolute;
                  c.side_a = l.side_a;
                  c.side_b = l.side_b;
                  c.tooth_a = pr.ka;
                  c.tooth_b = pr.kb;
                  c.point_a = pr.xa;
                  c.point_b = pr.xb;
                  c.surface_a = pr.sa;
                  c.surface_b = pr.sb;
                  c.point = 0.5 * (pr.xa + pr.xb);
                  c.normal = l.direction;
                  c.overlap = pr.overlap;
                  c.lever_a = Lever(c.point, oa, -c.normal);
                  c.lever_b = Lever(c.point, ob, c.normal);
                  c.curvature_radius_a = a.gear->base_radius() * pr.ua;
                  c.curvature_radius_b = ring_sign * b.gear->base_radius() * pr.ub;
                  c.roll_a = pr.ua;
                  c.roll_b = pr.ub;
                  out->push_back(c);
                });
    // Tip rounds against flanks, off the line of action. A tip round reaches the mate only around
    // the ends of the path of contact, where the owner's flank crosses the line of action near its
    // tip-end roll: the teeth whose roll there is within one pitch of it (all teeth with
    // options.exhaustive_tips). One pitch, not less: internal meshes are nearly conformal, and a
    // ring's round stays within a 150 µm window more than half a base pitch past the path's end.
    // The mates' reference tangent points (FlankReach): the line of action's, N_A and N_B.
    const Vec2& ref_a = frame.e_a;
    const Vec2 ref_b = internal ? ref_a : Vec2(-ref_a);
    auto tips = [&](const PosedGear& owner, const Vec2& rotation, const PosedGear& other,
                    int owner_side, int other_side, double base_angle, double other_base_angle,
                    const Vec2& other_reference, bool owner_is_a) {
      if (!owner.gear->has_tip_round()) return;
      TipRoundReuse::Rounds* known =
          keep != nullptr ? &keep->rounds[si][owner_is_a ? 0 : 1] : nullptr;
      if (known != nullptr && !refresh && known->usable &&
          std::all_of(known->dead, known->dead + known->count, [](bool d) { return d; })) {
        ++keep->skipped;
        return;
      }
      const double p = owner.gear->pitch_angle();
      const double rho = owner.gear->tip_round().radius;
      const WorldInvolute f0 = NominalFlank(owner, 0, owner_side);
      const double u0 = f0.hand * WrapAngle(base_angle - f0.start);
      const double u_tip = owner.gear->internal() ? f0.u_min : f0.u_max;
      if (refresh) {
        // The rounds that can be candidates anywhere within the budget (the window of rolls
        // widened by the owner's roll bound), and which of them cannot reach the mate there: a
        // round centre moves by at most 2D + D (both centres, the owner's turn at its outer
        // radius) relative to the mate's centre, and the mate turns by at most its budget.
        TipRoundReuse::Rounds& k = *known;
        k = {};
        const double widen = owner_roll[owner_is_a ? 0 : 1];
        k.usable = widen < 0.5 * p;
        if (k.usable) {
          ForEachRoll(u0, p, u_tip - p - widen, u_tip + p + widen, [&](double, long j) {
            if (k.count < 3)
              k.teeth[k.count++] = Mod(-f0.hand * j, owner.gear->teeth());
            else
              k.usable = false;
          });
        }
        if (k.usable) {
          const FlankReach reach =
              ReachOf(other, other_side, other_reference, other_base_angle, rho, window);
          const double eps = 3.0 * keep->centre_budget;
          const double turn = owner_is_a ? keep->turn_budget_b : keep->turn_budget_a;
          for (int t = 0; t < k.count; ++t)
            k.dead[t] = !MayReachWithin(
                reach, TipRoundCentre(owner, rotation, k.teeth[t], owner_side), eps, turn);
        }
      }
      auto skipped = [&](int tooth) {
        if (known == nullptr || !known->usable) return false;
        for (int t = 0; t < known->count; ++t) {
          if (known->teeth[t] != tooth) continue;
          keep->skipped += known->dead[t];
          return known->dead[t];
        }
        return false;
      };
      // At most three rolls fall in a window two pitches wide: no allocation for them.
      std::vector<int> all;
      int near[3], count = 0;
      if (options.exhaustive_tips) {
        for (int k = 0; k < owner.gear->teeth(); ++k) all.push_back(k);
      } else {
        ForEachRoll(u0, p, u_tip - p, u_tip + p, [&](double, long j) {
          if (count < 3) near[count++] = Mod(-f0.hand * j, owner.gear->teeth());
        });
      }
      const int* teeth_begin = options.exhaustive_tips ? all.data() : near;
      const int* teeth_end = options.exhaustive_tips ? all.data() + all.size() : near + count;
      const struct {
        const int *b, *e;
        const int* begin() const { return b; }
        const int* end() const { return e; }
      } teeth{teeth_begin, teeth_end};
      if (teeth_begin == teeth_end) return;
      const FlankReach reach =
          ReachOf(other, other_side, other_reference, other_base_angle, rho, window);
      for (const int tooth : teeth) {
        if (skipped(tooth)) continue;
        const Vec2 centre = TipRoundCentre(owner, rotation, tooth, owner_side);
        if (!options.exhaustive_tips && !MayReach(reach, centre)) continue;
        const NormalSpan span = TipRoundNormals(owner, tooth, owner_side);
        ArcAgainstFlanks(
            centre, rho, span.from, span.to, other, other_side, window, [&](const ArcHit& h) {
              PotentialContact c;
              c.kind = owner_is_a ? ContactKind::kTipRoundA : ContactKind::kTipRoundB;
              c.side_a = l.side_a;
              c.side_b = l.side_b;
              const Vec2 on_arc = centre - rho * h.flank_normal;
              c.overlap = rho - h.distance;
              const double other_radius = other.gear->base_radius() * h.roll;
              if (owner_is_a) {
                c.tooth_a = tooth;
                c.tooth_b = h.tooth;
                c.point_a = on_arc;
                c.point_b = h.flank_point;
                c.surface_a =
                    NominalTipRoundCentre(owner, tooth, owner_side) - rho * h.flank_normal;
                c.surface_b = h.flank_surface;
                c.normal = -h.flank_normal;
                c.curvature_radius_a = rho;
                c.curvature_radius_b = ring_sign * other_radius;
                c.roll_b = h.roll;
              } else {
                c.tooth_a = h.tooth;
                c.tooth_b = tooth;
                c.point_a = h.flank_point;
                c.point_b = on_arc;
                c.surface_a = h.flank_surface;
                c.surface_b =
                    NominalTipRoundCentre(owner, tooth, owner_side) - rho * h.flank_normal;
                c.normal = h.flank_normal;
                c.curvature_radius_a = other_radius;
                c.curvature_radius_b = rho;
                c.roll_a = h.roll;
              }
              c.point = 0.5 * (c.point_a + c.point_b);
              c.lever_a = Lever(c.point, oa, -c.normal);
              c.lever_b = Lever(c.point, ob, c.normal);
              out->push_back(c);
            });
      }
    };
    tips(a, rotation_a, b, l.side_a, l.side_b, l.base_angle_a, l.base_angle_b, ref_b, true);
    tips(b, rotation_b, a, l.side_b, l.side_a, l.base_angle_b, l.base_angle_a, ref_a, false);
  }
  if (refresh) keep->valid = true;
}

}  // namespace epicycle::geometry
