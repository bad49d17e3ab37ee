// Root stress against ISO 6336-3 method B (docs/model.md §9): the standard's root form (s_Fn,
// ρ_F at the 30° tangents) against the generated tooth, and the FE fillet stress under the full
// mesh load at the outer point of single pair contact against σ_F0 = F_t/(b m) Y_F Y_S, for both
// gears of the three ISO pairs in scenes/.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/transmission/scene.hpp"
#include "figures.hpp"

using namespace epicycle;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Case {
  const char* scene;
  int gear;  // 1 or 2
};
// Both gears of the three ISO pairs (the 30/30 pair's gears are one body).
const Case kCases[] = {{"iso_pair_17_43.toml", 1},
                       {"iso_pair_17_43.toml", 2},
                       {"iso_pair_20_40.toml", 1},
                       {"iso_pair_20_40.toml", 2},
                       {"iso_pair_30_30.toml", 1}};

geometry::iso::RootFormFactors IsoFactors(const geometry::GearPair& pair, int which) {
  const geometry::Gear& g = which == 1 ? pair.gear1() : pair.gear2();
  const geometry::GearSpec& s = g.spec();
  REQUIRE(s.rack);
  // The cutter's addendum cuts the root: it is the basic rack's dedendum h_fP; its tip radius ρ_fP.
  return geometry::iso::RootFormFactorsB(s.teeth, s.module, s.pressure_angle, s.profile_shift,
                                         s.rack->addendum, s.rack->tip_radius, 2.0 * g.tip_radius(),
                                         pair.summary().contact_ratio_iso);
}

