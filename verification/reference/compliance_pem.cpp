// The potential-energy-method mesh-stiffness reference (support/pem_reference.hpp) against
// references that do not come from itself: Yang & Lin's Hertzian term, the Timoshenko cantilever,
// the involute's geometry, Tian's published angle-parametrised energy integrals, and ISO 6336-1
// method B mesh stiffness for ISO basic-rack pairs.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "pem_reference.hpp"

namespace pem = epicycle::verification::pem;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// ISO basic rack (α = 20°, h_aP = 1.0 m, h_fP = 1.25 m), unshifted, steel; bore = 0.5 r_f.
pem::Gear IsoGear(int z, double module_m) {
  pem::Gear g;
  g.teeth = z;
  g.module_m = module_m;
  g.pressure_angle_rad = 20.0 * kDeg;
  g.profile_shift = 0.0;
  const double r = 0.5 * z * module_m;
  g.tip_radius_m = r + 1.0 * module_m;
  g.root_radius_m = r - 1.25 * module_m;
  g.bore_radius_m = 0.5 * g.root_radius_m;
  g.face_width_m = 0.020;
  g.youngs_modulus_pa = 206e9;
  g.poisson_ratio = 0.3;
  g.tool_tip_radius_coefficient = 0.38;  // ISO 53 profile A
  return g;
}

pem::GearPair IsoPair(int z1, int z2, double module_m) {
  pem::GearPair p;
  p.gear1 = IsoGear(z1, module_m);
  p.gear2 = IsoGear(z2, module_m);
  p.centre_distance_m = 0.5 * (z1 + z2) * module_m;
  return p;
}

/// ISO 6336-1:2006 method B, spur, solid discs, written out here from the standard (docs/model.md §8):
/// q′ = C1 + C2/z1 + C3/z2 + C4 x1 + C5 x1/z1 + C6 x2 + C7 x2/z2 + C8 x1² + C9 x2² [mm·µm/N],
/// c′ = (1/q′) C_M C_R C_B [N/(mm·µm)], C_M = 0.8, C_R = 1,
/// C_B = [1 + 0.5 (1.2 − h_fP/m)] [1 − 0.02 (20° − α)], c_γα = c′ (0.75 ε_α + 0.25).
/// C_B as ISO 6336-1:2006 writes it (and compliance/iso6336 implements it): 0.975, not 1, for the
/// h_fP = 1.25 m rack; with C_B = 1 both ISO values would be 2.6 % higher.
struct Iso {
  double q_prime, c_prime, basic_rack_factor, contact_ratio, c_gamma_alpha;
};

Iso IsoMethodB(int z1, int z2, double x1, double x2, double alpha_deg, double dedendum_per_module,
               double contact_ratio) {
  const double c[9] = {0.04723,  0.15551,  0.25791, -0.00635, -0.11654,
                       -0.00193, -0.24188, 0.00529, 0.00182};
  Iso iso;
  iso.q_prime = c[0] + c[1] / z1 + c[2] / z2 + c[3] * x1 + c[4] * x1 / z1 + c[5] * x2 +
                c[6] * x2 / z2 + c[7] * x1 * x1 + c[8] * x2 * x2;
  iso.basic_rack_factor =
      (1.0 + 0.5 * (1.2 - dedendum_per_module)) * (1.0 - 0.02 * (20.0 - alpha_deg));
  iso.c_prime = 1.0 / iso.q_prime * 0.8 * 1.0 * iso.basic_rack_factor;
  iso.contact_ratio = contact_ratio;
  iso.c_gamma_alpha = iso.c_prime * (0.75 * contact_ratio + 0.25);
  return iso;
}

/// ε_α of an external pair from its tip circles (ISO 21771), written out independently of pem::.
double TransverseContactRatio(int z1, int z2, double m, double alpha, double ra1, double ra2,
                              double a) {
  const double rb1 = 0.5 * z1 * m * std::cos(alpha), rb2 = 0.5 * z2 * m * std::cos(alpha);
  const double alpha_w = std::acos((rb1 + rb2) / a);
  const double path =
      std::sqrt(ra1 * ra1 - rb1 * rb1) + std::sqrt(ra2 * ra2 - rb2 * rb2) - a * std::sin(alpha_w);
  return path / (std::numbers::pi * m * std::cos(alpha));
}

}  // namespace

