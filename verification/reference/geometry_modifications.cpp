// Profile relief and pitch deviations in the contact geometry, against closed forms written here:
//  - on the line of action a relieved pair's overlap is the involutes' minus C_A(u_A) + C_B(u_B)
//    (the relief law evaluated from the scene's numbers, not the library's zones);
//  - rigid gears with relief: the unloaded transmission error, as a length on the line of action,
//    solves r_b1 Δ = C_A(u_A + Δ) + C_B(u_B) for the first pair to close (gear 2 held);
//  - a tooth turned by its cumulative pitch deviation F_p moves its flank along the line of action
//    by σ r_b F_p / r = σ F_p cos α.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/pair.hpp"
#include "figures.hpp"
#include "geometry_fixtures.hpp"

using namespace epicycle::geometry;
using epicycle::test::Sci;
using epicycle::test::VerifyRow;

namespace {

PairSpec IsoPair() { return epicycle::test::IsoPair2040(); }

// The relief law of the spec, from the scene's numbers: C (u − u_s)^p / (u_a − u_s)^p, u_a at the
// tip circle (the scene's pairs give none: the tool's reach r + x m + h_f0).
double ReliefLaw(const GearSpec& g, double u) {
  const Relief& t = g.modification.tip;
  if (t.amount == 0) return 0;
  const double rb = 0.5 * g.module * g.teeth * std::cos(g.pressure_angle);
  const double us = std::sqrt(std::pow(t.start_radius / rb, 2) - 1);
  const double ra = g.tip_radius > 0
                        ? g.tip_radius
                        : 0.5 * g.module * g.teeth + g.profile_shift * g.module + g.rack->dedendum;
  const double ua = std::sqrt(std::pow(ra / rb, 2) - 1);
  const double xi = (u - us) / (ua - us);  // internal gears: u_a < u_s
  if (xi <= 0) return 0;
  return t.amount * (t.shape == ReliefShape::kLinear ? xi : xi * xi);
}

using Key = std::tuple<int, int, int>;  // side, tooth A, tooth B
std::map<Key, PotentialContact> Involutes(const GearPair& p, const PairPoses& poses) {
  std::map<Key, PotentialContact> out;
  ContactSearchOptions o;
  o.gap_window = 200e-6;
  for (const PotentialContact& c : p.Contacts(poses, o)) {
    if (c.kind == ContactKind::kInvolute) out[{c.side_a, c.tooth_a, c.tooth_b}] = c;
  }
  return out;
}

}  // namespace

TEST_CASE("relief on the line of action: overlap minus C_A(u_A) + C_B(u_B)",
          "[reference][geometry]") {
  const PairSpec nominal = IsoPair();
  for (const ReliefShape shape : {ReliefShape::kLinear, ReliefShape::kParabolic}) {
    PairSpec s = nominal;
    s.gear1.modification.tip = {20e-6, 43.0e-3, shape};
    s.gear2.modification.tip = {12e-6, 82.5e-3, shape};
    const GearPair a(nominal), b(s);
    double worst = 0;
    int relieved = 0;
    for (int i = 0; i < 40; ++i) {
      const double angle = a.mesh_cycle() * i / 40.0;
      const auto c0 = Involutes(a, a.Poses(angle));
      const auto c1 = Involutes(b, b.Poses(angle));
      for (const auto& [key, c] : c1) {
        const auto it = c0.find(key);
        if (it == c0.end()) continue;  // at the involutes' ends (the relieved tip round moved them)
        const double expect =
            -(ReliefLaw(s.gear1, it->second.roll_a) + ReliefLaw(s.gear2, it->second.roll_b));
        if (expect < 0) ++relieved;
        worst = std::max(worst, std::abs(c.overlap - it->second.overlap - expect));
        // The relieved contact points sit on the line of action, C inside each flank.
        CHECK(std::abs((c.point_a - it->second.point_a).dot(c.normal) +
                       ReliefLaw(s.gear1, it->second.roll_a)) <= 1e-12);
      }
    }
    CHECK(relieved > 10);
    CHECK(worst <= 1e-12);  // round-off of positions of 0.1 m
  }
}

