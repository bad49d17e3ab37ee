// The study file (docs/studies.md): bad files give messages naming the key, the value and the
// rule; counter-based sampling (case k's values depend on (seed, k) only); the distributions'
// moments against their definitions; ISO 1328-1's run-out tolerance against a hand calculation;
// k_gamma_limit's rules and counts; the shipped K_gamma table studies' tolerances and table values.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <stdexcept>

#include "epicycle/geometry/iso.hpp"
#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/sampling.hpp"
#include "epicycle/studies/study.hpp"
#include "epicycle/studies/study_summary.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;
using Catch::Contains;
using test::StudyError;
using test::StudyText;

namespace {

const std::string kPins =
    "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planets\"\ndistribution = "
    "\"normal\"\nsigma_um = 5.0\n";

}  // namespace

TEST_CASE("study file: bad input names the key, the value and the rule", "[unit][studies]") {
  SECTION("unknown distribution") {
    const std::string m = StudyError(
        StudyText("",
                  "[[variable]]\nquantity = \"pin_radial\"\ngear = \"planet1\"\ndistribution = "
                  "\"gauss\"\nsigma_um = 5.0\n"));
    CHECK_THAT(m, Contains("bad.toml:") && Contains("variable[0].distribution = \"gauss\"") &&
                      Contains("must be one of \"normal\", \"uniform\", \"iso1328\", \"grid\""));
  }
  SECTION("a variable along the face width on a scene without slices") {
    // paper_stage.toml has no [face_width]: a pin tilt has no axial extent to act on.
    const std::string m =
        StudyError(StudyText("",
                             "[[variable]]\nquantity = \"pin_tilt_radial\"\ngear = \"planet1\"\n"
                             "distribution = \"normal\"\nsigma_um = 5.0\n"));
    CHECK_THAT(m, Contains("variable[0].quantity = \"pin_tilt_radial\"") &&
                      Contains("varies along the face width") &&
                      Contains("[face_width] slices >= 2 needed"));
  }
  SECTION("a pin tilt of the sun, a normal crowning") {
    const std::string scene =
        "scene = \"" + std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_pin_tilt.toml\"";
    const std::string sun =
        StudyError("[study]\nname = \"t\"\n" + scene +
                   "\n[[variable]]\nquantity = \"pin_tilt_tangential\"\ngear = \"sun\"\n"
                   "distribution = \"normal\"\nsigma_um = 5.0\n");
    CHECK_THAT(sun, Contains("variable[0].gear = \"sun\"") &&
                        Contains("pin-hole errors exist for planets only"));
    const std::string crowning =
        StudyError("[study]\nname = \"t\"\n" + scene +
                   "\n[[variable]]\nquantity = \"crowning\"\ngear = \"sun\"\n"
                   "distribution = \"normal\"\nsigma_um = 5.0\n");
    CHECK_THAT(crowning,
               Contains("variable[0].distribution = \"normal\"") && Contains("a crowning is >= 0"));
  }
  SECTION("negative sigma") {
    const std::string m = StudyError(
        StudyText("",
                  "[[variable]]\nquantity = \"pin_radial\"\ngear = \"planet2\"\ndistribution = "
                  "\"normal\"\nsigma_um = -2.0\n"));
    CHECK_THAT(m, Contains("variable[0].sigma_um = -2") && Contains("must be >= 0") &&
                      Contains("a standard deviation is >= 0"));
  }
  SECTION("a sigma wider than the values the cases can take") {
    // docs/studies.md: a pin error within a quarter module, m/4 = 4230/4 = 1057.5 um on the
    // paper's stage; with mean 1000 um the room is 57.5 um (a sixth of the cases or more fail
    // past it).
    const std::string pin =
        "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planet1\"\ndistribution = "
        "\"normal\"\n";
    CHECK_THAT(StudyError(StudyText("", pin + "sigma_um = 1e6\n")),
               Contains("variable[0].sigma_um = 1000000") && Contains("must be <= 1057.5") &&
                   Contains("[-1057.5, 1057.5] um") && Contains("a sixth of the cases or more"));
    CHECK_THAT(StudyError(StudyText("", pin + "mean_um = 1000.0\nsigma_um = 60.0\n")),
               Contains("variable[0].sigma_um = 60") && Contains("must be <= 57.5"));
    CHECK(StudyError(StudyText("", pin + "mean_um = 1000.0\nsigma_um = 57.0\n")).empty());
  }
  SECTION("grade outside the standard") {
    const std::string m =
        StudyError(StudyText("",
                             "[[variable]]\nquantity = \"runout\"\ngear = \"sun\"\ndistribution = "
                             "\"iso1328\"\ngrade = 12\n"));
    CHECK_THAT(m, Contains("variable[0].grade = 12") && Contains("[1, 11]") &&
                      Contains("ISO 1328-1:2013"));
  }
  SECTION("a planet the scene does not have") {
    const std::string m =
        StudyError(StudyText("", test::Replace(kPins, "\"planets\"", "\"planet4\"")));
    CHECK_THAT(m, Contains("variable[0].gear = \"planet4\"") && Contains("\"planet3\"") &&
                      Contains("has 3 planets") && Contains("pin-hole errors exist for planets"));
  }
  SECTION("a pin-hole error on the sun") {
    const std::string m = StudyError(StudyText("", test::Replace(kPins, "\"planets\"", "\"sun\"")));
    CHECK_THAT(m, Contains("variable[0].gear = \"sun\"") && Contains("planets only"));
  }
  SECTION("ISO 1328-1 for a quantity it does not cover") {
    const std::string m = StudyError(
        StudyText("",
                  "[[variable]]\nquantity = \"thickness\"\ngear = \"ring\"\ndistribution = "
                  "\"iso1328\"\ngrade = 6\n"));
    CHECK_THAT(m, Contains("variable[0].distribution = \"iso1328\"") &&
                      Contains("run-out only (not for thickness)"));
  }
  SECTION("an unknown key, a key without its unit") {
    CHECK_THAT(StudyError(StudyText("", test::Replace(kPins, "sigma_um", "sigma"))),
               Contains("sigma"));
    CHECK_THAT(StudyError(StudyText("seeds = 3", "")), Contains("study.seeds"));
    CHECK_THAT(StudyError(StudyText("stresses = \"yes\"", "")), Contains("study.stresses"));
  }
  SECTION("a torque that changes the loaded flanks") {
    const std::string m = StudyError(
        StudyText("",
                  "[[variable]]\nquantity = \"torque\"\ndistribution = \"grid\"\nvalues_Nm = "
                  "[-600.0, 300.0]\n"));
    CHECK_THAT(m, Contains("values_Nm = 300") && Contains("sign of the scene's sun_torque_Nm"));
  }
  SECTION("a missing scene file") {
    const std::string m = StudyError("[study]\nname = \"x\"\nscene = \"no_such_scene.toml\"\n");
    CHECK_THAT(m, Contains("study.scene = \"no_such_scene.toml\"") && Contains("is not a file"));
  }
}