TEST_CASE("PEM: the Hertzian term is Yang & Lin's pi E b / (4 (1 - nu^2))", "[reference][pem]") {
  const pem::GearPair pair = IsoPair(20, 40, 4e-3);
  const double e = 206e9, nu = 0.3, b = 0.020;
  const double k_h = std::numbers::pi * e * b / (4.0 * (1.0 - nu * nu));
  CHECK(pem::HertzStiffness(pair) == Approx(k_h).epsilon(1e-14));
  const pem::MeshGeometry m = pem::Geometry(pair);
  const pem::PairCompliance c =
      pem::SinglePairCompliance(pair, 0.5 * (m.path_start_m + m.path_end_m));
  CHECK(c.hertz_m_per_n == Approx(1.0 / k_h).epsilon(1e-14));
}

TEST_CASE("PEM: the adaptive Gauss-Legendre rule", "[reference][pem]") {
  // Analytic integrand: one 20-point panel is already exact to round-off.
  CHECK(pem::IntegrateAdaptive([](double x) { return std::sin(x); }, 0.0, std::numbers::pi,
                               1e-12) == Approx(2.0).epsilon(1e-14));
  // A √x end-point branch needs the adaptive splitting.
  CHECK(pem::IntegrateAdaptive([](double x) { return std::sqrt(x); }, 0.0, 1.0, 1e-11) ==
        Approx(2.0 / 3.0).epsilon(1e-10));
}

TEST_CASE("PEM: the energy integrals of a uniform beam are Timoshenko's cantilever",
          "[reference][pem]") {
  // Rectangle of half-thickness h, length L, width b, clamped at y = 0, loaded at y = L.
  const double length = 9e-3, h = 2.5e-3, b = 0.02, e = 2.2e11, g = 0.8e11;
  const double area = 2.0 * h * b, inertia = b * std::pow(2.0 * h, 3) / 12.0;
  const pem::BeamElasticity el{e, g, b};
  const auto uniform = [&](double y) { return pem::BeamSection{y, 1.0, h}; };
  const double tol = 1e-8;

  SECTION("transverse force: bending F L^3/(3EI) and shear 1.2 F L/(GA)") {
    const pem::BeamCompliance c =
        pem::BeamEnergyCompliance(uniform, 0.0, length, {length, 0.0, 0.0}, el, 1e-12);
    CHECK(c.bending_m_per_n == Approx(std::pow(length, 3) / (3.0 * e * inertia)).epsilon(tol));
    CHECK(c.shear_m_per_n == Approx(1.2 * length / (g * area)).epsilon(tol));
    CHECK(c.compression_m_per_n == 0.0);
  }
  SECTION("axial force: compression F L/(EA)") {
    const pem::BeamCompliance c = pem::BeamEnergyCompliance(
        uniform, 0.0, length, {length, 0.0, std::numbers::pi / 2}, el, 1e-12);
    CHECK(c.compression_m_per_n == Approx(length / (e * area)).epsilon(tol));
    CHECK(c.bending_m_per_n <= 1e-20 * c.compression_m_per_n);  // cos²(π/2) ~ 4e-33
  }
  SECTION("oblique force off the centre line: superposed closed forms") {
    // M(y) = cos β (L − y) − sin β e0; ∫ M² dy = cos²β L³/3 − cos β sin β e0 L² + sin²β e0² L.
    const double beta = 0.37, e0 = 1.1e-3, cb = std::cos(beta), sb = std::sin(beta);
    const pem::BeamCompliance c =
        pem::BeamEnergyCompliance(uniform, 0.0, length, {length, e0, beta}, el, 1e-12);
    const double bending = (cb * cb * std::pow(length, 3) / 3.0 - cb * sb * e0 * length * length +
                            sb * sb * e0 * e0 * length) /
                           (e * inertia);
    CHECK(c.bending_m_per_n == Approx(bending).epsilon(tol));
    CHECK(c.shear_m_per_n == Approx(1.2 * cb * cb * length / (g * area)).epsilon(tol));
    CHECK(c.compression_m_per_n == Approx(sb * sb * length / (e * area)).epsilon(tol));
  }
  SECTION("a beam clamped at y0 > 0, parametrised by p = y^2 (checks dy/dp)") {
    const double y0 = 30e-3;
    const auto by_square = [&](double p) {
      const double y = std::sqrt(p);
      return pem::BeamSection{y, 0.5 / y, h};
    };
    const pem::BeamCompliance c = pem::BeamEnergyCompliance(
        by_square, y0 * y0, std::pow(y0 + length, 2), {y0 + length, 0.0, 0.0}, el, 1e-12);
    CHECK(c.bending_m_per_n == Approx(std::pow(length, 3) / (3.0 * e * inertia)).epsilon(tol));
    CHECK(c.shear_m_per_n == Approx(1.2 * length / (g * area)).epsilon(tol));
  }
}

