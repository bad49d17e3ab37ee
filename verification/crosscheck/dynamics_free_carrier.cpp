// A carrier free in rotation ([dynamics] carrier = "torque") through the `epicycle` program: its
// natural modes against Lin & Parker's lumped model with the carrier free (docs/dynamic.md,
// "Natural modes"), and its load sharing in motion against the quasi-static program at falling
// speeds (docs/model.md §7).
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dynamics_fixtures.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"
#include "figures.hpp"
#include "lin_parker.hpp"
#include "csv_rows.hpp"
#include "program_runs.hpp"

using namespace epicycle;
using test::Sci;
using test::VerifyRow;

namespace {

constexpr double kPinStiffness = 1e8;      // [N/m], [supports] planet_stiffness_N_per_um = 100
constexpr double kCarrierStiffness = 2e8;  // [N/m], [dynamics] carrier_stiffness_N_per_um = 200
constexpr double kLoadInertia = 0.05;      // [kg m²], [dynamics] carrier_load_inertia_kgm2

// The paper's stage with an elastic sun and pins, the carrier free in rotation with a load
// inertia, on an elastic bearing if `bearing`, friction off.
std::string FreeCarrierScene(bool bearing) {
  std::string text = test::AllElastic(test::SceneText("paper_stage.toml"));
  text = test::Replace(text, "[dynamics]\n",
                       "[dynamics]\ncarrier = \"torque\"\ncarrier_load_inertia_kgm2 = 0.05\n" +
                           std::string(bearing ? "carrier_stiffness_N_per_um = 200.0\n" : ""));
  return test::Replace(text, "friction = \"xu-kahraman\"", "friction = \"off\"");
}

std::string WriteScene(const std::string& dir, const std::string& text) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/free_carrier.toml";
  std::FILE* f = std::fopen(path.c_str(), "w");
  REQUIRE(f != nullptr);
  REQUIRE(std::fwrite(text.data(), 1, text.size(), f) == text.size());
  REQUIRE(std::fclose(f) == 0);
  return path;
}

// Runs the program with `args` (after the executable); requires exit status 0.
void RunProgram(const std::vector<std::string>& args) {
  std::vector<std::string> all{EPICYCLE_EXE};
  all.insert(all.end(), args.begin(), args.end());
  REQUIRE(test::ExitStatus(all) == 0);
}

}  // namespace

TEST_CASE(
    "free carrier through the program: `epicycle modes` equals Lin & Parker's model with the "
    "carrier free in rotation and on its bearing",
    "[crosscheck][dynamics][modes]") {
  const test::TempDir temp("free-carrier-modes");
  const std::string dir = temp.path.string();
  const std::string text = FreeCarrierScene(true);
  const std::string scene = WriteScene(dir, text);
  RunProgram({"modes", scene, "--cache", EPICYCLE_TEST_CACHE_DIR, "--json", dir + "/modes.json"});
  const nlohmann::json j = nlohmann::json::parse(test::FileBytes(dir + "/modes.json"));

  // Lin & Parker's model fed with the scene's inertias and geometry, and the mesh stiffnesses the
  // program reports (the FE's, an input of the lumped model, not what is checked); the ring held.
  const transmission::Scene s = transmission::ParseScene(text, "free_carrier.toml");
  const geometry::Stage st(s.stage);
  namespace lp = test::lin_parker;
  lp::Parameters p;
  p.planets = st.planets();
  for (int i = 0; i < p.planets; ++i) p.psi.push_back(st.planet_angle(i));
  p.r_s = st.sun().base_radius();
  p.r_r = st.ring().base_radius();
  p.r_p = st.planet(0).base_radius();
  p.r_c = st.carrier_radius();
  p.m_s = s.inertia.sun.mass, p.m_r = s.inertia.ring.mass, p.m_p = s.inertia.planet.mass;
  p.m_c = s.inertia.carrier.mass;
  p.j_s = s.inertia.sun.inertia / (p.r_s * p.r_s);
  p.j_r = s.inertia.ring.inertia / (p.r_r * p.r_r);
  p.j_p = s.inertia.planet.inertia / (p.r_p * p.r_p);
  p.j_c = (s.inertia.carrier.inertia + kLoadInertia) / (p.r_c * p.r_c);
  p.k_sp = j.at("mesh_stiffness_sun_planet_N_per_m").get<double>();
  p.k_rp = j.at("mesh_stiffness_planet_ring_N_per_m").get<double>();
  p.k_s = test::kBearing;
  p.k_p = kPinStiffness;
  p.k_c = kCarrierStiffness;
  p.k_su = p.k_cu = 0;  // the sun and the carrier free in rotation
  p.alpha_s = -st.meshes()[0].pressure_angle;  // the loaded flanks of −600 N·m (mirror image)
  p.alpha_r = -st.meshes()[1].pressure_angle;
  const auto ref = lp::Hold(lp::ToInertial(p, lp::Build(p)), {lp::kRing, lp::kRing + 1, lp::kRing + 2});
  const auto ref_modes = dynamics::SolveModes(ref.M, ref.K, ref.layout);

  std::vector<double> f, fr;
  int rigid = 0, ref_rigid = 0;
  for (const nlohmann::json& m : j.at("modes")) {
    if (m.at("type") == "rigid") {
      rigid += m.at("multiplicity").get<int>();
      continue;
    }
    for (int k = 0; k < m.at("multiplicity").get<int>(); ++k)
      f.push_back(m.at("frequency_Hz").get<double>());
  }
  for (const auto& x : ref_modes) {
    if (x.rigid) {
      ref_rigid += x.multiplicity;
      continue;
    }
    for (int k = 0; k < x.multiplicity; ++k) fr.push_back(x.frequency);
  }
  // The sun, planets and carrier turn together about the held ring: one rigid mode.
  CHECK(ref_rigid == 1);
  CHECK(rigid == ref_rigid);
  REQUIRE(f.size() == fr.size());
  REQUIRE(f.size() == static_cast<std::size_t>(ref.M.rows() - ref_rigid));
  double worst = 0;
  for (std::size_t k = 0; k < f.size(); ++k)
    worst = std::max(worst, std::abs(f[k] - fr[k]) / fr[k]);
  // Same M and K up to the round-off of the geometry (levers to 1e-12) and of the JSON's
  // shortest round-trip numbers: 1e-9, as for the held carrier (dynamics_stage.cpp).
  VerifyRow("natural frequencies through `epicycle modes`, free carrier on its bearing",
            "Lin & Parker (1999) lumped model, carrier free in rotation",
            std::to_string(f.size()) + " frequencies, " + Sci(f.front(), 4) + " .. " +
                Sci(f.back(), 4) + " Hz, " + std::to_string(rigid) + " rigid",
            "largest relative " + Sci(worst), "1e-9", worst <= 1e-9);
  CHECK(worst <= 1e-9);
}