TEST_CASE("study and rows files that are not regular files are refused, not read",
          "[unit][studies]") {
  // A study file that is a FIFO (reading it would block) and a rows file that is a symlink to
  // /dev/full (it reads as endless zeros).
  test::TempDir dir("study-special");
  const std::string fifo = dir.File("study.toml");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  try {
    studies::ReadStudy(fifo);
    FAIL("a FIFO read as a study file");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Contains("study.toml: is a FIFO (named pipe), not a study file (TOML)"));
  }
  const std::string rows = dir.File("rows.csv");
  std::filesystem::create_symlink("/dev/full", rows);
  const studies::StudySpec study = studies::ParseStudy(StudyText("", kPins), "s.toml", "");
  try {
    studies::ReadRows(rows, study);
    FAIL("a device read as a rows file");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Contains("rows.csv: is a character device, not a study rows file (CSV)"));
  }
}

TEST_CASE("study file: counter-based sampling and grids", "[unit][studies]") {
  const studies::StudySpec s = studies::ParseStudy(
      StudyText("seed = 7\nsamples = 3",
                kPins + "[[variable]]\nquantity = \"torque\"\ndistribution = \"grid\"\n"
                        "values_Nm = [-300.0, -600.0]\n[[variable]]\nquantity = \"runout\"\n"
                        "gear = \"planet1\"\ndistribution = \"uniform\"\nmin_um = 0.0\n"
                        "max_um = 20.0\n"),
      "s.toml", "");
  REQUIRE(s.variables.size() == 5);  // three planets' pins, the torque, one run-out
  CHECK(s.GridPoints() == 2);
  CHECK(s.Cases() == 6);
  CHECK(s.Columns().size() == 6);  // the run-out has amplitude and phase
  // Case k's values depend on (seed, k) only: the same in any order, different between cases.
  const auto v5 = studies::SampleCase(s, 5);
  const auto v0 = studies::SampleCase(s, 0);
  CHECK(studies::SampleCase(s, 5) == v5);
  CHECK(v0 != v5);
  // The grid's first variable varies fastest: even cases -300, odd -600.
  for (long k = 0; k < 6; ++k) CHECK(studies::SampleCase(s, k)[3] == (k % 2 ? -600.0 : -300.0));
  // Applied to the scene: pin errors in m, the torque, the run-out with its phase in rad.
  const transmission::Scene c = studies::CaseScene(s, v5);
  CHECK(c.stage.pin_errors.at(2).tangential == Approx(v5[2] * 1e-6).epsilon(1e-15));
  CHECK(c.loads.sun_torque == -600.0);
  CHECK(c.stage.planet_runouts.at(0).amplitude == Approx(v5[4] * 1e-6).epsilon(1e-15));
  CHECK(c.stage.planet_runouts.at(0).phase == Approx(v5[5] * std::numbers::pi / 180.0));
  CHECK(v5[4] >= 0.0);
  CHECK(v5[4] < 20.0);
}