TEST_CASE("rigid gears with tip relief: unloaded transmission error is the relief on the LOA",
          "[reference][geometry]") {
  PairSpec s = IsoPair();
  s.gear1.modification.tip = {15e-6, 41.0e-3, ReliefShape::kLinear};
  s.gear2.modification.tip = {15e-6, 81.5e-3, ReliefShape::kLinear};
  const GearPair nominal(IsoPair()), relieved(s);
  const double rb1 = relieved.gear1().base_radius();
  const int side = relieved.loaded_side();
  double worst = 0, largest = 0;
  int compared = 0;
  for (int i = 0; i < 48; ++i) {
    const double angle = relieved.mesh_cycle() * i / 48.0;
    // Closed form: every loaded involute pair of the nominal gears touches (zero backlash); turning
    // gear 1 by Δ advances its flank r_b1 Δ along the line of action and its roll there by Δ, gear
    // 2's flank stays: the pair closes when r_b1 Δ = C_1(u_1 + Δ) + C_2(u_2) (fixed point; the
    // map contracts by C′/r_b1 ~ 1e-3).
    double closed = 1e9;
    for (const auto& [key, c] : Involutes(nominal, nominal.Poses(angle))) {
      if (std::get<0>(key) != side || std::abs(c.overlap) > 1e-12) continue;
      double d = 0;
      for (int it = 0; it < 50; ++it) {
        d = (ReliefLaw(s.gear1, c.roll_a + d) + ReliefLaw(s.gear2, c.roll_b)) / rb1;
      }
      closed = std::min(closed, rb1 * d);
    }
    // The library: bisection on gear 1's rotation until the largest loaded overlap is zero.
    auto largest_overlap = [&](double d) {
      PairPoses p = relieved.Poses(angle);
      p.gear1.rotation += side * d;
      double m = -1;
      for (const auto& [key, c] : Involutes(relieved, p)) {
        if (std::get<0>(key) == side) m = std::max(m, c.overlap);
      }
      return m;
    };
    double lo = 0, hi = 1e-3;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      (largest_overlap(mid) < 0 ? lo : hi) = mid;
    }
    const double model = rb1 * 0.5 * (lo + hi);
    worst = std::max(worst, std::abs(model - closed));
    largest = std::max(largest, closed);
    ++compared;
  }
  CHECK(compared == 48);
  CHECK(largest > 1e-6);  // the relieved zone is reached: the error is not trivially zero
  CHECK(worst <= 1e-12);  // bisection to 1e-3·2^-80 rad; fixed point to round-off
  VerifyRow("rigid pair 20/40 with 15 um linear tip relief: unloaded TE on the LOA",
            "closed form r_b1 D = C1(u1 + D) + C2(u2)", "contact search + bisection",
            Sci(worst) + " m (max TE " + Sci(largest) + " m)", "1e-12 m", worst <= 1e-12);
}

TEST_CASE("pitch deviation: the tooth's flank moves sigma F_p cos(alpha) along the LOA",
          "[reference][geometry]") {
  PairSpec s = IsoPair();
  s.gear1.pitch_deviations.assign(20, 0.0);
  s.gear1.pitch_deviations[3] = 6e-6;
  s.gear2.pitch_deviations.assign(40, 0.0);
  s.gear2.pitch_deviations[37] = -4e-6;
  const GearPair a(IsoPair()), b(s);
  const double ca = std::cos(s.gear1.pressure_angle);
  double worst = 0;
  int moved = 0;
  for (int i = 0; i < 200; ++i) {
    const double angle = 2 * kPi * i / 200.0;  // a whole revolution of gear 1
    const auto c0 = Involutes(a, a.Poses(angle));
    for (const auto& [key, c] : Involutes(b, b.Poses(angle))) {
      const auto it = c0.find(key);
      if (it == c0.end()) continue;
      const auto [side, ta, tb] = key;
      // Tooth A turned ccw by F_p/r: overlap + σ_A r_bA F_p/r_A. Gear B: the overlap is constant
      // under the rigid ratio θ_B = −(r_bA/r_bB) θ_A, so dδ/dθ_B = σ_A r_bB, and B's tooth turned
      // ccw by F_p/r_B adds σ_A r_bB F_p/r_B. Both are σ_A F_p cos α.
      const double expect =
          side * ca * (s.gear1.pitch_deviations[ta] + s.gear2.pitch_deviations[tb]);
      if (expect != 0) ++moved;
      worst = std::max(worst, std::abs(c.overlap - it->second.overlap - expect));
    }
  }
  CHECK(moved > 20);
  CHECK(worst <= 1e-12);
}

