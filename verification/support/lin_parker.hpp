// Independent reference for the natural modes: the lumped-parameter planetary model of Lin &
// Parker (1999, "Analytical characterization of the unique properties of planetary gear free
// vibration", J. Vib. Acoust. 121(3) 316–321), carrier speed Ω = 0, written from the paper's
// coordinates and spring deflections, not from the production dynamics layer (test-only).
//
// Coordinates (Lin & Parker): sun s, ring r, carrier c: translations x_j, y_j [m] and rotation
// u_j = r_j θ_j [m] (r_j base radius of sun and ring, carrier radius r_c); planet i: radial ζ_i
// and tangential η_i translations [m] along e_r(ψ_i) = (cos ψ_i, sin ψ_i) and
// e_t(ψ_i) = (−sin ψ_i, cos ψ_i), and u_i = r_p θ_i. q = (c, r, s, p_1 .. p_N), 3 entries each.
//
// Spring deflections (ψ_si = ψ_i − α_s, ψ_ri = ψ_i + α_r):
//   sun–planet  δ_si = −x_s sin ψ_si + y_s cos ψ_si − ζ_i sin α_s − η_i cos α_s + u_s + u_i
//   ring–planet δ_ri = −x_r sin ψ_ri + y_r cos ψ_ri + ζ_i sin α_r − η_i cos α_r + u_r − u_i
//   planet bearing, radial      ζ_i − (x_c cos ψ_i + y_c sin ψ_i)
//                   tangential  η_i − (−x_c sin ψ_i + y_c cos ψ_i + u_c)
//   central bearings x_j, y_j (k_j), torsional u_j (k_ju, in N/m of u: k_θ/r_j²).
// The sun–planet line of action is the sun base circle's tangent at angle ψ_i − α_s, in the
// direction of the sun's positive rotation; it touches the planet base circle on the far side
// (r_c cos α_s = r_s + r_p), so positive u_s and u_i both compress it. The ring–planet line is
// the ring's tangent at ψ_i + α_r, touching the planet on the same side (r_c cos α_r = r_r −
// r_p), so u_r compresses and u_i relieves it. K = Σ k v vᵀ over the springs, v the gradient of
// the deflection; M = diag(m_j, m_j, I_j/r_j²).
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/dynamics/modes.hpp"

