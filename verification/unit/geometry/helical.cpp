// Helical gears on the spur generator (docs/geometry.md, "Helical gears"): the transverse
// quantities against ISO 21771's formulas, a flank of every section against the closed-form
// involute helicoid, a stage's working quantities and contact ratios, the axial forces and the
// planets' tilting moments against a hand calculation, and the helices that cannot mesh.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/stage.hpp"
#include "figures.hpp"
#include "geometry_fixtures.hpp"
#include "thrown_message.hpp"

using namespace epicycle::geometry;
using Catch::Matchers::Contains;

namespace {

constexpr double kMm = 1e-3;

// A gear of the wind-turbine stage as scenes/grc_helical_stage.toml gives it: m_n 10 mm, α_n 20°,
// β 7.5°, ISO 53 profile A rack, given in the normal section; the ring's addendum 0.9 m_n.
GearSpec NormalGear(const char* name, GearKind kind, int teeth, double x_n, Hand hand) {
  GearSpec g;
  g.name = name;
  g.kind = kind;
  g.teeth = teeth;
  g.module = 10 * kMm;
  g.face_width = 227.5 * kMm;
  g.pressure_angle = Rad(20);
  g.profile_shift = x_n;
  g.tip_round_radius = 0.5 * kMm;
  g.min_tip_thickness = -1;
  g.helix = {Rad(7.5), hand};
  const double mt = g.module / std::cos(g.helix.angle), r = mt * teeth / 2;
  const double xm = x_n * g.module;  // x_n m_n = x_t m_t
  if (kind == GearKind::kExternal) {
    g.tip_radius = r + xm + 1.0 * g.module;
    g.hub_radius = 0.45 * r;
    g.rack = RackCutter{1.25 * g.module, 1.0 * g.module, 0.38 * g.module};
  } else {
    g.tip_radius = r + xm - 0.9 * g.module;  // 1.0 m_n would reach the planets' fillets
    g.root_radius = r + xm + 1.25 * g.module;
    g.root_round_radius = 0.38 * g.module;
    g.hub_radius = 1.2 * r;
  }
  return g;
}

StageSpec WindTurbineStage(double carrier_radius) {
  StageSpec s;
  s.sun = TransverseSpec(NormalGear("sun", GearKind::kExternal, 21, 0.0, Hand::kRight));
  s.planet = TransverseSpec(NormalGear("planet", GearKind::kExternal, 39, 0.0, Hand::kLeft));
  s.ring = TransverseSpec(NormalGear("ring", GearKind::kInternal, 99, 0.04, Hand::kLeft));
  s.carrier_radius = carrier_radius;
  s.planets = 3;
  s.load_sign = 1;
  return s;
}

// m_t (z_s + z_p)/2 of the stage's unshifted gears, plus 0.2 mm of backlash in the sun meshes.
double StandardCarrierRadius() { return 10 * kMm / std::cos(Rad(7.5)) * 60 / 2 + 0.2 * kMm; }

}  // namespace

TEST_CASE("transverse quantities of a helical gear follow ISO 21771", "[unit][geometry]") {
  // ISO 21771:2007, written out here: m_t = m_n/cos β, tan α_t = tan α_n/cos β, d = z m_t,
  // d_b = d cos α_t, p_x = π m_n/sin β, and the base helix angle by its second form,
  // sin β_b = sin β cos α_n (ISO 21771 gives both; the code uses tan β_b = tan β cos α_t).
  // Rounding of a few operations in double: 1e-14 relative.
  for (double beta_deg : {7.5, 15.0, 30.0, 44.0}) {
    const int z = 21;
    const double mn = 10 * kMm, an = Rad(20), xn = 0.35, beta = Rad(beta_deg);
    const TransverseQuantities t = Transverse(z, mn, an, xn, beta);
    const double mt = mn / std::cos(beta);
    const double at = std::atan(std::tan(an) / std::cos(beta));
    CHECK(t.module == Approx(mt).epsilon(1e-14));
    CHECK(t.pressure_angle == Approx(at).epsilon(1e-14));
    CHECK(t.profile_shift * t.module == Approx(xn * mn).epsilon(1e-14));
    CHECK(t.reference_diameter == Approx(z * mt).epsilon(1e-14));
    CHECK(t.base_diameter == Approx(z * mt * std::cos(at)).epsilon(1e-14));
    CHECK(t.base_helix_angle == Approx(std::asin(std::sin(beta) * std::cos(an))).epsilon(1e-13));
    CHECK(t.axial_pitch == Approx(kPi * mn / std::sin(beta)).epsilon(1e-14));
    // The lead turns the reference helix once: p_z = π d / tan β = z p_x.
    CHECK(t.lead == Approx(z * t.axial_pitch).epsilon(1e-13));
    // The generated transverse gear has these radii; its base pitch p_bt = π m_t cos α_t, whose
    // normal projection is the normal rack's base pitch: p_bt cos β_b = π m_n cos α_n.
    GearSpec g = NormalGear("sun", GearKind::kExternal, z, 0.0, Hand::kRight);
    g.helix.angle = beta;
    g.tip_radius = 0;  // the tool's reach
    const Gear gear(TransverseSpec(g));
    CHECK(2 * gear.reference_radius() == Approx(z * mt).epsilon(1e-14));
    CHECK(2 * gear.base_radius() == Approx(z * mt * std::cos(at)).epsilon(1e-14));
    CHECK(gear.base_pitch() * std::cos(t.base_helix_angle) ==
          Approx(kPi * mn * std::cos(an)).epsilon(1e-13));
    CHECK(NormalModule(gear) == Approx(mn).epsilon(1e-14));
  }
}

