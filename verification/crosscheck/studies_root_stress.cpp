// Root stresses in a tolerance study (docs/studies.md, docs/stresses.md): with `stresses = true`
// each case's row carries each gear's largest root tension, compression and range over its sweep,
// equal to what the `epicycle quasistatic --stresses` program reports for that case's scene
// written out as a scene file (its own path: scene reader, driver, summary JSON); such rows
// survive a resume; with stresses off the rows have the columns they always had, and the load
// sharing is the same either way.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/study_summary.hpp"
#include "figures.hpp"
#include "quasistatic_program.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;

namespace {

constexpr int kPositions = 6;
const double kPinUm[] = {0.0, 15.0};  // planet 1's tangential pin error of cases 0 and 1

// A grid of planet 1's tangential pin error (two cases), fixed sun, a few positions over a mesh
// cycle, stresses on or off.
studies::StudySpec Study(bool stresses) {
  return studies::ParseStudy(
      test::StudyText("positions = " + std::to_string(kPositions) + "\nsun = \"fixed\"\n" +
                          "stresses = " + (stresses ? "true" : "false"),
                      "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planet1\"\n"
                      "distribution = \"grid\"\nvalues_um = [0.0, 15.0]\n"),
      "stress_study.toml", "");
}

studies::RunReport Run(const studies::StudySpec& s, const std::string& file, long max_cases = -1) {
  studies::RunOptions o;
  o.rows_file = file;
  o.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  o.threads = 2;
  o.max_new_cases = max_cases;
  return studies::RunStudy(s, o);
}

// The `quasistatic` program's summary for the paper's stage with planet 1's pin error, written as
// a scene file (the base scene's text with an [[errors.pin]] table).
nlohmann::json QuasiStatic(const test::TempDir& dir, double pin_um, int k) {
  const std::string scene = test::WriteText(
      dir.File("case" + std::to_string(k) + ".toml"),
      test::FileBytes(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml") +
          "\n[[errors.pin]]\ngear = \"planet1\"\ntangential_um = " + std::to_string(pin_um) + "\n");
  return nlohmann::json::parse(test::QuasiStaticCycleSummary(
      scene, kPositions, dir.File("qs" + std::to_string(k)), {"--stresses"}));
}

}  // namespace

TEST_CASE("study root stress: each case's extremes those of the quasistatic program",
          "[crosscheck][studies][stress]") {
  test::TempDir dir("study-stress");
  const studies::StudySpec on = Study(true), off = Study(false);
  REQUIRE(on.Cases() == 2);
  const std::vector<std::string> gears = on.StressGears();
  REQUIRE(gears == std::vector<std::string>{"sun", "ring", "planet1", "planet2", "planet3"});
  CHECK(off.StressGears().empty());

  // Stresses off: the columns the rows always had.
  CHECK(studies::RowHeader(off) ==
        "case,planet1.pin_tangential_um,status,positions,converged,K_gamma,K_gamma_mean,LSR_min,"
        "LSR_max,TE_pp_urad,sun_orbit_um,message,check");
  std::string head =
      "case,planet1.pin_tangential_um,status,positions,converged,K_gamma,"
      "K_gamma_mean,LSR_min,LSR_max,TE_pp_urad,sun_orbit_um";
  for (const std::string& g : gears)
    head += ",sigma_t_" + g + "_MPa,sigma_c_" + g + "_MPa,sigma_range_" + g + "_MPa";
  CHECK(studies::RowHeader(on) == head + ",message,check");

  double largest = 0;  // relative difference from the program's figures

  // One case, then a resume: the rows read back (parsed) and the computed one are the same.
  Run(on, dir.File("on.csv"), 1);
  const studies::RunReport a = Run(on, dir.File("on.csv"));
  CHECK(a.resumed == 1);
  CHECK(a.computed == 1);
  const studies::RunReport b = Run(off, dir.File("off.csv"));
  REQUIRE(a.rows.size() == 2);
  REQUIRE(b.rows.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    const studies::CaseRow& r = a.rows[k];
    INFO("case " << r.id << ": " << r.message);
    REQUIRE(r.ok());
    REQUIRE(b.rows[k].ok());
    CHECK(b.rows[k].root_stress.empty());
    // The load sharing does not depend on the stresses (the tables' compliance is the same).
    CHECK(b.rows[k].k_gamma == r.k_gamma);
    CHECK(b.rows[k].te_peak_to_peak == r.te_peak_to_peak);
    REQUIRE(r.root_stress.size() == 3 * gears.size());

    // The independent path: the program on the case's scene file. Same angles, same warm-started
    // sequence, same model; the inputs may differ in their last digit (the pin error converted
    // µm → m by the study's grid and by the scene's key), and each contact solve stops once its
    // nondimensional residual is below 1e-10 (ContactOptions::tolerance), so solves of the two
    // may differ by that much relative: 1e-9 is ten times it (measured: 2e-13), and far below any
    // modelling effect (planet 1's 15 µm moves its root stress by tens of per cent).
    const nlohmann::json qs = QuasiStatic(dir, kPinUm[r.id], static_cast<int>(r.id));
    const nlohmann::json& list = qs.at("root_stress");
    REQUIRE(list.size() == gears.size());
    for (std::size_t g = 0; g < gears.size(); ++g) {
      INFO(gears[g]);
      CHECK(list[g].at("gear") == gears[g]);
      const double expected[3] = {list[g].at("tension_MPa").get<double>(),
                                  list[g].at("compression_MPa").get<double>(),
                                  list[g].at("largest_range_MPa").get<double>()};
      for (int q = 0; q < 3; ++q) {
        const double got = r.root_stress[3 * g + q];
        CHECK(std::abs(got - expected[q]) <= 1e-9 * std::abs(expected[q]));
        largest = std::max(largest, std::abs(got - expected[q]) / std::abs(expected[q]));
      }
      CHECK(expected[0] > 0);
      CHECK(expected[1] < 0);
    }
    test::Figure("study root stress case " + std::to_string(r.id) + " (planet1 pin " +
                 test::Sci(kPinUm[r.id]) + " um): planet1 tension " +
                 test::Sci(r.root_stress[3 * 2]) + " MPa, K_gamma " + test::Sci(r.k_gamma));
  }
  test::VerifyRow("study with stresses, 2 cases: each gear's root tension, compression, range",
                  "the quasistatic program on the case's scene file", "5 gears x 3 x 2 cases",
                  test::Sci(largest) + " relative", "1e-9", largest <= 1e-9);
  // Planet 1's pin error moves load to planet 1: its largest tension grows with it.
  CHECK(a.rows[1].root_stress[3 * 2] > 1.1 * a.rows[0].root_stress[3 * 2]);

  // The summary: each gear's distribution over the two cases.
  const studies::StudySummary s = studies::SummariseStudy(on, a.rows);
  REQUIRE(s.root_stress.size() == gears.size());
  CHECK(s.root_stress[2].gear == "planet1");
  CHECK(s.root_stress[2].tension.count == 2);
  CHECK(s.root_stress[2].tension.max == a.rows[1].root_stress[3 * 2]);
  CHECK(s.root_stress[1].compression.max == std::max(std::abs(a.rows[0].root_stress[3 * 1 + 1]),
                                                     std::abs(a.rows[1].root_stress[3 * 1 + 1])));
  CHECK(studies::SummariseStudy(off, b.rows).root_stress.empty());

  // A file written without stresses is not resumed with them (the study file unchanged, its base
  // scene's [model] stresses switched on): its column line says so.
  studies::StudySpec edited = off;
  edited.scene.model.stresses = true;
  try {
    Run(edited, dir.File("off.csv"));
    FAIL("no error");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Catch::Contains("not the rows file of this study") &&
                             Catch::Contains("sigma_t_sun_MPa"));
  }
}