TEST_CASE("ISO 1328-1 pitch tolerances and the random set of a grade", "[unit][geometry]") {
  // Hand values from the standard's formulas: m = 4.23 mm, d = 67.68 mm (the paper's sun).
  const double m = 4.23e-3, d = 16 * m;
  const double f6 = (0.001 * 67.68 + 0.4 * 4.23 + 5) * std::sqrt(2.0) * 1e-6;
  const double F6 =
      (0.002 * 67.68 + 0.55 * std::sqrt(67.68) + 0.7 * 4.23 + 12) * std::sqrt(2.0) * 1e-6;
  CHECK(iso::SinglePitchTolerance(m, d, 6) == Approx(f6).epsilon(1e-12));
  CHECK(iso::CumulativePitchTolerance(m, d, 6) == Approx(F6).epsilon(1e-12));
  // One class is a factor √2.
  CHECK(iso::SinglePitchTolerance(m, d, 7) / iso::SinglePitchTolerance(m, d, 6) ==
        Approx(std::sqrt(2.0)).epsilon(1e-14));
  const std::vector<double> fp = iso::RandomPitchDeviations(16, m, 6, 7);
  REQUIRE(fp.size() == 16);
  CHECK(fp[0] == 0.0);
  double worst_single = 0;
  for (int k = 0; k < 16; ++k) {
    worst_single = std::max(worst_single, std::abs(fp[(k + 1) % 16] - fp[k]));
  }
  const auto [lo, hi] = std::minmax_element(fp.begin(), fp.end());
  CHECK(worst_single <= f6 * (1 + 1e-12));
  CHECK(*hi - *lo <= F6 * (1 + 1e-12));
  CHECK(worst_single >= 0.3 * f6);                       // a grade-6 set, not a negligible one
  CHECK(iso::RandomPitchDeviations(16, m, 6, 7) == fp);  // the seed fixes the set
  CHECK(iso::RandomPitchDeviations(16, m, 6, 8) != fp);
  CHECK_THROWS_WITH(iso::SinglePitchTolerance(m, d, 12, "sun.pitch.iso1328_grade"),
                    Catch::Matchers::Contains("sun.pitch.iso1328_grade = 12: must be an ISO "
                                              "1328-1:2013 flank tolerance class, 1 to 11"));
}

namespace {

// The relieved flank of tooth k, side σ, as a dense polyline: the generated involute (the half
// profile's), turned by the tooth's pitch deviation, each point moved into the tooth by the relief
// law of the spec at its roll u = √(R²/r_b² − 1) (normal from the polyline's own chords).
std::vector<Vec2> DenseRelievedFlank(const PosedGear& g, int tooth, int side, int n) {
  const GearSpec& s = g.gear->spec();
  const Segment* seg = g.gear->half_profile().Find(SegmentRole::kInvolute);
  const double r = 0.5 * s.module * s.teeth, rb = r * std::cos(s.pressure_angle);
  const double fp = s.pitch_deviations.empty() ? 0.0 : s.pitch_deviations[tooth];
  const double turn = g.pose.rotation + tooth * g.gear->pitch_angle() + fp / r;
  std::vector<Vec2> body;
  for (int i = 0; i <= n; ++i) {
    Vec2 p = seg->Point(seg->t0 + (seg->t1 - seg->t0) * i / n);
    p.y() *= side;
    body.push_back(p);
  }
  std::vector<Vec2> out;
  for (int i = 0; i <= n; ++i) {
    const Vec2 t = body[std::min(i + 1, n)] - body[std::max(i - 1, 0)];
    Vec2 normal = Vec2(-t.y(), t.x()).normalized();
    const Vec2 e_theta = Vec2(-body[i].y(), body[i].x()).normalized();
    if (normal.dot(e_theta) * side < 0) normal = -normal;  // out of the tooth, into the space
    const double u = std::sqrt(std::max(0.0, body[i].squaredNorm() / (rb * rb) - 1));
    const double c = ReliefLaw(s, u);
    out.push_back(g.pose.geometric_centre + Rotate(body[i] - c * normal, turn));
  }
  return out;
}

double DistanceToPolyline(const Vec2& c, const std::vector<Vec2>& line) {
  double best = 1e9;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec2 ab = line[i + 1] - line[i];
    const double t = std::clamp((c - line[i]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (line[i] + t * ab - c).norm());
  }
  return best;
}

}  // namespace

