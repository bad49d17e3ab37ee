// The FE reference's reader of CalculiX's nodal stresses (no ccx needed): a hand-written .frd in
// CalculiX's ASCII layout (fixed columns whose numbers touch, an ERROR block after each STRESS
// block, nodes outside the fillets) against σ_tt = tᵀσt worked out by hand, and the per-tooth
// extremes interpolated between two steps.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "fe_deck.hpp"

using namespace epicycle;

namespace {

// One node row of a STRESS block: " -1", the node in 10 columns, six stresses in 12 [MPa].
std::string Row(int node, double xx, double yy, double xy) {
  char line[128];
  std::snprintf(line, sizeof line, " -1%10d%12.5E%12.5E%12.5E%12.5E%12.5E%12.5E", node, xx, yy,
                -7.0, xy, 0.0, 0.0);
  return line;
}

void WriteFrd(const std::string& path, int steps) {
  std::ofstream f(path);
  f << "    1C\n    2C                             3                                     1\n"
    << " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n -3\n";
  for (int k = 1; k <= steps; ++k) {
    const double s = k;  // step k: the stresses of step 1 times k
    f << "    1PSTEP                         " << k << "           1           " << k << "\n"
      << "  100CL  10" << k << " " << k << ".000000000           4                     0    " << k
      << "           1\n"
      << " -4  STRESS      6    1\n -5  SXX         1    4    1    1\n"
      << Row(11, -120.0 * s, 35.5 * s, -10.0 * s) << "\n"
      << Row(12, 20.0 * s, -250.25 * s, 5.0 * s) << "\n"
      << Row(99, 1e4, 1e4, 1e4) << "\n"  // not a fillet node
      << Row(13, 100.0 * s, 60.0 * s, 40.0 * s) << "\n -3\n"
      << "  100CL  10" << k << " " << k << ".000000000           4                     0    " << k
      << "           1\n -4  ERROR       1    1\n -1        11 5.00000E+00\n -3\n";
  }
  f << "9999\n";
}

fe_reference::FeDeckInfo Info() {
  fe_reference::FeDeckInfo info;
  info.rotations = {1e-4, 1.2e-4};
  const double c = std::cos(geometry::kPi / 6), s = std::sin(geometry::kPi / 6);
  info.fillet_nodes = {{1, 0, 1, 11, 0.5e-3, 1.0, 0.0},
                       {1, 0, -1, 12, 1.5e-3, 0.0, 1.0},
                       {2, 3, 1, 13, 2.5e-3, c, s}};
  return info;
}

}  // namespace

TEST_CASE("fe_reference: sigma_tt from CalculiX's nodal stresses and per-tooth extremes",
          "[unit][fe_reference]") {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "epicycle_ccx_reader_test").string();
  std::filesystem::create_directories(dir);
  WriteFrd(dir + "/deck.frd", 2);
  const fe_reference::FeDeckInfo info = Info();
  const auto sigma = fe_reference::ReadFilletStresses(dir, info);
  REQUIRE(sigma.size() == 2);
  // By hand: node 11 t = x: σ_xx; node 12 t = y: σ_yy; node 13 t at 30°:
  // 0.75·100 + 0.25·60 + 2·(√3/4)·40 = 90 + 20√3 MPa. Print precision 6 digits: 1e-5 relative.
  const double n13 = 90.0 + 20.0 * std::sqrt(3.0);
  for (int k = 0; k < 2; ++k) {
    CHECK(sigma[k][0] == Approx(-120e6 * (k + 1)).epsilon(1e-5));
    CHECK(sigma[k][1] == Approx(-250.25e6 * (k + 1)).epsilon(1e-5));
    CHECK(sigma[k][2] == Approx(n13 * 1e6 * (k + 1)).epsilon(1e-5));
  }
  // Between the steps at u = 0.25: every value × 1.25. Gear 1 tooth 0: tension at node 11
  // (−150 MPa: a tooth without tension reports its largest, negative, value), compression at 12.
  fe_reference::FeSample sample;
  sample.step = 0;
  sample.weight = 0.25;
  const auto teeth = fe_reference::FilletExtremes(info, sample, sigma);
  REQUIRE(teeth.size() == 2);
  CHECK(teeth[0].gear == 1);
  CHECK(teeth[0].tooth == 0);
  CHECK(teeth[0].tension == Approx(-150e6).epsilon(1e-5));
  CHECK(teeth[0].tension_side == 1);
  CHECK(teeth[0].tension_arc == Approx(0.5e-3));
  CHECK(teeth[0].compression == Approx(-312.8125e6).epsilon(1e-5));
  CHECK(teeth[0].compression_side == -1);
  CHECK(teeth[0].compression_arc == Approx(1.5e-3));
  CHECK(teeth[1].gear == 2);
  CHECK(teeth[1].tooth == 3);
  CHECK(teeth[1].tension == Approx(1.25 * n13 * 1e6).epsilon(1e-5));
  // A file with one step of two, or without one of the nodes, is refused.
  WriteFrd(dir + "/deck.frd", 1);
  CHECK_THROWS_AS(fe_reference::ReadFilletStresses(dir, info), std::runtime_error);
  fe_reference::FeDeckInfo more = info;
  more.fillet_nodes.push_back({2, 3, -1, 14, 0.0, 1.0, 0.0});
  WriteFrd(dir + "/deck.frd", 2);
  CHECK_THROWS_AS(fe_reference::ReadFilletStresses(dir, more), std::runtime_error);
  std::filesystem::remove_all(dir);
}
