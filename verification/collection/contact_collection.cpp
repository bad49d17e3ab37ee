// The contact problem collection. Magnitudes of the gear-like cases follow the paper's stage
// (module 4.23 mm, 25°, z 16/24, b = 25 mm, steel, −600 N·m on the sun).
#include "contact_collection.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include <Eigen/QR>

namespace epicycle::solvers {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Platform-independent uniform and normal numbers (the std distributions are not).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  double Uniform(double lo = 0.0, double hi = 1.0) {
    const double u = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * u;
  }
  double Normal() {
    const double u1 = 1.0 - Uniform(), u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }

 private:
  std::mt19937_64 engine_;
};

LocalTermParameters SteelLocal(double r_eq, double h1, double h2) {
  LocalTermParameters p;
  p.face_width = 0.025;
  p.reduced_radius = r_eq;
  p.body[0] = {207e9, 0.3, h1};
  p.body[1] = {207e9, 0.3, h2};
  return p;
}

Eigen::MatrixXd RandomSpd(Rng& rng, int n, double scale, double min_eig) {
  Eigen::MatrixXd a(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) a(i, j) = rng.Normal();
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
  Eigen::VectorXd eig(n);
  for (int i = 0; i < n; ++i)  // log-spaced from min_eig to 1, shuffled by Q
    eig(i) = n == 1 ? 1.0 : std::pow(min_eig, static_cast<double>(i) / (n - 1));
  Eigen::MatrixXd c = scale * q * eig.asDiagonal() * q.transpose();
  return 0.5 * (c + c.transpose());
}