TEST_CASE("PEM: tooth thickness and the load line follow the involute", "[reference][pem]") {
  for (const double x : {-0.3, 0.0, 0.227, 0.5}) {
    for (const double alpha_deg : {20.0, 25.0}) {
      pem::Gear g = IsoGear(24, 4.23e-3);
      g.profile_shift = x;
      g.pressure_angle_rad = alpha_deg * kDeg;
      const double alpha = g.pressure_angle_rad;
      // s = m (π/2 + 2 x tan α) at the reference circle.
      CHECK(pem::ToothThicknessAt(g, pem::ReferenceRadius(g)) ==
            Approx(g.module_m * (std::numbers::pi / 2 + 2.0 * x * std::tan(alpha))).epsilon(1e-14));
      // The flank point of roll t: its polar radius and half-angle agree with s(r); the load line
      // through it at β below the perpendicular to the centre line is tangent to the base circle
      // (distance r_b from the centre) and normal to the flank (finite-difference tangent).
      const double r_b = pem::BaseRadius(g);
      for (const double t : {0.05, 0.3, 0.5, 0.7}) {
        const pem::FlankPoint p = pem::FlankAtRoll(g, t);
        if (p.radius_m > g.tip_radius_m) continue;
        CHECK(std::hypot(p.y_m, p.half_thickness_m) == Approx(r_b * std::hypot(1.0, t)));
        CHECK(2.0 * p.radius_m * p.half_angle_rad ==
              Approx(pem::ToothThicknessAt(g, p.radius_m)).epsilon(1e-12));
        const double dx = -std::cos(p.load_angle_rad), dy = -std::sin(p.load_angle_rad);
        CHECK(std::abs(p.half_thickness_m * dy - p.y_m * dx) == Approx(r_b).epsilon(1e-12));
        const double dt = 1e-6;
        const pem::FlankPoint a = pem::FlankAtRoll(g, t - dt), b = pem::FlankAtRoll(g, t + dt);
        const double tx = b.half_thickness_m - a.half_thickness_m, ty = b.y_m - a.y_m;
        CHECK(std::abs(tx * dx + ty * dy) / std::hypot(tx, ty) < 1e-8);
        CHECK((b.y_m - a.y_m) / (2 * dt) == Approx(p.dy_dt).epsilon(1e-7));
      }
    }
  }
}