// With the material's endurance limits in the base scene, each case's row also carries every
// gear's safety factors from its own stresses; the reference is the `quasistatic --rating`
// program on the case's scene file (its JSON's S_F_model_stress, S_H_model_pressure), to the same
// 1e-9 as the stresses above (the factors are σ_lim-scaled reciprocals of them).
TEST_CASE("study safety factors: each case's S_F and S_H those of quasistatic --rating",
          "[crosscheck][studies][stress]") {
  test::TempDir dir("study-rating");
  std::string base = test::FileBytes(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
  const std::string nu = "poisson_ratio = 0.3\n";
  REQUIRE(base.find(nu) != std::string::npos);
  base.insert(base.find(nu) + nu.size(), "bending_limit_MPa = 430.0\ncontact_limit_MPa = 1500.0\n");
  const std::string scene = test::WriteText(dir.File("rated.toml"), base);
  const studies::StudySpec study = studies::ParseStudy(
      "[study]\nname = \"rated\"\nscene = \"" + scene +
          "\"\npositions = " + std::to_string(kPositions) + "\nsun = \"fixed\"\nstresses = true\n" +
          "[[variable]]\nquantity = \"pin_tangential\"\ngear = \"planet1\"\n"
          "distribution = \"grid\"\nvalues_um = [0.0, 15.0]\n",
      "rated_study.toml", "");
  REQUIRE(study.Rated());
  const std::vector<std::string> gears = study.StressGears();
  CHECK_THAT(studies::RowHeader(study),
             Catch::Contains(",sigma_range_planet3_MPa,S_F_sun,S_H_sun,S_F_ring,S_H_ring,") &&
                 Catch::EndsWith(",S_F_planet3,S_H_planet3,message,check"));
  const studies::RunReport report = Run(study, dir.File("rows.csv"));
  REQUIRE(report.rows.size() == 2);
  // Read back: the factors survive the rows file.
  const auto back = studies::ReadRows(dir.File("rows.csv"), study);
  REQUIRE(back.rows.size() == 2);
  double largest = 0;
  for (const studies::CaseRow& r : report.rows) {
    INFO("case " << r.id << ": " << r.message);
    REQUIRE(r.ok());
    REQUIRE(r.safety.size() == 2 * gears.size());
    for (const auto& b : back.rows)
      if (b.id == r.id) CHECK(b.safety == r.safety);
    const std::string case_scene =
        test::WriteText(dir.File("case" + std::to_string(r.id) + ".toml"),
                        base + "\n[[errors.pin]]\ngear = \"planet1\"\ntangential_um = " +
                            std::to_string(kPinUm[r.id]) + "\n");
    const nlohmann::json qs = nlohmann::json::parse(test::QuasiStaticCycleSummary(
        case_scene, kPositions, dir.File("qs" + std::to_string(r.id)), {"--rating"}));
    for (const nlohmann::json& g : qs.at("rating").at("gears")) {
      const auto at = std::find(gears.begin(), gears.end(), g.at("gear").get<std::string>());
      REQUIRE(at != gears.end());
      const auto k = static_cast<std::size_t>(at - gears.begin());
      const double sf = g.at("S_F_model_stress").get<double>(),
                   sh = g.at("S_H_model_pressure").get<double>();
      INFO(*at << ": S_F " << r.safety[2 * k] << " (program " << sf << "), S_H "
               << r.safety[2 * k + 1] << " (program " << sh << ")");
      CHECK(std::abs(r.safety[2 * k] - sf) <= 1e-9 * sf);
      CHECK(std::abs(r.safety[2 * k + 1] - sh) <= 1e-9 * sh);
      largest = std::max(
          {largest, std::abs(r.safety[2 * k] - sf) / sf, std::abs(r.safety[2 * k + 1] - sh) / sh});
    }
  }
  test::VerifyRow("study safety factors, 2 cases x 5 gears: S_F and S_H per case",
                  "quasistatic --rating on each case's scene file", "",
                  test::Sci(largest, 2) + " relative", "1e-9 (the stresses' tolerance)",
                  largest <= 1e-9);
}
