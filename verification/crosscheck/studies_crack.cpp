// A root crack's depth as a study variable (docs/studies.md): each case builds its own damaged
// rows (through the table cache) and its row equals what the `epicycle quasistatic` program
// reports for the case's scene written out as a scene file, the crack's depth_mm set there (its
// own path: scene reader, tables, driver, summary JSON).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/studies/runner.hpp"
#include "figures.hpp"
#include "quasistatic_program.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;

namespace {

constexpr int kPositions = 8;
const double kDepthMm[] = {0.5, 2.0};

// The paper's stage with a crack in sun tooth 0 (which meshes with planet 1 over the first mesh
// cycle) of depth `depth_mm`.
std::string CrackedScene(double depth_mm) {
  return test::FileBytes(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml") +
         "\n[[damage.crack]]\ngear = \"sun\"\ntooth = 0\nside = \"-\"\ndepth_mm = " +
         std::to_string(depth_mm) + "\nangle_deg = 45\n";
}

}  // namespace

TEST_CASE("study of a crack's depth: each case that of the quasistatic program",
          "[crosscheck][studies][crack]") {
  test::TempDir dir("study-crack");
  const std::string base = test::WriteText(dir.File("base.toml"), CrackedScene(1.0));
  const studies::StudySpec study = studies::ParseStudy(
      "[study]\nname = \"crack\"\nscene = \"" + base +
          "\"\npositions = " + std::to_string(kPositions) +
          "\nsun = \"fixed\"\n[[variable]]\nquantity = \"crack_depth\"\ncrack = 0\n"
          "distribution = \"grid\"\nvalues_mm = [0.5, 2.0]\n",
      "crack_study.toml", "");
  REQUIRE(study.Cases() == 2);
  studies::RunOptions o;
  o.rows_file = dir.File("rows.csv");
  o.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  o.threads = 2;
  const studies::RunReport report = studies::RunStudy(study, o);
  REQUIRE(report.rows.size() == 2);
  double largest = 0;
  for (const studies::CaseRow& r : report.rows) {
    INFO("case " << r.id << ": " << r.message);
    REQUIRE(r.ok());
    // The independent path: the program on the case's scene file, same angles and sequence.
    // The depth enters bit-identically (the grid's 0.5 and 2.0 mm, ×1e-3 in both readers), so
    // the two differ by the contact solves' stopping alone: each stops below 1e-10 relative
    // (ContactOptions::tolerance); 1e-9 is ten times it.
    const std::string scene = test::WriteText(dir.File("case" + std::to_string(r.id) + ".toml"),
                                              CrackedScene(kDepthMm[r.id]));
    const nlohmann::json qs = nlohmann::json::parse(
        test::QuasiStaticCycleSummary(scene, kPositions, dir.File("qs" + std::to_string(r.id))));
    const double k = qs.at("K_gamma_max").get<double>();
    const double te = qs.at("transmission_error_max_urad").get<double>() -
                      qs.at("transmission_error_min_urad").get<double>();
    CHECK(std::abs(r.k_gamma - k) <= 1e-9 * k);
    CHECK(std::abs(r.te_peak_to_peak - te) <= 1e-9 * te);
    largest =
        std::max({largest, std::abs(r.k_gamma - k) / k, std::abs(r.te_peak_to_peak - te) / te});
    test::Figure("crack study case " + std::to_string(r.id) + " (" + test::Sci(kDepthMm[r.id]) +
                 " mm): K_gamma " + test::Sci(r.k_gamma) + ", TE p-p " +
                 test::Sci(r.te_peak_to_peak) + " urad");
  }
  // The depth acts: the deeper crack widens the TE's range over the cycle.
  CHECK(report.rows[1].te_peak_to_peak > report.rows[0].te_peak_to_peak);
  test::VerifyRow("study of a sun crack's depth (0.5, 2 mm), 2 cases: K_gamma and TE p-p",
                  "the quasistatic program on the case's scene file", "2 quantities x 2 cases",
                  test::Sci(largest) + " relative", "1e-9", largest <= 1e-9);
}