TEST_CASE("a spur gear's transverse quantities are its own, bit for bit", "[unit][geometry]") {
  const TransverseQuantities t = Transverse(16, 4.23 * kMm, Rad(25), 0.3, 0.0);
  CHECK(t.module == 4.23 * kMm);
  CHECK(t.pressure_angle == Rad(25));
  CHECK(t.profile_shift == 0.3);
  CHECK(t.base_helix_angle == 0);
  CHECK(std::isinf(t.axial_pitch));
  const GearSpec spur = epicycle::test::PaperStage().stage.sun;
  const GearSpec same = TransverseSpec(spur);
  CHECK(same.module == spur.module);
  CHECK(same.pressure_angle == spur.pressure_angle);
  CHECK(same.profile_shift == spur.profile_shift);
  const Gear g(spur);
  CHECK(SectionTurn(g, 0.01) == 0);
}

TEST_CASE("a slice's flank lies on the exact involute helicoid", "[unit][geometry]") {
  // The involute helicoid of base radius r_b and base helix angle β_b (Litvin & Fuentes, "Gear
  // Geometry and Applied Theory", the screw involute surface): the σ = +1 flank of tooth 0 of an
  // external gear at roll u in the section at height z is
  //   P(u, z) = r_b [e(τ) + u e⊥(τ)],  τ = θ0 − u + h z tan β_b / r_b,
  // the base helix's lead 2π r_b / tan β_b turning the tangency line once (h = +1 right hand),
  // and θ0 = s/(2r) + inv α_t the polar angle where the involute leaves the base circle
  // (s = m_t (π/2 + 2 x_t tan α_t) the transverse arc thickness at the reference circle); the
  // σ = −1 flank is its mirror at z = 0, turned alike. Everything below is computed here from
  // the normal-section data (β_b from sin β_b = sin β cos α_n); the gear's points come from its
  // generated half profile (the rack-envelope segment of the involute) turned by SectionTurn.
  // Tolerance 1e-9 m (the brief's): the envelope and the rotation are exact to rounding
  // (~1e-15 relative of a 0.1 m radius).
  for (Hand hand : {Hand::kRight, Hand::kLeft}) {
    const double mn = 10 * kMm, an = Rad(20), beta = Rad(7.5), xn = 0.25;
    GearSpec g = NormalGear("planet", GearKind::kExternal, 39, xn, hand);
    const Gear gear(TransverseSpec(g));
    const double mt = mn / std::cos(beta), at = std::atan(std::tan(an) / std::cos(beta));
    const double r = 39 * mt / 2, rb = r * std::cos(at), xt = xn * mn / mt;
    const double beta_b = std::asin(std::sin(beta) * std::cos(an));
    const double s = mt * (kPi / 2 + 2 * xt * std::tan(at));
    const double theta0 = s / (2 * r) + std::tan(at) - at;
    const int h = hand == Hand::kRight ? 1 : -1;
    int checked = 0;
    double worst = 0;
    for (const Segment& seg : gear.half_profile().segments) {
      if (seg.role != SegmentRole::kInvolute) continue;
      for (int k = 0; k <= 8; ++k) {
        const Vec2 p = seg.Point(seg.t0 + (seg.t1 - seg.t0) * k / 8.0);
        const double u = std::sqrt(p.squaredNorm() / (rb * rb) - 1);
        for (double z : {-113.75 * kMm, -40 * kMm, 0.0, 77 * kMm, 113.75 * kMm}) {
          const double tau = theta0 - u + h * z * std::tan(beta_b) / rb;
          const Vec2 exact = rb * (Dir(tau) + u * DirPerp(tau));
          const Vec3 code = SurfacePoint(gear, p, z);
          CHECK((code.head<2>() - exact).norm() < 1e-9);
          CHECK(code.z() == z);
          // σ = −1: the mirror of the section z = 0, turned by the same lead.
          const double tau_m = -(theta0 - u) + h * z * std::tan(beta_b) / rb;
          const Vec2 exact_m = rb * (Dir(tau_m) - u * DirPerp(tau_m));
          const Vec3 code_m = SurfacePoint(gear, Vec2(p.x(), -p.y()), z);
          CHECK((code_m.head<2>() - exact_m).norm() < 1e-9);
          worst = std::max(
              {worst, (code.head<2>() - exact).norm(), (code_m.head<2>() - exact_m).norm()});
          ++checked;
        }
      }
    }
    CHECK(checked > 0);
    epicycle::test::FigureValue(
        std::string("helical flank vs involute helicoid, ") + HandName(hand) + " hand", worst, "m");
  }
}