TEST_CASE("study sampling: the distributions' moments", "[unit][studies]") {
  // N draws: the sample mean of a standard normal has σ = 1/√N, its variance's σ ≈ √(2/N);
  // uniform [0,1): mean 1/2 (σ = 1/√(12N)). Tolerances 5σ: a correct generator fails with
  // probability below 1e-6.
  const long n = 200000;
  double sum = 0, sum2 = 0, usum = 0;
  long below = 0;
  for (long k = 0; k < n; ++k) {
    studies::CaseStream r(99, k, 0);
    const double z = r.Normal(), u = r.Uniform();
    sum += z;
    sum2 += z * z;
    usum += u;
    below += z < 1.6448536269514722 ? 1 : 0;  // Φ(1.645) = 0.95
  }
  const double nd = static_cast<double>(n);
  CHECK(std::abs(sum / nd) <= 5.0 / std::sqrt(nd));
  CHECK(std::abs(sum2 / nd - 1.0) <= 5.0 * std::sqrt(2.0 / nd));
  CHECK(std::abs(usum / nd - 0.5) <= 5.0 / std::sqrt(12.0 * nd));
  CHECK(std::abs(static_cast<double>(below) / nd - 0.95) <= 5.0 * std::sqrt(0.95 * 0.05 / nd));
}