TEST_CASE("PEM: tooth integrals equal Tian's published angle-parametrised integrals",
          "[reference][pem]") {
  // Tian (2004, MSc thesis, U. Alberta) and Wu, Zuo & Parey (2008, J. Sound Vib. 317:608),
  // for a tooth whose root circle is its base circle, with α2 = ψ_b (base half-angle) and α1 the
  // load angle, tan α_c = α1 + α2 at the contact radius:
  //   1/k_b = ∫_{−α1}^{α2} 3{1 + cos α1[(α2 − α) sin α − cos α]}² (α2 − α) cos α
  //                        / (2 E b [sin α + (α2 − α) cos α]³) dα
  //   1/k_s = ∫ 1.2 (1 + ν)(α2 − α) cos α cos²α1 / (E b [sin α + (α2 − α) cos α]) dα
  //   1/k_a = ∫ (α2 − α) cos α sin²α1 / (2 E b [sin α + (α2 − α) cos α]) dα
  // (plane stress: E as is). pem:: integrates the same energies in its own coordinates (the roll
  // angle of the flank point and the section's distance from the gear centre).
  for (const int z : {20, 40}) {
    pem::Gear g = IsoGear(z, 4e-3);
    g.profile_shift = z == 20 ? 0.25 : 0.0;
    g.root_radius_m = pem::BaseRadius(g);
    pem::Options options;
    options.plane = pem::PlaneModel::kPlaneStress;
    const double e = g.youngs_modulus_pa, nu = g.poisson_ratio, b = g.face_width_m;
    const double a2 = pem::BaseHalfAngle(g);
    for (const double frac : {0.1, 0.45, 0.8, 1.0}) {
      const double r_c = pem::BaseRadius(g) + frac * (g.tip_radius_m - pem::BaseRadius(g));
      const double a1 = pem::RollAtRadius(g, r_c) - a2;
      const double ca1 = std::cos(a1), sa1 = std::sin(a1);
      const auto tian = [&](double a) {
        const double w = (a2 - a) * std::cos(a), d = std::sin(a) + (a2 - a) * std::cos(a);
        const double m = 1.0 + ca1 * ((a2 - a) * std::sin(a) - std::cos(a));
        return std::array<double, 3>{3.0 * m * m * w / (2.0 * e * b * d * d * d),
                                     1.2 * (1.0 + nu) * w * ca1 * ca1 / (e * b * d),
                                     w * sa1 * sa1 / (2.0 * e * b * d)};
      };
      const auto ref = pem::IntegrateAdaptive<3>(tian, -a1, a2, 1e-12);
      const pem::ToothCompliance c = pem::ToothComplianceAt(g, r_c, b, options);
      INFO("z = " << z << ", r_c = " << r_c);
      CHECK(c.load_angle_rad == Approx(a1).epsilon(1e-12));
      CHECK(c.bending_m_per_n == Approx(ref[0]).epsilon(1e-8));
      CHECK(c.shear_m_per_n == Approx(ref[1]).epsilon(1e-8));
      CHECK(c.compression_m_per_n == Approx(ref[2]).epsilon(1e-8));
    }
  }
}

TEST_CASE("PEM: Sainsot's fillet-foundation polynomials", "[reference][pem]") {
  // Table 1 of Sainsot, Velex & Duverger (2004) evaluated outside this code (Python, from the
  // table as reprinted by Chaari et al. 2009) at h_fi = 2, θ_f = 0.15: a transcription check. The
  // values lie inside the span of Sainsot's fitted bodies (L* 6.82–6.94, M* 1.08–3.29,
  // P* 2.56–13.47, Q* 0.141–0.62, as the ROSS code checks them).
  const auto x = pem::SainsotCoefficients(2.0, 0.15);
  CHECK(x[0] == Approx(6.876960933333334).epsilon(1e-13));
  CHECK(x[1] == Approx(1.195104).epsilon(1e-13));
  CHECK(x[2] == Approx(2.577359733333333).epsilon(1e-13));
  CHECK(x[3] == Approx(0.47633431111111113).epsilon(1e-13));
  // The fillet term of a tooth is cos²β/(E b)[…] with u_f = r_b/cos β − r_f: the load line's
  // crossing of the centre line, found here by intersecting the line with x = 0 directly.
  const pem::Gear g = IsoGear(20, 4e-3);
  const double r_c = 0.5 * (pem::BaseRadius(g) + g.tip_radius_m);
  const pem::ToothCompliance c = pem::ToothComplianceAt(g, r_c, g.face_width_m);
  const pem::FlankPoint p = pem::FlankAtRoll(g, pem::RollAtRadius(g, r_c));
  const double crossing = p.y_m - p.half_thickness_m * std::tan(p.load_angle_rad);
  CHECK(c.fillet_u_m == Approx(crossing - g.root_radius_m).epsilon(1e-12));
  // θ_f of the ISO rack (ρ = 0.38 m, h_fP = 1.25 m), z = 20: (π/4 + 0.87 tan 20° + 0.38/cos
  // 20°)/10.
  CHECK(pem::RootHalfAngle(g) ==
        Approx((std::numbers::pi / 4 + 0.87 * std::tan(20 * kDeg) + 0.38 / std::cos(20 * kDeg)) /
               10.0)
            .epsilon(1e-12));
}