TEST_CASE("a helical stage's working quantities and contact ratios", "[unit][geometry]") {
  const double a = StandardCarrierRadius();
  const Stage st(WindTurbineStage(a));
  const double mn = 10 * kMm, an = Rad(20), beta = Rad(7.5), b = 227.5 * kMm;
  const double mt = mn / std::cos(beta), at = std::atan(std::tan(an) / std::cos(beta));
  // ISO 21771: ε_β = b sin β/(π m_n); the working pitch cylinders of an external mesh divide a
  // in the ratio of the teeth, d_w1 = 2 a z1/(z1 + z2) (internal: 2 a z1/(z2 − z1)), and
  // tan β_w = tan β d_w/d; cos α_wt = m_t (z2 ± z1) cos α_t/(2a); ε_α from the tip circles:
  // [√(r_a1² − r_b1²) ± √(r_a2² − r_b2²) ∓ a sin α_wt]/(π m_t cos α_t).
  const double eps_beta = b * std::sin(beta) / (kPi * mn);
  for (const MeshSummary& m : st.meshes()) {
    const bool ring = m.kind == MeshKind::kPlanetRing;
    const Gear& g1 = ring ? st.planet(m.planet) : st.sun();
    const Gear& g2 = ring ? st.ring() : st.planet(m.planet);
    const HelicalMesh h = SummariseHelicalMesh(m, g1, g2);
    const int z1 = g1.teeth(), z2 = g2.teeth();
    const double awt = std::acos(mt * (ring ? z2 - z1 : z2 + z1) * std::cos(at) / (2 * a));
    const double dw1 = 2 * a * z1 / (ring ? z2 - z1 : z2 + z1);
    const double bw = std::atan(std::tan(beta) * dw1 / (z1 * mt));
    const double rb1 = z1 * mt * std::cos(at) / 2, rb2 = z2 * mt * std::cos(at) / 2;
    const double l1 = std::sqrt(std::pow(g1.tip_radius(), 2) - rb1 * rb1);
    const double l2 = std::sqrt(std::pow(g2.tip_radius(), 2) - rb2 * rb2);
    const double eps_alpha = (ring ? l1 - l2 + a * std::sin(awt) : l1 + l2 - a * std::sin(awt)) /
                             (kPi * mt * std::cos(at));
    CHECK(h.working_pressure_angle == Approx(awt).epsilon(1e-12));
    CHECK(h.working_helix_angle == Approx(bw).epsilon(1e-12));
    CHECK(h.overlap_ratio == Approx(eps_beta).epsilon(1e-14));
    CHECK(h.transverse_contact_ratio == Approx(eps_alpha).epsilon(1e-12));
    CHECK(h.total_contact_ratio == Approx(eps_alpha + eps_beta).epsilon(1e-12));
  }
  // The assembly condition and the phasing stay those of the transverse plane:
  // (z_s + z_r)/n = 40 whole, planet i's mesh phase z_s ψ_i/(2π) mod 1 = 0, 1/3, 2/3 cycles (7i).
  for (int i = 0; i < 3; ++i)
    CHECK(st.meshes()[MeshIndex(i, MeshKind::kSunPlanet)].phase ==
          Approx(std::fmod(21.0 * i / 3, 1.0)).margin(1e-12));
}