std::string SeedName(const std::string& base, std::uint64_t seed) {
  return base + "_s" + std::to_string(seed);
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Solve c F + u(F) = d for F ≥ 0 by bisection (u increasing): the closed-form cases' reference.
double SolveScalar(double c, const LocalTermParameters& p, double d) {
  if (d <= 0.0) return 0.0;
  double lo = 0.0, hi = d / c;
  for (int it = 0; it < 400 && hi - lo > 0.0; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (c * mid + LocalApproach(p, mid) > d ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<ContactProblemFile> ClosedFormCases() {
  std::vector<ContactProblemFile> out;
  const LocalTermParameters loc = SteelLocal(0.010, 2e-3, 2e-3);
  {
    ContactProblemFile f;
    f.category = "closed-form";
    f.data.name = "cf_one_contact_overlap";
    f.description = "one contact with a local term, no equality: c F + u(F) = delta0";
    f.data.compliance = Eigen::MatrixXd::Constant(1, 1, 4e-9);
    f.data.overlap = Eigen::VectorXd::Constant(1, 30e-6);
    f.data.local = {loc};
    ContactSolution s;
    s.force = Eigen::VectorXd::Constant(1, SolveScalar(4e-9, loc, 30e-6));
    s.multiplier.resize(0);
    f.expected = s;
    f.expected_note = "bisection on c F + u(F) = delta0";
    out.push_back(f);
  }
  {
    ContactProblemFile f;
    f.category = "closed-form";
    f.data.name = "cf_one_contact_load";
    f.description =
        "one contact with a local term carrying a given load: F = W, lambda = cW + u(W) - delta0";
    f.data.compliance = Eigen::MatrixXd::Constant(1, 1, 4e-9);
    f.data.overlap = Eigen::VectorXd::Constant(1, -5e-6);
    f.data.local = {loc};
    f.data.equality_matrix = Eigen::MatrixXd::Constant(1, 1, 1.0);
    f.data.equality_rhs = Eigen::VectorXd::Constant(1, 5000.0);
    ContactSolution s;
    s.force = Eigen::VectorXd::Constant(1, 5000.0);
    s.multiplier = Eigen::VectorXd::Constant(1, 4e-9 * 5000.0 + LocalApproach(loc, 5000.0) + 5e-6);
    f.expected = s;
    f.expected_note = "F = W, lambda = c W + u(W) - delta0";
    out.push_back(f);
  }
  {
    ContactProblemFile f;
    f.category = "closed-form";
    f.data.name = "cf_one_contact_open";
    f.description = "one contact with a gap and no load: F = 0";
    f.data.compliance = Eigen::MatrixXd::Constant(1, 1, 4e-9);
    f.data.overlap = Eigen::VectorXd::Constant(1, -10e-6);
    f.data.local = {loc};
    ContactSolution s;
    s.force = Eigen::VectorXd::Zero(1);
    f.expected = s;
    f.expected_note = "gap, no load";
    out.push_back(f);
  }
  {
    ContactProblemFile f;
    f.category = "closed-form";
    f.data.name = "cf_two_symmetric";
    f.description = "two symmetric coupled contacts with local terms sharing a load 2P: F = P each";
    f.data.compliance.resize(2, 2);
    f.data.compliance << 4e-9, 1e-9, 1e-9, 4e-9;
    f.data.overlap = Eigen::VectorXd::Constant(2, 3e-6);
    f.data.local = {loc, loc};
    f.data.equality_matrix = Eigen::MatrixXd::Constant(1, 2, 1.0);
    f.data.equality_rhs = Eigen::VectorXd::Constant(1, 8000.0);
    ContactSolution s;
    s.force = Eigen::VectorXd::Constant(2, 4000.0);
    s.multiplier = Eigen::VectorXd::Constant(1, 5e-9 * 4000.0 + LocalApproach(loc, 4000.0) - 3e-6);
    f.expected = s;
    f.expected_note = "symmetry: F = P, lambda = (c11 + c12) P + u(P) - delta0";
    out.push_back(f);
  }
  {
    ContactProblemFile f;
    f.category = "closed-form";
    f.data.name = "cf_two_symmetric_overlap";
    f.description =
        "two symmetric coupled contacts with local terms pressed by an overlap, no equality";
    f.data.compliance.resize(2, 2);
    f.data.compliance << 4e-9, 1e-9, 1e-9, 4e-9;
    f.data.overlap = Eigen::VectorXd::Constant(2, 25e-6);
    f.data.local = {loc, loc};
    ContactSolution s;
    s.force = Eigen::VectorXd::Constant(2, SolveScalar(5e-9, loc, 25e-6));
    f.expected = s;
    f.expected_note = "symmetry: (c11 + c12) F + u(F) = delta0 by bisection";
    out.push_back(f);
  }
  {
    // Three parallel springs under a rigid bar loaded by a force P and a moment M; the third is
    // held open by a large gap, so statics alone gives F1, F2 and the gaps give lambda.
    ContactProblemFile f;
    f.category = "closed-form";
    f.data.name = "cf_linear_springs";
    f.description = "three linear springs under a rigid bar (force and moment), one held open";
    const double c[3] = {2e-9, 3e-9, 5e-9}, r[3] = {-0.05, 0.04, 0.1};
    const double d0[3] = {1e-6, -2e-6, -1e-3}, p = 1e4, mom = 100.0;
    f.data.compliance = Eigen::Vector3d(c[0], c[1], c[2]).asDiagonal();
    f.data.overlap = Eigen::Vector3d(d0[0], d0[1], d0[2]);
    f.data.equality_matrix.resize(2, 3);
    f.data.equality_matrix << 1, 1, 1, r[0], r[1], r[2];
    f.data.equality_rhs = Eigen::Vector2d(p, mom);
    const double f1 = (mom - r[1] * p) / (r[0] - r[1]), f2 = p - f1;
    // c_j F_j − δ0_j = λ1 + r_j λ2 for j = 1, 2.
    const double a1 = c[0] * f1 - d0[0], a2 = c[1] * f2 - d0[1];
    const double l2 = (a1 - a2) / (r[0] - r[1]), l1 = a1 - r[0] * l2;
    ContactSolution s;
    s.force = Eigen::Vector3d(f1, f2, 0.0);
    s.multiplier = Eigen::Vector2d(l1, l2);
    f.expected = s;
    f.expected_note =
        "statics F1 = (M - r2 P)/(r1 - r2), F2 = P - F1, F3 = 0; lambda from the two closed gaps";
    out.push_back(f);
  }
  {
    ContactProblemFile f;
    f.category = "closed-form";
    f.data.name = "cf_elastic_support";
    f.description =
        "one linear contact on an elastic support of stiffness K: F + K lambda = W, lambda = c F - "
        "delta0, so F = (W + K delta0)/(1 + K c)";
    const double c = 4e-9, s = 5e8, d0 = 10e-6, w = 3000.0;
    f.data.compliance = Eigen::MatrixXd::Constant(1, 1, c);
    f.data.overlap = Eigen::VectorXd::Constant(1, d0);
    f.data.equality_matrix = Eigen::MatrixXd::Constant(1, 1, 1.0);
    f.data.equality_rhs = Eigen::VectorXd::Constant(1, w);
    f.data.support_stiffness = Eigen::MatrixXd::Constant(1, 1, s);
    const double force = (w + s * d0) / (1.0 + s * c);
    ContactSolution sol;
    sol.force = Eigen::VectorXd::Constant(1, force);
    sol.multiplier = Eigen::VectorXd::Constant(1, c * force - d0);
    f.expected = sol;
    f.expected_note = "F + s lambda = W with lambda = c F - delta0";
    out.push_back(f);
  }
  return out;
}

ContactProblemFile RandomCase(std::uint64_t seed, int n, int m, bool local, bool support,
                              double min_eig, const std::string& base) {
  Rng rng(seed * 7919 + static_cast<std::uint64_t>(n * 31 + m));
  ContactProblemFile f;
  f.category = "random";
  f.seed = seed;
  f.data.name = SeedName(base, seed);
  f.description = "random SPD C (eigenvalues log-spaced down to " + std::to_string(min_eig) +
                  " x 5e-9 m/N), N = " + std::to_string(n) + ", m = " + std::to_string(m) +
                  (local ? ", local terms" : "") + (support ? ", elastic supports" : "");
  f.data.compliance = RandomSpd(rng, n, 5e-9, min_eig);
  f.data.overlap.resize(n);
  for (int j = 0; j < n; ++j) f.data.overlap(j) = rng.Uniform(-20e-6, 20e-6);
  if (local)
    for (int j = 0; j < n; ++j)
      f.data.local.push_back(
          SteelLocal(rng.Uniform(6e-3, 14e-3), rng.Uniform(1e-3, 3e-3), rng.Uniform(1e-3, 3e-3)));
  if (m > 0) {
    f.data.equality_matrix.resize(m, n);
    for (int j = 0; j < n; ++j) {
      f.data.equality_matrix(0, j) = 1.0;  // a force row
      for (int i = 1; i < m; ++i)
        f.data.equality_matrix(i, j) = rng.Uniform(-0.06, 0.06);  // moments
    }
    Eigen::VectorXd nominal(n);
    for (int j = 0; j < n; ++j) nominal(j) = rng.Uniform(0.0, 2000.0);
    f.data.equality_rhs = f.data.equality_matrix * nominal;
    if (support) {
      f.data.support_stiffness = Eigen::MatrixXd::Zero(m, m);
      f.data.support_stiffness(0, 0) = 1e-9;  // row 0 on a bearing, the others hard
    }
  }
  return f;
}

}  // namespace

ContactProblemFile MakeGearLikeProblem(const GearLikeSpec& spec, const std::string& name) {
  if (spec.planets < 1 || spec.drive_pairs < 1 || spec.coast_pairs < 0)
    throw std::invalid_argument(
        "GearLikeSpec: planets and drive_pairs must be >= 1, coast_pairs >= 0");
  Rng rng(spec.seed);
  const double alpha = 25.0 * kPi / 180.0, module = 4.23e-3;
  const double r_s = module * 16 / 2, r_p = module * 24 / 2, r_c = r_s + r_p;
  const double p_b = kPi * module * std::cos(alpha);
  const int per_mesh = spec.drive_pairs + spec.coast_pairs;
  const int n = spec.planets * 2 * per_mesh;
  const int m = 3 + spec.planets;  // sun θ, sun x, sun y, planet θ_i

  ContactProblemFile f;
  f.category = "gear-like";
  f.seed = spec.seed;
  f.data.name = name;
  f.description =
      "gear-like stage: " + std::to_string(spec.planets) + " planets, " + std::to_string(per_mesh) +
      " candidate pairs per mesh (" + std::to_string(spec.drive_pairs) + " drive), sun torque " +
      std::to_string(spec.sun_torque) + " N m, run-out " + std::to_string(spec.runout * 1e6) +
      " um on planet 1" + (spec.local ? ", local terms" : "");
  ContactProblemData& d = f.data;
  d.equality_matrix = Eigen::MatrixXd::Zero(m, n);
  d.overlap.resize(n);
  d.multiplier_labels = {"sun rotation [rad]", "sun x [m]", "sun y [m]"};
  for (int i = 0; i < spec.planets; ++i)
    d.multiplier_labels.push_back("planet " + std::to_string(i + 1) + " rotation [rad]");

  std::vector<int> mesh_of(n), body_planet(n), is_sun(n), is_drive(n);
  std::vector<double> position(n);
  Eigen::VectorXd nominal = Eigen::VectorXd::Zero(n);
  int j = 0;
  for (int i = 0; i < spec.planets; ++i) {
    const double psi = 2.0 * kPi * i / spec.planets;
    const Eigen::Vector2d e(std::cos(psi), std::sin(psi)), t(-std::sin(psi), std::cos(psi));
    const Eigen::Vector2d centre = r_c * e;
    for (int member = 0; member < 2; ++member) {  // 0 sun mesh, 1 ring mesh
      for (int k = 0; k < per_mesh; ++k, ++j) {
        const bool drive = k < spec.drive_pairs;
        const int kk = drive ? k : k - spec.drive_pairs;
        const int count = drive ? spec.drive_pairs : spec.coast_pairs;
        const double s = (kk - 0.5 * (count - 1)) * p_b;
        const double side = drive ? 1.0 : -1.0;
        mesh_of[j] = 2 * (2 * i + member) + (drive ? 0 : 1);
        body_planet[j] = i;
        is_sun[j] = member == 0;
        is_drive[j] = drive;
        position[j] = s;
        if (member == 0) {
          const Eigen::Vector2d nn = side * std::cos(alpha) * t + std::sin(alpha) * e;  // on planet
          const Eigen::Vector2d c = r_s * e + s * nn;
          d.equality_matrix(0, j) = Cross(c, nn);
          d.equality_matrix(1, j) = nn.x();
          d.equality_matrix(2, j) = nn.y();
          d.equality_matrix(3 + i, j) = -Cross(c - centre, nn);
        } else {
          const Eigen::Vector2d on_planet = side * std::cos(alpha) * t - std::sin(alpha) * e;
          const Eigen::Vector2d nn = -on_planet;  // on the ring
          const Eigen::Vector2d c = centre + r_p * e + s * nn;
          d.equality_matrix(3 + i, j) = Cross(c - centre, nn);
        }
        // Overlaps: tip-relief-like gaps growing away from the pitch point, scatter, run-out of
        // planet 1 on its drive flanks; coast flanks held open by the backlash.
        double d0 = drive ? -15e-6 * std::abs(s) / p_b + spec.scatter * rng.Uniform(-1.0, 1.0)
                          : -100e-6 - rng.Uniform(0.0, 20e-6);
        if (i == 0 && drive) d0 += 0.5 * spec.runout;
        d.overlap(j) = d0;
        if (drive)
          nominal(j) = spec.sun_torque / (spec.planets * r_s * std::cos(alpha) * spec.drive_pairs);
        d.contact_labels.push_back("planet" + std::to_string(i + 1) +
                                   (member == 0 ? " sun" : " ring") + " mesh " +
                                   (drive ? "drive" : "coast") + " pair " + std::to_string(kk + 1));
        if (spec.local)
          d.local.push_back(SteelLocal(rng.Uniform(8e-3, 12e-3), rng.Uniform(1e-3, 3e-3),
                                       rng.Uniform(1e-3, 3e-3)));
      }
    }
  }
  // Compliance: per flank an exponential kernel along the line of action (tooth and rim
  // coupling of neighbouring pairs), per planet body and for the sun body a uniform positive
  // coupling: sums of positive semidefinite kernels plus a positive diagonal, hence SPD.
  const double c_pair = 4e-9, c_planet = 0.3e-9, c_sun = 0.1e-9, ell = 0.6 * p_b;
  d.compliance = Eigen::MatrixXd::Zero(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      double v = 0.0;
      if (mesh_of[a] == mesh_of[b])
        v += c_pair * std::exp(-std::abs(position[a] - position[b]) / ell);
      if (body_planet[a] == body_planet[b]) v += c_planet;
      if (is_sun[a] && is_sun[b]) v += c_sun;
      d.compliance(a, b) = v;
    }
  d.equality_rhs = d.equality_matrix * nominal;
  for (int i = 1; i < m; ++i)  // sums that vanish by symmetry: exact zeros, not round-off
    if (std::abs(d.equality_rhs(i)) < 1e-9 * std::abs(spec.sun_torque) / r_s)
      d.equality_rhs(i) = 0.0;
  if (spec.support_stiffness > 0.0) {
    d.support_stiffness = Eigen::MatrixXd::Zero(m, m);
    d.support_stiffness(1, 1) = d.support_stiffness(2, 2) = spec.support_stiffness;
  }
  return f;
}

std::vector<ContactProblemFile> GenerateContactCollection(std::uint64_t seed) {
  std::vector<ContactProblemFile> out = ClosedFormCases();
  for (std::uint64_t s = seed; s < seed + 3; ++s) {
    out.push_back(RandomCase(s, 10, 0, false, false, 1e-2, "rand_n10"));
    out.push_back(RandomCase(s, 20, 2, false, false, 1e-2, "rand_n20_m2"));
    out.push_back(RandomCase(s, 40, 0, true, false, 1e-2, "rand_n40_local"));
    out.push_back(RandomCase(s, 30, 3, true, true, 1e-2, "rand_n30_m3_local_support"));
  }
  struct G {
    int planets, drive, coast;
    double support;
    const char* name;
  };
  for (const G& g :
       {G{3, 3, 2, 0.0, "gear_p3_n30_m6"}, G{4, 3, 2, 0.0, "gear_p4_n40_m7"},
        G{5, 3, 3, 0.0, "gear_p5_n60_m8"}, G{3, 4, 3, 5e8, "gear_p3_n42_m6_bearing"}}) {
    GearLikeSpec spec;
    spec.planets = g.planets;
    spec.drive_pairs = g.drive;
    spec.coast_pairs = g.coast;
    spec.support_stiffness = g.support;
    spec.seed = seed;
    out.push_back(MakeGearLikeProblem(spec, SeedName(g.name, seed)));
  }
  {
    GearLikeSpec spec;
    spec.local = false;
    spec.seed = seed + 1;
    out.push_back(MakeGearLikeProblem(spec, SeedName("gear_p3_n30_m6_linear", seed + 1)));
  }

  // Stiff and extreme cases.
  auto stiff = [&](ContactProblemFile f, const std::string& name, const std::string& what) {
    f.category = "stiff";
    f.data.name = name;
    f.description = what + "; " + f.description;
    out.push_back(f);
  };
  {
    GearLikeSpec spec;
    spec.sun_torque = 2e5;
    spec.seed = seed;
    stiff(MakeGearLikeProblem(spec, ""), SeedName("stiff_high_load", seed),
          "load so high that the Hertz half-width passes the depth h (L > h)");
  }
  {
    GearLikeSpec spec;
    spec.sun_torque = 1e-6;
    spec.runout = 0.0;
    spec.scatter = 0.0;
    spec.seed = seed;
    stiff(MakeGearLikeProblem(spec, ""), SeedName("stiff_near_zero_load", seed),
          "sun torque 1e-6 N m: forces where u' is largest");
  }
  {
    ContactProblemFile f = RandomCase(seed, 30, 0, true, false, 1e-2, "x");
    f.data.overlap.setConstant(-20e-6);
    f.data.overlap(7) = 5e-6;
    stiff(f, SeedName("stiff_one_active", seed), "all but one contact opening (gaps 20 um)");
  }
  {
    ContactProblemFile f = RandomCase(seed, 30, 1, true, false, 1e-2, "x");
    f.data.equality_matrix.setOnes();
    f.data.equality_rhs.setConstant(1, 500.0);
    f.data.overlap.setConstant(-50e-6);
    f.data.overlap(11) = 0.0;
    stiff(f, SeedName("stiff_one_active_load", seed),
          "a load carried by one contact, the others open");
  }
  {
    ContactProblemFile f = RandomCase(seed, 20, 0, false, false, 1e-10, "x");
    stiff(f, SeedName("stiff_cond1e10", seed), "C with condition number 1e10");
  }
  {
    ContactProblemFile f = RandomCase(seed + 1, 20, 2, true, false, 1e-10, "x");
    stiff(f, SeedName("stiff_cond1e10_m2_local", seed + 1),
          "C with condition number 1e10 (before the local terms), two equalities");
  }
  // Redundant equalities: an extra row equal to the sun-torque row (exactly: λ is not unique,
  // the forces and Gᵀλ are), or up to a relative perturbation of 1e-6 per entry (a genuine but
  // nearly dependent constraint: large, ill-determined multipliers). The right-hand side is
  // consistent: the same nominal forces as the other rows.
  for (double eps : {0.0, 1e-6}) {
    GearLikeSpec spec;
    spec.seed = seed;
    ContactProblemFile f = MakeGearLikeProblem(spec, "");
    ContactProblemData& d = f.data;
    const Eigen::Index m = d.equality_rhs.size();
    d.equality_matrix.conservativeResize(m + 1, Eigen::NoChange);
    Rng rng(seed + 99);
    for (Eigen::Index jj = 0; jj < d.equality_matrix.cols(); ++jj)
      d.equality_matrix(m, jj) = d.equality_matrix(0, jj) * (1.0 + eps * rng.Uniform(-1.0, 1.0));
    Eigen::VectorXd nominal = Eigen::VectorXd::Zero(d.overlap.size());
    const double alpha = 25.0 * kPi / 180.0, r_bs = 4.23e-3 * 8 * std::cos(alpha);
    for (Eigen::Index jj = 0; jj < nominal.size(); ++jj)
      if (d.contact_labels[jj].find("drive") != std::string::npos)
        nominal(jj) = spec.sun_torque / (3 * r_bs * 3);
    d.equality_rhs.conservativeResize(m + 1);
    d.equality_rhs(m) = eps == 0.0 ? d.equality_rhs(0) : d.equality_matrix.row(m).dot(nominal);
    d.multiplier_labels.push_back("copy of the sun row [rad]");
    if (eps == 0.0)
      stiff(f, SeedName("stiff_redundant_exact", seed),
            "an extra equality identical to the sun-torque row (multipliers not unique)");
    else
      stiff(f, SeedName("stiff_nearly_redundant", seed),
            "an extra equality equal to the sun-torque row up to 1e-6 relative per entry");
  }
  {
    ContactProblemFile f = RandomCase(seed, 12, 1, false, false, 1e-3, "x");
    f.data.compliance *= 1e-3;  // ~5e-12 m/N
    f.data.overlap *= 1e-3;
    f.data.equality_rhs *= 1e3;  // ~1e7 N
    stiff(f, SeedName("stiff_raw_si", seed), "raw SI magnitudes: C ~ 5e-12 m/N, W ~ 1e7 N");
  }
  return out;
}

}  // namespace epicycle::solvers