// A case's scene, pair and the standard's factors of its gear.
struct Loaded {
  explicit Loaded(const Case& c)
      : which(c.gear),
        scene(transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/" + c.scene)),
        pair(scene.pair),
        iso(IsoFactors(pair, c.gear)) {}
  const geometry::Gear& gear() const { return which == 1 ? pair.gear1() : pair.gear2(); }
  int which;
  transmission::Scene scene;
  geometry::GearPair pair;
  geometry::iso::RootFormFactors iso;
};

// Arc length [m] along the profile path where the σ = +1 fillet's tangent makes 30° with the
// tooth centre line (the x axis), by bisection between the space centre line and the form point.
double ThirtyDegreeTangent(const compliance::ProfilePath& path, double s_form) {
  auto excess = [&](double s) {
    const Eigen::Vector2d t = path.Tangent(s);
    return std::atan2(std::abs(t.y()), std::abs(t.x())) - kPi / 6;  // angle to the x axis − 30°
  };
  double lo = 0.0, hi = s_form;
  REQUIRE(excess(lo) * excess(hi) < 0);
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (excess(lo) * excess(mid) <= 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("ISO 6336-3 root form against the generated tooth", "[reference][geometry][stress]") {
  // The standard's s_Fn and ρ_F come from the rack's trochoid in closed form; the generated
  // profile is the envelope of the same rack: they must agree but for the bisection's and the
  // curvature's central difference (O(ds²), ds = 1e-4 m): held to 1e-6 of the module on s_Fn
  // and 1e-3 relative on ρ_F.
  for (const Case& c : kCases) {
    const Loaded d(c);
    const geometry::Gear& gear = d.gear();
    const geometry::iso::RootFormFactors& iso = d.iso;
    const compliance::ProfilePath path(gear);
    const double s_form = compliance::MakeFlankGrid(gear).form_arc;
    const double s = ThirtyDegreeTangent(path, s_form);
    const double s_fn = 2.0 * path.Point(s).y();
    const double ds = 1e-4 * gear.module();
    const Eigen::Vector2d t0 = path.Tangent(s - ds), t1 = path.Tangent(s + ds);
    const double curvature = std::abs(t0.x() * t1.y() - t0.y() * t1.x()) / (2 * ds);
    INFO(c.scene << " gear " << c.gear << ": s_Fn ISO " << iso.s_fn * 1e3 << " mm, generated "
                 << s_fn * 1e3 << " mm; rho_F ISO " << iso.rho_f * 1e3 << " mm, generated "
                 << 1e3 / curvature << " mm");
    const double e_s = std::abs(s_fn - iso.s_fn), e_rho = std::abs(1.0 / curvature - iso.rho_f);
    CHECK(e_s <= 1e-6 * gear.module());
    CHECK(e_rho <= 1e-3 * iso.rho_f);
    const std::string what = std::string(c.scene) + " gear " + std::to_string(c.gear);
    test::VerifyRow("root chord s_Fn at the 30 deg tangents, " + what,
                    "ISO 6336-3 method B " + test::Sci(iso.s_fn) + " m", test::Sci(s_fn) + " m",
                    test::Sci(e_s) + " m", "1e-6 m_n", e_s <= 1e-6 * gear.module());
    test::VerifyRow("fillet radius rho_F at the 30 deg tangents, " + what,
                    "ISO 6336-3 method B " + test::Sci(iso.rho_f) + " m",
                    test::Sci(1.0 / curvature) + " m", test::Sci(e_rho / iso.rho_f) + " relative",
                    "1e-3", e_rho <= 1e-3 * iso.rho_f);
  }
}

TEST_CASE("root stress at the outer point of single contact against ISO 6336-3 method B",
          "[reference][compliance][stress]") {
  // The full normal mesh force F_n = T_1/r_b1 (= F_t/cos α) on tooth 0's σ = +1 flank at the
  // outer point of single pair contact d_en of the gear considered, along the line of action (the
  // flank normal); the model's root stress is the largest σ_tt on that side's fillet. ISO's
  // σ_F0 = F_t/(b m) Y_F Y_S (Y_β = Y_B = Y_DT = 1) is an approximation of the same quantity: the
  // standard expects about ±20 %.
  for (const Case& c : kCases) {
    const Loaded d(c);
    const geometry::Gear& gear = d.gear();
    const geometry::iso::RootFormFactors& iso = d.iso;
    const double torque1 = std::abs(d.scene.pair_torque);
    const double f_n = torque1 / d.pair.gear1().base_radius();
    const double f_t = f_n * std::cos(gear.spec().pressure_angle);  // at the reference circle
    const double b = gear.spec().face_width, m = gear.module();
    const double sigma_iso = f_t / (b * m) * iso.y_f * iso.y_s;

    compliance::InfluenceTableOptions options;
    options.fillet_stress = true;
    const compliance::InfluenceTable table = compliance::InfluenceTable::Build(
        gear,
        compliance::ElasticMaterial{d.scene.material.youngs_modulus, d.scene.material.poisson_ratio,
                                    b, compliance::PlaneAssumption::kPlaneStrain},
        options);
    // The flank position at radius d_en/2 (bisection on the involute's radius, which rises).
    const compliance::ProfilePath path(gear);
    const double s0 = table.grid().form_arc;
    double lo = 0.0, hi = table.arc_length_max();
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      (path.Point(s0 + mid).norm() < iso.d_en / 2 ? lo : hi) = mid;
    }
    const double s = 0.5 * (lo + hi);
    const auto load = table.PrepareDirected({0, 1, s}, -path.Normal(s0 + s));
    std::vector<double> tension(table.fillet_points().size(), 0.0), compression = tension;
    table.AddFilletStress(load, f_n, 0, 0, tension.data());
    table.AddFilletStress(load, f_n, 0, 1, compression.data());
    const double sigma_fe = *std::max_element(tension.begin(), tension.end());
    const double difference = sigma_fe / sigma_iso - 1.0;
    WARN(c.scene << " gear " << c.gear << " (z = " << gear.teeth() << "): Y_F " << iso.y_f
                 << ", Y_S " << iso.y_s << ", d_en " << iso.d_en * 1e3 << " mm; sigma_F0 ISO "
                 << sigma_iso / 1e6 << " MPa, model " << sigma_fe / 1e6 << " MPa ("
                 << (difference >= 0 ? "+" : "") << difference * 100 << " %), compression side "
                 << *std::min_element(compression.begin(), compression.end()) / 1e6 << " MPa");
    CHECK(std::abs(difference) <= 0.20);
    test::VerifyRow(std::string("root stress at the outer point of single contact, ") + c.scene +
                        " gear " + std::to_string(c.gear),
                    "ISO 6336-3 method B sigma_F0 " + test::Sci(sigma_iso / 1e6) + " MPa",
                    test::Sci(sigma_fe / 1e6) + " MPa",
                    test::Sci(100 * difference, 2) + " % (signed)",
                    "+-20 % (the standard's approximation)", std::abs(difference) <= 0.20);
  }
}