namespace epicycle::test::lin_parker {

inline constexpr double kPi = 3.14159265358979323846;

/// Parameters of Lin & Parker's model (symbols of the paper).
struct Parameters {
  int planets = 3;                            ///< N
  std::vector<double> psi;                    ///< ψ_i [rad], planet angles
  double m_s = 0, m_r = 0, m_c = 0, m_p = 0;  ///< masses [kg]
  double j_s = 0, j_r = 0, j_c = 0, j_p = 0;  ///< I_j/r_j² [kg]
  double r_s = 0, r_r = 0, r_c = 0, r_p = 0;  ///< base radii, carrier radius [m] (u = r θ)
  double k_sp = 0, k_rp = 0;                  ///< mesh stiffnesses [N/m]
  double k_s = 0, k_r = 0, k_c = 0, k_p = 0;  ///< bearing stiffnesses [N/m]
  double k_su = 0, k_ru = 0, k_cu = 0;        ///< torsional stiffnesses of u [N/m] (k_θ/r²)
  /// Mesh pressure angles [rad]. Positive: the flanks loaded when the sun drives in the
  /// positive (counter-clockwise) sense, as in the deflections above; negative values give the
  /// other flank pair (the mirror image: the stage driven clockwise, as the paper's −600 N·m).
  double alpha_s = 0, alpha_r = 0;
};

/// Equally spaced planets: ψ_i = 2π(i−1)/N.
inline std::vector<double> EqualSpacing(int planets) {
  std::vector<double> psi;
  for (int i = 0; i < planets; ++i) psi.push_back(2 * kPi * i / planets);
  return psi;
}

/// The example system of Lin & Parker (1999), Table 1: m_s = 0.4, m_r = 2.35, m_c = 5.43,
/// m_p = 0.66 kg; I/r² = 0.39, 3.00, 6.29, 0.61 kg; k_sp = k_rp = 5e8 N/m; k_s = k_r = k_c =
/// k_p = 1e8 N/m; k_ru = 1e9 N/m, k_su = k_cu = 0; α_s = α_r = 24.6°; base diameters sun 77.4 mm,
/// ring 275.0 mm, planet 100.3 mm, carrier 176.8 mm (only used to turn u into θ). The values as
/// transcribed by the public reproduction gfsReboucas/Drivetrain-python
/// (tests/test_lin_parker_1999.py, "Lin and Parker 1999 Table 1 / Lin thesis Table C.1").
inline Parameters Table1Example(int planets) {
  Parameters p;
  p.planets = planets;
  p.psi = EqualSpacing(planets);
  p.m_s = 0.4, p.m_r = 2.35, p.m_c = 5.43, p.m_p = 0.66;
  p.j_s = 0.39, p.j_r = 3.00, p.j_c = 6.29, p.j_p = 0.61;
  p.r_s = 77.4e-3 / 2, p.r_r = 275.0e-3 / 2, p.r_c = 176.8e-3 / 2, p.r_p = 100.3e-3 / 2;
  p.k_sp = p.k_rp = 5e8;
  p.k_s = p.k_r = p.k_c = p.k_p = 1e8;
  p.k_su = 0, p.k_ru = 1e9, p.k_cu = 0;
  p.alpha_s = p.alpha_r = 24.6 * kPi / 180;
  return p;
}

/// The natural frequencies [Hz] Lin & Parker (1999, Table 2) print for Table1Example(planets),
/// per class: rotational (each single; 0 is the rigid rotation allowed by k_su = k_cu = 0),
/// translational (each double), planet (each of multiplicity N − 3; none for N = 3). As
/// transcribed in the same public reproduction; one decimal printed.
struct PublishedFrequencies {
  std::vector<double> rotational, translational, planet;
};
inline PublishedFrequencies Table2Frequencies(int planets) {
  switch (planets) {
    case 3:
      return {{0.0, 1475.7, 1930.3, 2658.3, 7462.8, 11775.3},
              {743.2, 1102.4, 1896.0, 2276.4, 6986.3, 9647.9},
              {}};
    case 4:
      return {{0.0, 1536.6, 1970.6, 2625.7, 7773.6, 13071.1},
              {727.0, 1091.0, 1892.8, 2342.5, 7189.9, 10437.6},
              {1808.2, 5963.8, 6981.7}};
    case 5:
      return {{0.0, 1567.4, 2006.1, 2614.8, 8065.4, 14253.1},
              {710.0, 1072.0, 1888.1, 2425.3, 7382.4, 11172.3},
              {1808.2, 5963.8, 6981.7}};
    default:
      throw std::invalid_argument("Lin & Parker Table 2 has N = 3, 4, 5 planets, not " +
                                  std::to_string(planets));
  }
}

/// M and K over q = (x_c, y_c, u_c, x_r, y_r, u_r, x_s, y_s, u_s, ζ_1, η_1, u_1, ...).
struct Model {
  Eigen::MatrixXd M, K;
};

inline constexpr int kCarrier = 0, kRing = 3, kSun = 6;
inline int PlanetIndex(int i) { return 9 + 3 * i; }

inline Model Build(const Parameters& p) {
  if (static_cast<int>(p.psi.size()) != p.planets)
    throw std::invalid_argument("lin_parker::Build: psi has " + std::to_string(p.psi.size()) +
                                " angles for " + std::to_string(p.planets) + " planets");
  const int n = 9 + 3 * p.planets;
  Model m{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  const double masses[][2] = {{p.m_c, p.j_c}, {p.m_r, p.j_r}, {p.m_s, p.j_s}};
  for (int j = 0; j < 3; ++j) {
    m.M(3 * j, 3 * j) = m.M(3 * j + 1, 3 * j + 1) = masses[j][0];
    m.M(3 * j + 2, 3 * j + 2) = masses[j][1];
  }
  // A spring of stiffness k whose deflection is Σ v_a q_(index_a).
  auto spring = [&m](double k, const std::vector<std::pair<int, double>>& v) {
    for (const auto& [a, va] : v)
      for (const auto& [b, vb] : v) m.K(a, b) += k * va * vb;
  };
  const double bearings[][3] = {
      {p.k_c, p.k_cu, kCarrier}, {p.k_r, p.k_ru, kRing}, {p.k_s, p.k_su, kSun}};
  for (const auto& [k, ku, at] : bearings) {
    const int j = static_cast<int>(at);
    spring(k, {{j, 1.0}});
    spring(k, {{j + 1, 1.0}});
    spring(ku, {{j + 2, 1.0}});
  }
  for (int i = 0; i < p.planets; ++i) {
    const int q = PlanetIndex(i);
    m.M(q, q) = m.M(q + 1, q + 1) = p.m_p;
    m.M(q + 2, q + 2) = p.j_p;
    const double psi = p.psi[static_cast<size_t>(i)];
    const double psi_s = psi - p.alpha_s, psi_r = psi + p.alpha_r;
    spring(p.k_sp, {{kSun, -std::sin(psi_s)},
                    {kSun + 1, std::cos(psi_s)},
                    {kSun + 2, 1.0},
                    {q, -std::sin(p.alpha_s)},
                    {q + 1, -std::cos(p.alpha_s)},
                    {q + 2, 1.0}});
    spring(p.k_rp, {{kRing, -std::sin(psi_r)},
                    {kRing + 1, std::cos(psi_r)},
                    {kRing + 2, 1.0},
                    {q, std::sin(p.alpha_r)},
                    {q + 1, -std::cos(p.alpha_r)},
                    {q + 2, -1.0}});
    spring(p.k_p, {{q, 1.0}, {kCarrier, -std::cos(psi)}, {kCarrier + 1, -std::sin(psi)}});
    spring(p.k_p, {{q + 1, 1.0},
                   {kCarrier, std::sin(psi)},
                   {kCarrier + 1, -std::cos(psi)},
                   {kCarrier + 2, -1.0}});
  }
  return m;
}

/// The layout of Lin & Parker's q for SolveModes (u counted as the member's rotation DOF).
inline std::vector<dynamics::MemberDofs> Layout(int planets) {
  std::vector<dynamics::MemberDofs> layout = {
      {"carrier", true, kCarrier, kCarrier + 1, kCarrier + 2},
      {"ring", true, kRing, kRing + 1, kRing + 2},
      {"sun", true, kSun, kSun + 1, kSun + 2}};
  for (int i = 0; i < planets; ++i) {
    const int q = PlanetIndex(i);
    layout.push_back({"planet " + std::to_string(i + 1), false, q, q + 1, q + 2});
  }
  return layout;
}

/// A model in the production layout: every member has inertial x [m], y [m], θ [rad].
struct InertialModel {
  Eigen::MatrixXd M, K;
  std::vector<dynamics::MemberDofs> layout;
};

/// Lin & Parker's model in inertial x, y, θ coordinates (same member order, 3 DOFs each):
/// q_LP = T q with u_j = r_j θ_j, ζ_i = x_i cos ψ_i + y_i sin ψ_i, η_i = −x_i sin ψ_i + y_i cos
/// ψ_i; M' = TᵀMT, K' = TᵀKT (a congruence: the frequencies are unchanged, the mass matrix stays
/// diagonal, with I_j = (I_j/r_j²)·r_j² on θ_j). This is what the production model should
/// reproduce when fed the same stiffnesses, inertias and mesh pressure angles.
inline InertialModel ToInertial(const Parameters& p, const Model& m) {
  const int n = static_cast<int>(m.M.rows());
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(n, n);
  const double radii[] = {p.r_c, p.r_r, p.r_s};
  for (int j = 0; j < 3; ++j) {
    t(3 * j, 3 * j) = t(3 * j + 1, 3 * j + 1) = 1.0;
    t(3 * j + 2, 3 * j + 2) = radii[j];
  }
  for (int i = 0; i < p.planets; ++i) {
    const int q = PlanetIndex(i);
    const double c = std::cos(p.psi[static_cast<size_t>(i)]),
                 s = std::sin(p.psi[static_cast<size_t>(i)]);
    t(q, q) = c, t(q, q + 1) = s;
    t(q + 1, q) = -s, t(q + 1, q + 1) = c;
    t(q + 2, q + 2) = p.r_p;
  }
  return {t.transpose() * m.M * t, t.transpose() * m.K * t, Layout(p.planets)};
}

/// Removes the DOFs `held` (e.g. a member fixed in the production model) from M, K and the
/// layout (their entries become −1, the others are renumbered).
inline InertialModel Hold(const InertialModel& in, std::vector<int> held) {
  const int n = static_cast<int>(in.M.rows());
  std::vector<int> map(static_cast<size_t>(n), 0);
  for (int d : held) map.at(static_cast<size_t>(d)) = -1;
  int kept = 0;
  for (int d = 0; d < n; ++d)
    if (map[static_cast<size_t>(d)] == 0) map[static_cast<size_t>(d)] = kept++;
  InertialModel out{Eigen::MatrixXd(kept, kept), Eigen::MatrixXd(kept, kept), in.layout};
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (map[static_cast<size_t>(a)] >= 0 && map[static_cast<size_t>(b)] >= 0) {
        out.M(map[static_cast<size_t>(a)], map[static_cast<size_t>(b)]) = in.M(a, b);
        out.K(map[static_cast<size_t>(a)], map[static_cast<size_t>(b)]) = in.K(a, b);
      }
  for (dynamics::MemberDofs& member : out.layout)
    for (int* d : {&member.x, &member.y, &member.theta})
      if (*d >= 0) *d = map[static_cast<size_t>(*d)];
  return out;
}

}  // namespace epicycle::test::lin_parker