TEST_CASE("ISO 1328-1:2013 run-out tolerance against a hand calculation", "[unit][studies]") {
  // Class 5, d = 100 mm, m_n = 4 mm: F_pT = 0.2 + 0.55·10 + 2.8 + 12 = 20.5 µm, F_rT = 18.45 µm;
  // one class coarser multiplies by √2.
  CHECK(studies::Iso1328RunoutTolerance(5, 0.1, 0.004) == Approx(18.45e-6).epsilon(1e-12));
  CHECK(studies::Iso1328RunoutTolerance(6, 0.1, 0.004) ==
        Approx(18.45e-6 * std::numbers::sqrt2).epsilon(1e-12));
  CHECK_THROWS_AS(studies::Iso1328RunoutTolerance(12, 0.1, 0.004), std::invalid_argument);
  CHECK_THROWS_AS(studies::Iso1328RunoutTolerance(5, 0.1, 0.0004), std::invalid_argument);
}

TEST_CASE("study file: a spall's size as study variables", "[unit][studies]") {
  // The example scene's pit 0 (planet 1, w 0.5, 30 µm): its depth on a grid, its width uniform.
  const std::string scene = std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_spall.toml";
  const std::string vars =
      "[[variable]]\nquantity = \"pit_depth\"\npit = 0\ndistribution = \"grid\"\n"
      "values_um = [10.0, 50.0]\n[[variable]]\nquantity = \"pit_width\"\npit = 0\n"
      "distribution = \"uniform\"\nmin_fraction = 0.2\nmax_fraction = 0.8\n";
  const std::string text =
      "[study]\nname = \"spall\"\nscene = \"" + scene + "\"\nsamples = 2\n" + vars;
  const studies::StudySpec s = studies::ParseStudy(text, "spall.toml", "");
  REQUIRE(s.variables.size() == 2);
  CHECK(s.Columns() == std::vector<std::string>{"pit0.pit_depth_um", "pit0.pit_width_fraction"});
  for (long k = 0; k < s.Cases(); ++k) {
    const auto v = studies::SampleCase(s, k);
    const transmission::Scene c = studies::CaseScene(s, v);
    CHECK(c.damage.pits.at(0).depth == Approx(v[0] * 1e-6).epsilon(1e-15));
    CHECK(c.damage.pits.at(0).width_fraction == v[1]);
    CHECK(v[0] == Approx(k % 2 ? 50.0 : 10.0).epsilon(1e-15));  // through 1e-6 and back
    CHECK(v[1] >= 0.2);
    CHECK(v[1] < 0.8);
    CHECK(c.damage.pits.at(0).tooth == 13);  // the rest of the pit is the scene's
  }
  // Bad: a pit the scene does not have, a width above 1, a scene without pits.
  CHECK_THAT(StudyError(test::Replace(text, "pit = 0\ndistribution = \"grid\"",
                                      "pit = 1\ndistribution = \"grid\"")),
             Contains("variable[0].pit = 1") && Contains("must be in [0, 0]") &&
                 Contains("[[damage.pit]]"));
  CHECK_THAT(StudyError(test::Replace(text, "max_fraction = 0.8", "max_fraction = 1.5")),
             Contains("variable[1].max_fraction = 1.5") && Contains("must be in (0, 1]"));
  CHECK_THAT(StudyError(StudyText("", vars)),
             Contains("variable[0].quantity = \"pit_depth\"") && Contains("no [[damage.pit]]"));
}