TEST_CASE("tip round against a relieved flank of a tooth with a pitch deviation: brute force",
          "[reference][geometry]") {
  // The paper's stage with 10 µm parabolic long-ish tip relief on every gear and a pitch
  // deviation on every sun tooth: each tip-round contact's overlap against ρ − the distance from
  // the (relieved, turned) round's centre to a 20 000-point polyline of the relieved flank.
  auto scene = epicycle::test::PaperStage();
  const Stage nominal(scene.stage);
  scene.stage.sun.modification.tip = {10e-6, 37.0e-3, ReliefShape::kParabolic};
  scene.stage.planet.modification.tip = {10e-6, 52.5e-3, ReliefShape::kParabolic};
  scene.stage.ring.modification.tip = {10e-6, 136.5e-3, ReliefShape::kParabolic};
  scene.stage.sun.pitch_deviations = iso::RandomPitchDeviations(16, scene.stage.sun.module, 8, 5);
  const Stage st(scene.stage);
  ContactSearchOptions opt;
  opt.gap_window = 100e-6;
  double worst = 0;
  int tested = 0;
  for (int k = 0; k < 40; ++k) {
    const StagePoses p = st.Poses(st.mesh_cycle() * k / 40.0);
    epicycle::test::ForEachStageContact(
        st, p, opt,
        [&](const PosedGear& a, const PosedGear& b, MeshKind, const PotentialContact& c) {
          if (c.kind == ContactKind::kInvolute) return;
          const bool on_a = c.kind == ContactKind::kTipRoundA;
          const PosedGear& owner = on_a ? a : b;
          const PosedGear& mate = on_a ? b : a;
          const int tooth = on_a ? c.tooth_a : c.tooth_b, side = on_a ? c.side_a : c.side_b;
          const GearSpec& os = owner.gear->spec();
          const double fp = os.pitch_deviations.empty() ? 0.0 : os.pitch_deviations[tooth];
          Vec2 centre = owner.gear->tip_round().centre;
          centre.y() *= side;
          centre = owner.pose.geometric_centre +
                   Rotate(centre, owner.pose.rotation + tooth * owner.gear->pitch_angle() +
                                      fp / (0.5 * os.module * os.teeth));
          const auto flank = DenseRelievedFlank(mate, on_a ? c.tooth_b : c.tooth_a,
                                                on_a ? c.side_b : c.side_a, 20000);
          const double overlap = owner.gear->tip_round().radius - DistanceToPolyline(centre, flank);
          worst = std::max(worst, std::abs(overlap - c.overlap));
          ++tested;
        });
  }
  CHECK(tested >= 12);
  // The polyline's chord error: (arc step)²/(8 ρ_min) ≈ (5 mm/2e4)²/(8·1 mm) ≈ 1e-11 m; the
  // relief's offset along a finite-difference normal adds C·(normal error) ≈ 1e-5·1e-8.
  CHECK(worst <= 1e-8);
  VerifyRow("tip round vs relieved flank (10 um parabolic, sun pitch class 8), " +
                std::to_string(tested) + " contacts",
            "dense relieved-flank polyline (20 000 points)", "Newton on the relieved curve",
            Sci(worst) + " m", "1e-8 m", worst <= 1e-8);
}