TEST_CASE(
    "free carrier through the program: `epicycle dynamic` with a heavy carrier load equals the "
    "run with the carrier turned at its speed",
    "[crosscheck][dynamics]") {
  // Planet 1's pin 30 µm off tangentially: the planets share unequally. The carrier's centre is
  // held in both runs. A load inertia of 1e4 kg m² puts the free carrier's torsional mode on
  // the pins at sqrt(n k_p r_c² / J) = 15 rad/s, far below the mesh frequency (2017 rad/s): the
  // mesh torques turn it by ~T/(J ω_m²) ~ 1e-7 rad, and the free carrier must move as the carrier
  // that the other run turns at its speed, a model without the carrier's rotation.
  const test::TempDir temp("free-carrier-dynamic");
  const std::string dir = temp.path.string();
  const std::string pin =
      "\n[[errors.pin]]\ngear = \"planet1\"\nradial_um = 0.0\ntangential_um = 30.0\n";
  const std::string free_text = test::Replace(FreeCarrierScene(false) + pin,
                                              "carrier_load_inertia_kgm2 = 0.05",
                                              "carrier_load_inertia_kgm2 = 1e4");
  const std::string driven_text =
      test::Replace(test::Replace(free_text, "carrier = \"torque\"\n", ""),
                    "carrier_load_inertia_kgm2 = 1e4\n", "");
  REQUIRE(driven_text.find("carrier = ") == std::string::npos);
  std::map<std::string, std::vector<double>> steps[2];
  nlohmann::json summary[2];
  for (int k = 0; k < 2; ++k) {
    const std::string name = k == 0 ? "free" : "driven";
    const std::string scene = WriteScene(dir + "/" + name, k == 0 ? free_text : driven_text);
    const std::string out = dir + "/" + name + "/out";
    RunProgram({"dynamic", scene, "--range", "cycle", "--outputs-per-cycle", "24", "--cache",
                EPICYCLE_TEST_CACHE_DIR, "--quiet", "--out", out});
    steps[k] = test::ReadCsvColumns(out + "/dynamic_steps.csv");
    summary[k] = nlohmann::json::parse(test::FileBytes(out + "/dynamic_summary.json"));
  }
  REQUIRE(steps[0].at("time_s") == steps[1].at("time_s"));
  double gap = 0;
  for (int i = 1; i <= 3; ++i) {
    const std::string lsr = "LSR_" + std::to_string(i);
    for (std::size_t j = 0; j < steps[0].at(lsr).size(); ++j)
      gap = std::max(gap, std::abs(steps[0].at(lsr)[j] - steps[1].at(lsr)[j]));
  }
  // Each run's deflections are held to the integrator's absolute tolerance atol (its relative
  // tolerance of µm deflections is smaller); an error atol in a sun-mesh deflection moves
  // LSR_i by k_sp r_b,s atol / |T_s|, and N steps' errors add as a random walk (√N, the suite's
  // convention): 2 runs × √N × that.
  const transmission::Scene s = transmission::ParseScene(free_text, "free.toml");
  const double r_b = geometry::Stage(s.stage).sun().base_radius();
  const double n = std::max(summary[0].at("steps").get<double>(), summary[1].at("steps").get<double>());
  const double per_step = summary[0].at("mesh_stiffness_sun_planet_N_per_m").get<double>() * r_b *
                          summary[0].at("atol_length_m").get<double>() /
                          std::abs(s.loads.sun_torque);
  const double tolerance = 2 * std::sqrt(n) * per_step;
  const bool pass = gap <= tolerance;
  VerifyRow("free carrier with a load inertia of 1e4 kg m2 in motion through the program "
            "(pin error 30 um, 1500 rpm, a mesh cycle)",
            "the program's run with the carrier turned at its speed",
            "largest LSR gap " + Sci(gap), Sci(gap),
            Sci(tolerance) + " (2 sqrt(N) k_sp r_b atol / |T_s|, N = " +
                std::to_string(static_cast<long>(n)) + " steps)",
            pass);
  CHECK(pass);
}
