// SolveModes on small systems with closed-form modes: frequencies, rigid-body modes, degenerate
// groups and their energy fractions, and the validation of its inputs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "epicycle/dynamics/modes.hpp"
#include "figures.hpp"
#include "thrown_message.hpp"

using namespace epicycle::dynamics;
using epicycle::test::ThrownMessage;

namespace {

// Two masses in a chain: ground —k1— m1 —k2— m2. ω² are the roots of
// m1 m2 λ² − (m1 k2 + m2 (k1 + k2)) λ + k1 k2 = 0.
struct Chain {
  double m1 = 2, m2 = 0.5, k1 = 3e6, k2 = 1e6;
  Eigen::MatrixXd M() const { return Eigen::Vector2d(m1, m2).asDiagonal(); }
  Eigen::MatrixXd K() const {
    Eigen::MatrixXd k(2, 2);
    k << k1 + k2, -k2, -k2, k2;
    return k;
  }
  double Lambda(int sign) const {
    const double b = m1 * k2 + m2 * (k1 + k2), c = m1 * m2;
    return (b + sign * std::sqrt(b * b - 4 * c * k1 * k2)) / (2 * c);
  }
};

double Hz(double lambda) { return std::sqrt(lambda) / (2 * M_PI); }

}  // namespace

TEST_CASE("a two-mass chain: frequencies and energy fractions in closed form",
          "[unit][dynamics][modes]") {
  const Chain ch;
  // Member "a" (central) moves along x only, member "b" (a planet) along x only.
  const std::vector<MemberDofs> layout = {{"a", true, 0, -1, -1}, {"b", false, 1, -1, -1}};
  const std::vector<Mode> modes = SolveModes(ch.M(), ch.K(), layout);
  REQUIRE(modes.size() == 2);
  double worst = 0;
  for (int j = 0; j < 2; ++j) {
    const double lambda = ch.Lambda(j == 0 ? -1 : 1);
    worst = std::max(worst, std::abs(modes[j].frequency / Hz(lambda) - 1));
    // Tolerance: a dense symmetric eigensolver's eigenvalues carry ~ε·max λ absolute error.
    CHECK(modes[j].frequency == Approx(Hz(lambda)).epsilon(1e-12));
    CHECK(modes[j].multiplicity == 1);
    CHECK_FALSE(modes[j].rigid);
    // Shape (1, r) with r = (k1 + k2 − m1 λ)/k2; energy share of m1 = m1/(m1 + m2 r²).
    const double r = (ch.k1 + ch.k2 - ch.m1 * lambda) / ch.k2;
    const double share = ch.m1 / (ch.m1 + ch.m2 * r * r);
    CHECK(modes[j].central_translation == Approx(share).epsilon(1e-10));
    CHECK(modes[j].planets == Approx(1 - share).epsilon(1e-10));
    CHECK(modes[j].central_rotation == 0.0);
    CHECK(modes[j].type == ModeType::kTranslational);
    CHECK((modes[j].shape.transpose() * ch.M() * modes[j].shape)(0, 0) ==
          Approx(1.0).epsilon(1e-12));
  }
  epicycle::test::VerifyRow("SolveModes, two-mass chain: both frequencies",
                            "roots of m1 m2 l^2 - (m1 k2 + m2 (k1 + k2)) l + k1 k2", "SolveModes",
                            epicycle::test::Sci(worst, 2) + " relative", "1e-12", worst <= 1e-12);
}

TEST_CASE("a free–free pair is reported as one rigid mode at 0 Hz, not NaN",
          "[unit][dynamics][modes]") {
  const double m1 = 1.5, m2 = 0.7, k = 2e7;
  Eigen::MatrixXd M = Eigen::Vector2d(m1, m2).asDiagonal(), K(2, 2);
  K << k, -k, -k, k;
  const std::vector<Mode> modes =
      SolveModes(M, K, {{"carrier", true, -1, -1, 0}, {"load", true, -1, -1, 1}});
  REQUIRE(modes.size() == 2);
  CHECK(modes[0].rigid);
  CHECK(modes[0].frequency == 0.0);
  CHECK(modes[0].type == ModeType::kRotational);  // both central members only rotate
  CHECK(modes[1].frequency == Approx(Hz(k * (1 / m1 + 1 / m2))).epsilon(1e-12));
  for (const Mode& mode : modes) CHECK(mode.shape.allFinite());
}