TEST_CASE("PEM: mesh cycle bookkeeping", "[reference][pem]") {
  const pem::GearPair pair = IsoPair(20, 40, 4e-3);
  const pem::MeshGeometry m = pem::Geometry(pair);
  CHECK(m.contact_ratio ==
        Approx(TransverseContactRatio(20, 40, 4e-3, 20 * kDeg, pair.gear1.tip_radius_m,
                                      pair.gear2.tip_radius_m, pair.centre_distance_m))
            .epsilon(1e-12));
  CHECK(m.operating_pressure_angle_rad == Approx(20 * kDeg).epsilon(1e-12));
  const int n = 400;
  const pem::MeshCurve curve = pem::MeshStiffnessCurve(pair, n);
  int double_contact = 0;
  for (const pem::MeshSample& s : curve.samples) {
    double share = 0.0;
    for (double l : s.load_share) share += l;
    CHECK(share == Approx(1.0).epsilon(1e-14));
    CHECK((s.pair_position_m.size() == 1 || s.pair_position_m.size() == 2));
    if (s.pair_position_m.size() == 2) ++double_contact;
  }
  // Two pairs carry the load for (ε_α − 1) of the cycle.
  CHECK(static_cast<double>(double_contact) / n == Approx(m.contact_ratio - 1.0).margin(1.5 / n));
  // The sampled mean tends to the exact (integrated) mean, at O(1/n) for the jumps.
  CHECK(curve.sampled_mean_n_per_m ==
        Approx(pem::MeanMeshStiffness(pair))
            .epsilon(0.5 * (curve.max_n_per_m / curve.min_n_per_m) / n));
}

TEST_CASE("PEM: mean mesh stiffness of ISO basic-rack pairs against ISO 6336-1 c_gamma_alpha",
          "[reference][pem]") {
  // α = 20°, x = 0, m = 4 mm, b = 20 mm, E = 206 GPa, ν = 0.3, h_a = 1.0 m, h_f = 1.25 m,
  // r_f = r − 1.25 m, bore r_int = 0.5 r_f (h_fi = 2), plane strain, ISO 53 A fillet (ρ = 0.38 m).
  struct Case {
    int z1, z2;
  };
  for (const Case k : {Case{20, 40}, Case{30, 30}}) {
    const double m = 4e-3;
    const pem::GearPair pair = IsoPair(k.z1, k.z2, m);
    const double eps = TransverseContactRatio(k.z1, k.z2, m, 20 * kDeg, pair.gear1.tip_radius_m,
                                              pair.gear2.tip_radius_m, pair.centre_distance_m);
    const Iso iso = IsoMethodB(k.z1, k.z2, 0.0, 0.0, 20.0, 1.25, eps);
    const pem::MeshStiffnessSummary s = pem::Summarise(pair);
    const pem::MeshCurve curve = pem::MeshStiffnessCurve(pair, 200);
    std::printf(
        "PEM %d/%d: eps_alpha %.4f | mean mesh %.3f N/(mm um) (sampled %.3f, min %.3f, max %.3f) "
        "vs ISO c_gamma_alpha %.3f: ratio %.3f | peak single pair %.3f (at s = %.3f mm, %s) vs ISO "
        "c' %.3f: ratio %.3f [C_B %.3f, q' %.5f]\n",
        k.z1, k.z2, eps, s.mean_per_width, pem::PerUnitWidth(curve.sampled_mean_n_per_m, 0.02),
        pem::PerUnitWidth(curve.min_n_per_m, 0.02), pem::PerUnitWidth(curve.max_n_per_m, 0.02),
        iso.c_gamma_alpha, s.mean_per_width / iso.c_gamma_alpha, s.peak_single_pair_per_width,
        s.peak.position_m * 1e3,
        s.peak.in_single_contact_zone ? "in the single-contact zone" : "outside the single zone",
        iso.c_prime, s.peak_single_pair_per_width / iso.c_prime, iso.basic_rack_factor,
        iso.q_prime);
    // Breakdown at the pitch point, for the record.
    const pem::MeshGeometry g = pem::Geometry(pair);
    const pem::PairCompliance c =
        pem::SinglePairCompliance(pair, pem::BaseRadius(pair.gear1) * std::tan(20 * kDeg));
    const double w = 0.02 * 1e9;  // compliance × b·1e9 → mm·µm/N
    std::printf(
        "    pitch point compliance [mm um/N]: hertz %.5f | gear1 b %.5f s %.5f a %.5f f %.5f | "
        "gear2 b %.5f s %.5f a %.5f f %.5f | total %.5f (path %.3f..%.3f mm)\n",
        c.hertz_m_per_n * w, c.tooth1.bending_m_per_n * w, c.tooth1.shear_m_per_n * w,
        c.tooth1.compression_m_per_n * w, c.tooth1.foundation_m_per_n * w,
        c.tooth2.bending_m_per_n * w, c.tooth2.shear_m_per_n * w, c.tooth2.compression_m_per_n * w,
        c.tooth2.foundation_m_per_n * w, c.Total() * w, g.path_start_m * 1e3, g.path_end_m * 1e3);
    CHECK(s.mean_per_width == Approx(iso.c_gamma_alpha).epsilon(0.20));
  }
}

