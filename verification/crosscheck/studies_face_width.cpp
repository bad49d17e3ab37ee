// A study of a planet pin's tilt (docs/studies.md, docs/face_width.md): each case's K_Hβ and
// K_γ·K_Hβ per mesh against the quasi-static driver run on that case's scene written out as a
// scene of its own ([[face_width.pin_tilt]] with the case's value), the door a user would take to
// check one case by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/study_summary.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "program_runs.hpp"
#include "stage_fixtures.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;

namespace {

// The paper stage with 5 uncoupled slices of the face width (a quarter of the scenes' default:
// both drivers run the same model, the comparison does not need the converged count).
std::string SlicedScene() {
  return test::SceneText("paper_stage.toml") + "\n[face_width]\nslices = 5\n";
}

class NoSink final : public transmission::QuasiStaticSink {};

// A double as a TOML number that reads back to the same double.
std::string Exact(double v) {
  std::ostringstream o;
  o << std::setprecision(17) << v;
  const std::string s = o.str();
  return s.find_first_of(".e") == std::string::npos ? s + ".0" : s;
}

}  // namespace

TEST_CASE(
    "face width in a study: each case's K_Hbeta and K_gamma K_Hbeta per mesh are those of "
    "the quasi-static driver on the case's scene",
    "[crosscheck][studies][face_width]") {
  const test::TempDir dir("study-face-width");
  const std::string scene_file = test::WriteText(dir.File("sliced.toml"), SlicedScene());
  // Planet 1's radial tilt on a grid (either sign, and none) and a random tangential one: three
  // grid points, two cases each, four positions over the mesh cycle.
  const std::string text =
      "[study]\nname = \"pin tilt\"\nscene = \"" + scene_file +
      "\"\nseed = 5\nsamples = 2\npositions = 4\n"
      "[[variable]]\nquantity = \"pin_tilt_radial\"\ngear = \"planet1\"\ndistribution = "
      "\"grid\"\nvalues_um = [-20.0, 0.0, 20.0]\n"
      "[[variable]]\nquantity = \"pin_tilt_tangential\"\ngear = \"planet1\"\ndistribution = "
      "\"uniform\"\nmin_um = -10.0\nmax_um = 10.0\n";
  const studies::StudySpec study = studies::ParseStudy(text, "tilt.toml", "");
  REQUIRE(study.FaceMeshes().size() == 6);
  REQUIRE(study.Columns() ==
          std::vector<std::string>{"planet1.pin_tilt_radial_um", "planet1.pin_tilt_tangential_um"});
  studies::RunOptions o;
  o.rows_file = dir.File("rows.csv");
  o.cache_directory = test::CachedTables().cache_directory;
  const studies::RunReport run = studies::RunStudy(study, o);
  REQUIRE(run.rows.size() == 6);

  // The quasi-static driver on each case's scene. Both solve the same contact problems to the
  // back end's tolerance 1e-10 on the nondimensional residual (100× that when converged
  // inaccurately); K_Hβ and L_i·K_Hβ are ratios of forces, so their relative error is at most
  // twice the forces': 2e-8. The study warm-starts a case's first position from its grid point's
  // first case, the driver from its previous position: the answers differ by no more.
  double worst = 0;
  for (const studies::CaseRow& row : run.rows) {
    REQUIRE(row.ok());
    REQUIRE(row.face_load.size() == 12);
    transmission::QuasiStaticRequest q;
    q.scene = transmission::ParseScene(
        SlicedScene() + "[[face_width.pin_tilt]]\nplanet = 1\nradial_um = " + Exact(row.values[0]) +
            "\ntangential_um = " + Exact(row.values[1]) + "\n",
        "case " + std::to_string(row.id));
    q.positions = 4;
    q.threads = 1;
    q.tables = test::CachedTables();
    NoSink none;
    const transmission::QuasiStaticRecord r = transmission::RunQuasiStatic(q, none);
    REQUIRE(r.converged_positions == 4);
    REQUIRE(r.summary.face_width.size() == 6);
    for (std::size_t m = 0; m < 6; ++m) {
      const transmission::MeshFaceSummary& f = r.summary.face_width[m];
      INFO("case " << row.id << " " << f.mesh);
      CHECK(row.face_load[2 * m] == Approx(f.k_h_beta_max).epsilon(2e-8));
      CHECK(row.face_load[2 * m + 1] == Approx(f.k_gamma_k_h_beta_max).epsilon(2e-8));
      worst = std::max(worst, std::abs(row.face_load[2 * m] / f.k_h_beta_max - 1));
    }
  }
  // The summary's distribution per mesh: its largest is the largest case's.
  const studies::StudySummary s = studies::SummariseStudy(study, run.rows);
  REQUIRE(s.face_width.size() == 6);
  CHECK(s.face_width[0].mesh == "sun-planet1");
  double largest = 0;
  for (const studies::CaseRow& row : run.rows) largest = std::max(largest, row.face_load[1]);
  CHECK(s.face_width[0].k_gamma_k_h_beta.max == largest);
  CHECK(s.face_width[0].k_gamma_k_h_beta.count == 6);
  // The tilts misalign planet 1's meshes (a radial and a tangential tilt may cancel in one mesh:
  // 20 µm radial has 20 sin 27.85° = 9.3 µm along the sun mesh's normal, 10 µm tangential
  // 10 cos 27.85° = 8.8 µm), so some case's K_Hβ is well off 1.
  CHECK(s.face_width[0].k_h_beta.max > 1.05);
  test::VerifyRow("study of a pin tilt: K_Hbeta per case and mesh (6 cases, 5 slices)",
                  "quasi-static driver on each case's scene",
                  "largest relative difference " + test::Sci(worst), "",
                  "<= 2e-8 (solver tolerance)", worst <= 2e-8);
}