TEST_CASE("an isotropic planar oscillator: one double translational group, energy by member",
          "[unit][dynamics][modes]") {
  // Central member c (x, y, θ) on isotropic springs k_b, coupled isotropically (k_m) to a
  // non-central member p (x, y). In x and y separately it is the chain above (k1 = k_b,
  // k2 = k_m): every frequency is double, and the group's central energy equals the chain's share
  // whatever basis the solver picks in the degenerate plane. θ has its own spring.
  const Chain ch;
  const double j = 0.01, k_t = 5e4;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(5, 5), K = Eigen::MatrixXd::Zero(5, 5);
  // q = (x_c, y_c, θ_c, x_p, y_p)
  M.diagonal() << ch.m1, ch.m1, j, ch.m2, ch.m2;
  for (int axis = 0; axis < 2; ++axis) {
    const int c = axis, p = 3 + axis;
    K(c, c) = ch.k1 + ch.k2, K(p, p) = ch.k2, K(c, p) = K(p, c) = -ch.k2;
  }
  K(2, 2) = k_t;
  const std::vector<MemberDofs> layout = {{"c", true, 0, 1, 2}, {"p", false, 3, 4, -1}};
  const std::vector<Mode> modes = SolveModes(M, K, layout);
  REQUIRE(modes.size() == 3);
  const double f_theta = Hz(k_t / j);
  int translational = 0, rotational = 0;
  for (const Mode& mode : modes) {
    if (mode.type == ModeType::kRotational) {
      ++rotational;
      CHECK(mode.multiplicity == 1);
      CHECK(mode.frequency == Approx(f_theta).epsilon(1e-12));
      CHECK(mode.central_rotation == Approx(1.0).epsilon(1e-12));
      continue;
    }
    REQUIRE(mode.type == ModeType::kTranslational);
    ++translational;
    CHECK(mode.multiplicity == 2);
    CHECK(mode.shapes.cols() == 2);
    const double lambda = std::pow(2 * M_PI * mode.frequency, 2);
    const double r = (ch.k1 + ch.k2 - ch.m1 * lambda) / ch.k2;
    CHECK(mode.central_translation == Approx(ch.m1 / (ch.m1 + ch.m2 * r * r)).epsilon(1e-10));
    CHECK(mode.member_energy[0] + mode.member_energy[1] == Approx(1.0).epsilon(1e-12));
    const Eigen::MatrixXd gram = mode.shapes.transpose() * M * mode.shapes;
    CHECK((gram - Eigen::MatrixXd::Identity(2, 2)).cwiseAbs().maxCoeff() < 1e-12);
  }
  CHECK(translational == 2);
  CHECK(rotational == 1);
}

TEST_CASE("a degenerate group mixing rotation and translation is 'other', not misread",
          "[unit][dynamics][modes]") {
  // The isotropic oscillator above with the torsional frequency tuned onto the lower chain
  // frequency: the three modes at that frequency form one group whose subspace contains both
  // central translation and rotation. Whatever basis the solver returns, the group's summed
  // energy shows both, so the group is kOther with multiplicity 3.
  const Chain ch;
  const double j = 0.01, lambda = ch.Lambda(-1);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(5, 5), K = Eigen::MatrixXd::Zero(5, 5);
  M.diagonal() << ch.m1, ch.m1, j, ch.m2, ch.m2;
  for (int axis = 0; axis < 2; ++axis) {
    const int c = axis, p = 3 + axis;
    K(c, c) = ch.k1 + ch.k2, K(p, p) = ch.k2, K(c, p) = K(p, c) = -ch.k2;
  }
  K(2, 2) = lambda * j;
  const std::vector<Mode> modes = SolveModes(M, K, {{"c", true, 0, 1, 2}, {"p", false, 3, 4, -1}});
  REQUIRE(modes.size() == 2);
  CHECK(modes[0].multiplicity == 3);
  CHECK(modes[0].type == ModeType::kOther);
  // Averaged over the 3 modes: the rotation carries 1/3 of the group's energy, the translation
  // 2/3 of the chain's central share.
  const double r = (ch.k1 + ch.k2 - ch.m1 * lambda) / ch.k2;
  CHECK(modes[0].central_rotation == Approx(1.0 / 3).epsilon(1e-9));
  CHECK(modes[0].central_translation ==
        Approx(2.0 / 3 * ch.m1 / (ch.m1 + ch.m2 * r * r)).epsilon(1e-9));
  CHECK(modes[1].type == ModeType::kTranslational);
}

TEST_CASE("bad inputs of SolveModes are named", "[unit][dynamics][modes]") {
  const Chain ch;
  const std::vector<MemberDofs> layout = {{"a", true, 0, -1, -1}, {"b", false, 1, -1, -1}};
  Eigen::MatrixXd asym = ch.K();
  asym(0, 1) *= 1.01;
  CHECK(ThrownMessage([&] { SolveModes(ch.M(), asym, layout); }).find("K(0,1)") !=
        std::string::npos);
  CHECK(ThrownMessage([&] {
          SolveModes(ch.M(), Eigen::MatrixXd::Zero(3, 3), layout);
        }).find("K is 3x3") != std::string::npos);
  Eigen::MatrixXd singular = ch.M();
  singular(1, 1) = 0;
  CHECK(ThrownMessage([&] {
          SolveModes(singular, ch.K(), layout);
        }).find("M is not positive definite") != std::string::npos);
  CHECK(ThrownMessage([&] {
          SolveModes(ch.M(), ch.K(), {{"a", true, 0, -1, -1}, {"b", false, 2, -1, -1}});
        }).find("layout[1] (b).x = 2") != std::string::npos);
  CHECK(ThrownMessage([&] {
          SolveModes(ch.M(), ch.K(), {{"a", true, 0, -1, -1}, {"b", false, 0, -1, -1}});
        }).find("already belongs to layout[0] (a)") != std::string::npos);
  CHECK(ThrownMessage([&] {
          SolveModes(ch.M(), ch.K(), {{"a", true, 0, -1, -1}});
        }).find("DOF 1 belongs to no member") != std::string::npos);
  CHECK(ThrownMessage([&] {
          SolveModes(ch.M(), ch.K(), layout, 0.0);
        }).find("degeneracy_tolerance = 0") != std::string::npos);
  Eigen::MatrixXd unstable = ch.K();
  unstable(1, 1) = -1e6;
  unstable(0, 1) = unstable(1, 0) = 0;
  CHECK_THROWS_AS(SolveModes(ch.M(), unstable, layout), std::domain_error);
  CHECK(ModeTypeName(ModeType::kPlanet) == "planet");
  CHECK(ModeTypeName(ModeType::kTranslational) == "translational");
}