TEST_CASE("PEM: a shifted 25 deg pair at its operating centre distance", "[reference][pem]") {
  // The paper's sun-planet mesh (scenes/paper_stage.toml): m = 4.23 mm, α = 25°, z = 16/24,
  // x = 0.30/0.227, tips r + (x + 1.0) m, roots r + (x − 1.35) m (rack tip radius 0.05 m), hub
  // radius 20 mm, b = 25 mm, E = 207 GPa. The centre distance comes from the involute-function
  // relation inv α_w = inv α + 2 tan α (x1 + x2)/(z1 + z2) (docs/model.md §8), solved here by Newton;
  // pem:: must recover α_w from a and the base radii.
  const double m = 4.23e-3, alpha = 25.0 * kDeg;
  const auto make = [&](int z, double x) {
    pem::Gear g;
    g.teeth = z;
    g.module_m = m;
    g.pressure_angle_rad = alpha;
    g.profile_shift = x;
    const double r = 0.5 * z * m;
    g.tip_radius_m = r + (x + 1.0) * m;
    g.root_radius_m = r + (x - 1.35) * m;
    g.bore_radius_m = 20e-3;
    g.face_width_m = 0.025;
    g.youngs_modulus_pa = 207e9;
    g.poisson_ratio = 0.3;
    g.tool_tip_radius_coefficient = 0.05;
    return g;
  };
  pem::GearPair pair;
  pair.gear1 = make(16, 0.30);
  pair.gear2 = make(24, 0.227);
  const double inv_w = pem::Involute(alpha) + 2.0 * std::tan(alpha) * (0.30 + 0.227) / 40.0;
  double alpha_w = alpha;
  for (int i = 0; i < 60; ++i) {
    alpha_w -= (pem::Involute(alpha_w) - inv_w) / std::pow(std::tan(alpha_w), 2);
  }
  pair.centre_distance_m = 0.5 * 40 * m * std::cos(alpha) / std::cos(alpha_w);
  const pem::MeshGeometry g = pem::Geometry(pair);
  CHECK(g.operating_pressure_angle_rad == Approx(alpha_w).epsilon(1e-12));
  CHECK(g.operating_pressure_angle_rad / kDeg == Approx(27.85).margin(0.01));
  CHECK(g.contact_ratio ==
        Approx(TransverseContactRatio(16, 24, m, alpha, pair.gear1.tip_radius_m,
                                      pair.gear2.tip_radius_m, pair.centre_distance_m))
            .epsilon(1e-12));
  const pem::MeshStiffnessSummary s = pem::Summarise(pair);
  std::printf(
      "PEM 16/24 (25 deg, x 0.30/0.227, a %.4f mm, alpha_w %.3f deg): eps_alpha %.4f | mean mesh "
      "%.3f N/(mm um), peak single pair %.3f (%s); Sainsot h_fi %.2f / %.2f\n",
      pair.centre_distance_m * 1e3, g.operating_pressure_angle_rad / kDeg, g.contact_ratio,
      s.mean_per_width, s.peak_single_pair_per_width,
      s.peak.in_single_contact_zone ? "in the single-contact zone" : "outside the single zone",
      pair.gear1.root_radius_m / pair.gear1.bore_radius_m,
      pair.gear2.root_radius_m / pair.gear2.bore_radius_m);
  // The mean of a pair with 1 < ε_α < 2 lies between the single-pair peak and twice it.
  CHECK(s.mean_mesh_stiffness_n_per_m > s.peak_single_pair_stiffness_n_per_m);
  CHECK(s.mean_mesh_stiffness_n_per_m < 2.0 * s.peak_single_pair_stiffness_n_per_m);
}