TEST_CASE("study file: a root crack's depth as a study variable", "[unit][studies]") {
  // The example scene's crack 0 (sun tooth 0, 2 mm at 45°): its depth on a grid.
  const std::string scene = std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_runout_crack.toml";
  const std::string vars =
      "[[variable]]\nquantity = \"crack_depth\"\ncrack = 0\ndistribution = \"grid\"\n"
      "values_mm = [0.5, 1.5]\n";
  const std::string text =
      "[study]\nname = \"crack\"\nscene = \"" + scene + "\"\nsamples = 1\n" + vars;
  const studies::StudySpec s = studies::ParseStudy(text, "crack.toml", "");
  REQUIRE(s.variables.size() == 1);
  CHECK(s.VariesBodies());
  CHECK(s.Columns() == std::vector<std::string>{"crack0.crack_depth_mm"});
  REQUIRE(s.Cases() == 2);
  for (long k = 0; k < s.Cases(); ++k) {
    const auto v = studies::SampleCase(s, k);
    const transmission::Scene c = studies::CaseScene(s, v);
    CHECK(v[0] == Approx(k == 0 ? 0.5 : 1.5).epsilon(1e-15));  // through 1e-3 and back
    REQUIRE(c.damage.cracks.at(0).crack.path.size() == 1);
    CHECK(c.damage.cracks.at(0).crack.path[0].length == v[0] * 1e-3);
    CHECK(c.damage.cracks.at(0).crack.path[0].angle ==
          s.scene.damage.cracks[0].crack.path[0].angle);  // the rest of the crack is the scene's
  }
  CHECK_THAT(StudyError(test::Replace(text, "values_mm = [0.5, 1.5]", "values_mm = [0.0]")),
             Contains("variable[0].values_mm") && Contains("(0, 4.23]"));
  CHECK_THAT(StudyError(test::Replace(text, "crack = 0", "crack = 2")),
             Contains("variable[0].crack = 2") && Contains("[[damage.crack]]"));
  CHECK_THAT(StudyError(StudyText("", vars)),
             Contains("variable[0].quantity = \"crack_depth\"") && Contains("no [[damage.crack]]"));
  CHECK_FALSE(test::PinStudy("").VariesBodies());
}

TEST_CASE("study file: a spread reaching past the backlash or the cases' values is a warning",
          "[unit][studies]") {
  // The paper's stage: normal backlash j_n = 150 um (the [[fit]]s), pin errors within m/4 =
  // 1057.5 um. sigma 40: 3 sigma = 120 < 150, no warning; sigma 60: 180 > 150, the backlash
  // warning; mean 900, sigma 100: 900 + 300 past 1057.5, the range warning too.
  auto warnings = [](const std::string& keys) {
    const studies::StudySpec s = studies::ParseStudy(
        StudyText("",
                  "[[variable]]\nquantity = \"pin_radial\"\ngear = \"planet2\"\n"
                  "distribution = \"normal\"\n" +
                      keys),
        "w.toml", "");
    std::string all;
    for (const std::string& w : s.warnings) all += w + "\n";
    return all;
  };
  CHECK(warnings("sigma_um = 40.0\n").find("sigma_um") == std::string::npos);
  CHECK_THAT(warnings("sigma_um = 60.0\n"), Contains("variable[0].sigma_um = 60") &&
                                                Contains("past the normal backlash j_n = 150"));
  CHECK_THAT(warnings("mean_um = 900.0\nsigma_um = 100.0\n"),
             Contains("mean +- 3 sigma reaches outside") && Contains("0.1 % of the cases"));
}

TEST_CASE("study file: k_gamma_limit, a number or an array, reported as P(K_gamma > x)",
          "[unit][studies]") {
  CHECK(test::PinStudy("k_gamma_limit = 1.25").k_gamma_limits == std::vector<double>{1.25});
  CHECK(test::PinStudy("k_gamma_limit = [1.1, 1.2]").k_gamma_limits ==
        std::vector<double>{1.1, 1.2});
  CHECK(test::PinStudy("").k_gamma_limits.empty());
  // K_γ = max_i n LSR_i is in [1, n]: the paper's stage has n = 3.
  CHECK_THAT(StudyError(StudyText("k_gamma_limit = 0.9", kPins)),
             Contains("study.k_gamma_limit = 0.9") && Contains("must be in [1, 3]") &&
                 Contains("K_gamma = max_i n LSR_i lies in [1, n] (n = 3 planets)"));
  CHECK_THAT(StudyError(StudyText("k_gamma_limit = [1.2, 4.0]", kPins)),
             Contains("study.k_gamma_limit[1] = 4") && Contains("must be in [1, 3]"));
  CHECK_THAT(StudyError(StudyText("k_gamma_limit = []", kPins)),
             Contains("study.k_gamma_limit = []") && Contains("at least one value"));
  // The summary counts the ok rows above each limit: K_γ = 1.0, 1.1, ..., 1.9 (ten cases, one
  // failed case left out): 5 above 1.45, 2 above 1.75.
  const studies::StudySpec s = test::PinStudy("samples = 11\nk_gamma_limit = [1.45, 1.75]");
  std::vector<studies::CaseRow> rows(11);
  for (int i = 0; i < 11; ++i) {
    rows[i].id = i;
    rows[i].values = {0, 0, 0};
    rows[i].status =
        i < 10 ? transmission::RunStatus::kCompleted : transmission::RunStatus::kContactFailure;
    rows[i].k_gamma = rows[i].k_gamma_mean = 1.0 + 0.1 * i;
  }
  const studies::StudySummary sum = studies::SummariseStudy(s, rows);
  REQUIRE(sum.k_gamma_exceedance.size() == 2);
  CHECK(sum.k_gamma_exceedance[0].count == 10);
  CHECK(sum.k_gamma_exceedance[0].above == 5);
  CHECK(sum.k_gamma_exceedance[1].above == 2);
  CHECK(sum.k_gamma_exceedance[1].threshold == 1.75);
}