TEST_CASE("axial forces and the planets' tilting moments against a hand calculation",
          "[unit][geometry]") {
  // Hand calculation (docs/geometry.md, "Helical gears", and the model specification's
  // "Helical forces"): with the sun torque T shared by n planets,
  // the tangential force at the reference cylinder is F_t = T/(n r_sun) and F_a = F_t tan β
  // (= F_t,w tan β_w at the working cylinder: F_t r = F_t,w r_w and tan β_w = tan β r_w/r).
  // Direction by the screw rule: a right-hand sun turned counter-clockwise (T > 0, +z) by its
  // torque is pushed by its mates along +z, as a right-hand screw driven into a held nut; the
  // planets take −z from the sun and, from the ring whose flank faces the other way, +z. The
  // forces act at the operating pitch points, r_w,p = a z_p/(z_s + z_p) towards the sun and
  // a z_p/(z_r − z_p) towards the ring; their moment about the planet's centre is taken here
  // with 3D cross products, M = Σ ρ × F.
  const double a = StandardCarrierRadius();
  for (double torque : {56.7e3, -56.7e3}) {
    StageSpec spec = WindTurbineStage(a);
    spec.load_sign = torque > 0 ? 1 : -1;
    const Stage st(spec);
    const StageAxialLoads loads = AxialLoads(st, torque);
    const double mt = 10 * kMm / std::cos(Rad(7.5));
    const double f_a = std::abs(torque) / (3 * 21 * mt / 2) * std::tan(Rad(7.5));
    const double sign = torque > 0 ? 1 : -1;
    CHECK(loads.sun_axial_force == Approx(3 * sign * f_a).epsilon(1e-12));
    CHECK(loads.ring_axial_force == Approx(-3 * sign * f_a).epsilon(1e-12));
    for (int i = 0; i < 3; ++i) {
      const MeshAxialLoad& sun_mesh = loads.meshes[MeshIndex(i, MeshKind::kSunPlanet)];
      const MeshAxialLoad& ring_mesh = loads.meshes[MeshIndex(i, MeshKind::kPlanetRing)];
      CHECK(sun_mesh.axial_force == Approx(f_a).epsilon(1e-12));
      CHECK(ring_mesh.axial_force == Approx(f_a).epsilon(1e-12));
      const Eigen::Vector3d e_r(std::cos(st.planet_angle(i)), std::sin(st.planet_angle(i)), 0);
      const Eigen::Vector3d e_t(-e_r.y(), e_r.x(), 0), ez(0, 0, 1);
      const Eigen::Vector3d moment =
          (-a * 39 / 60 * e_r).cross(-sign * f_a * ez) + (a * 39 / 60 * e_r).cross(sign * f_a * ez);
      CHECK(loads.planets[i].tilting_moment == Approx(moment.dot(e_t)).epsilon(1e-12));
      CHECK(std::abs(moment.dot(e_r)) < 1e-9);  // about the tangential axis only
      CHECK(std::abs(loads.planets[i].net_axial_force) < 1e-9 * f_a);
    }
    // Magnitude: F_a d_w,planet, a diameter apart (here both meshes at the same centre distance).
    CHECK(std::abs(loads.planets[0].tilting_moment) ==
          Approx(f_a * 2 * a * 39 / 60).epsilon(1e-12));
  }
}

TEST_CASE("helices that cannot mesh are refused, naming the key and the rule", "[unit][geometry]") {
  const double a = StandardCarrierRadius();
  StageSpec s = WindTurbineStage(a);
  s.planet.helix.hand = Hand::kRight;  // the same hand as the sun: an external mesh
  CHECK_THROWS_WITH(Stage(s), Contains("planet.hand = \"right\"") &&
                                  Contains("an external mesh needs opposite hands"));
  s = WindTurbineStage(a);
  s.ring.helix.hand = Hand::kRight;  // not the planets' hand: an internal mesh
  CHECK_THROWS_WITH(Stage(s), Contains("ring.hand = \"right\"") &&
                                  Contains("an internal mesh needs the same hand"));
  s = WindTurbineStage(a);
  s.planet.helix.angle = Rad(8);
  CHECK_THROWS_WITH(Stage(s), Contains("planet.helix_angle_deg = 8") &&
                                  Contains("must equal sun.helix_angle_deg = 7.5"));
  CHECK_THROWS_WITH(Transverse(21, 10 * kMm, Rad(20), 0, Rad(45)),
                    Contains("helix_angle_deg = 45: must be in [0, 45)"));
  PairSpec p = epicycle::test::IsoPair2040();
  p.gear1.helix = {Rad(10), Hand::kLeft};
  p.gear2.helix = {Rad(10), Hand::kLeft};
  p.gear1 = TransverseSpec(p.gear1);
  p.gear2 = TransverseSpec(p.gear2);
  CHECK_THROWS_WITH(GearPair(p), Contains("gear2.hand = \"left\"") &&
                                     Contains("an external mesh needs opposite hands"));
}