TEST_CASE("the shipped K_gamma table studies: tolerances of their class, the table's values",
          "[unit][studies]") {
  // docs/studies.md "The standard's K_gamma table": every pin hole within ±f_pT/2 of ISO 1328-1
  // at the carrier's pitch circle d = 2 r_c (m_n of the gears), every gear's run-out of the same
  // class, the ABS table's K_γ by planet count (up to 3: 1.0, 4: 1.2, 5: 1.3, 6 and over: 1.4),
  // and the 3-planet stage's force per sun mesh, T/(n z_s) = 600/(3 · 16) N·m per tooth-count.
  const std::map<int, double> table{{3, 1.0}, {4, 1.2}, {5, 1.3}, {6, 1.4}};
  int files = 0;
  for (int n = 3; n <= 6; ++n)
    for (int grade = 5; grade <= 7; ++grade)
      for (const std::string support : {"", "_fixed"}) {
        const std::string path = std::string(EPICYCLE_SCENES_DIR) +
                                 "/studies/kgamma_table/planets" + std::to_string(n) + "_class" +
                                 std::to_string(grade) + support + ".toml";
        INFO(path);
        const studies::StudySpec s = studies::ReadStudy(path);
        ++files;
        const auto& st = s.scene.stage;
        REQUIRE(st.planets == n);
        CHECK(s.sun == (support.empty() ? transmission::SunSupport::kFloating
                                        : transmission::SunSupport::kFixed));
        CHECK(s.k_gamma_limits.front() == table.at(n));
        // The files give f_pT/2 to 4 decimals of a µm: within 5e-5 µm.
        const double half =
            0.5 * geometry::iso::SinglePitchTolerance(st.sun.module, 2 * st.carrier_radius, grade);
        double torque = s.scene.loads.sun_torque;
        int pins = 0, runouts = 0;
        for (const studies::Variable& v : s.variables) {
          if (v.quantity == studies::Quantity::kPinRadial ||
              v.quantity == studies::Quantity::kPinTangential) {
            ++pins;
            CHECK(v.distribution == studies::Distribution::kUniform);
            CHECK(v.max == Approx(half).margin(5.1e-11));
            CHECK(v.min == -v.max);
          }
          if (v.quantity == studies::Quantity::kRunout) {
            ++runouts;
            CHECK(v.distribution == studies::Distribution::kIso1328);
            CHECK(v.grade == grade);
          }
          if (v.quantity == studies::Quantity::kTorque) torque = v.grid.at(0);
        }
        CHECK(pins == 2 * n);
        CHECK(runouts == n + 2);
        CHECK(torque / (n * st.sun.teeth) == Approx(-600.0 / (3 * 16)).epsilon(1e-12));
      }
  CHECK(files == 24);
}
