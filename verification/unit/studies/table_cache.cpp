// The FE influence tables under studies: two processes building the same table at once both end
// with a valid cache file (unique temporary names, atomic rename); a tooth-thickness error does
// not change the table (it is built on the nominal body) and the compliance read on the nominal
// body at the turned-back flank points agrees with that of a table built on the body with the
// error, within the body's change, 3|Δs|/s (bending ∝ 1/s³).
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "epicycle/compliance/compliance_operator.hpp"
#include "epicycle/compliance/influence_cache.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "study_fixtures.hpp"

using namespace epicycle;
using test::Sci;
using test::VerifyRow;

namespace {

compliance::InfluenceTableOptions Coarse() { return test::CoarseTableOptions(); }

}  // namespace

TEST_CASE("influence-table cache: two processes building one table at once",
          "[unit][studies][cache]") {
  const transmission::Scene scene = test::PaperScene();
  const geometry::Gear gear(scene.stage.planet);
  const compliance::ElasticMaterial steel{
      scene.material.youngs_modulus, scene.material.poisson_ratio, scene.stage.planet.face_width,
      compliance::PlaneAssumption::kPlaneStrain};
  test::TempDir dir("ilt-race");
  // Both children wait on one pipe and start together: both find no file and build.
  int go[2];
  REQUIRE(pipe(go) == 0);
  std::vector<pid_t> children;
  std::fflush(nullptr);  // the children must not write the parent's buffered output again
  for (int c = 0; c < 2; ++c) {
    const pid_t pid = fork();
    if (pid == 0) {
      close(go[1]);
      char byte = 0;
      if (read(go[0], &byte, 1) != 1) _exit(3);
      try {
        compliance::CacheReport r;
        const auto t =
            compliance::LoadOrBuildInfluenceTable(gear, steel, Coarse(), dir.path.string(), &r);
        _exit(t.join_depth() > 0 ? 0 : 2);
      } catch (...) {
        _exit(1);
      }
    }
    children.push_back(pid);
  }
  close(go[0]);
  const char bytes[2] = {1, 1};
  REQUIRE(write(go[1], bytes, 2) == 2);
  close(go[1]);
  int ok = 0;
  for (pid_t pid : children) {
    int status = 0;
    waitpid(pid, &status, 0);
    ok += WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 1 : 0;
  }
  CHECK(ok == 2);
  // One valid file, no temporary left behind; a third reader loads it.
  int files = 0, temporaries = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path)) {
    ++files;
    temporaries += e.path().extension() == ".tmp" ? 1 : 0;
  }
  CHECK(files == 1);
  CHECK(temporaries == 0);
  compliance::CacheReport r;
  compliance::LoadOrBuildInfluenceTable(gear, steel, Coarse(), dir.path.string(), &r);
  CHECK(r.outcome == compliance::CacheOutcome::kLoaded);
  VerifyRow("influence-table cache: two processes build the same table at once",
            "each ends with a table; one valid file",
            std::to_string(ok) + " of 2 succeeded, " + std::to_string(files) +
                " file, third process: " +
                (r.outcome == compliance::CacheOutcome::kLoaded ? "loaded" : "rebuilt"),
            "-", "2 of 2, loaded", ok == 2 && r.outcome == compliance::CacheOutcome::kLoaded);
}

TEST_CASE("influence tables: a thickness error leaves the table's key nominal and acts as a gap",
          "[unit][studies][cache]") {
  // A planet thinner by |Δs| opens a gap of |Δs|/2 normal to each loaded flank, one in the sun
  // mesh and one in the ring mesh, in series along the planet's load path: to first order the
  // path error e_1 = |Δs|, the same as a tangential pin-hole error Δη with
  // e_1 = −Δη (cos α_sp + cos α_pr) (docs/model.md §8). Both are run through the quasi-static
  // driver on the same (nominal) tables; their mesh-cycle means of 1 − L_i must agree to the
  // second-order difference of the two errors: the pin error also turns the two meshes' lines of
  // action by Δη/a (a the centre distances), a relative change of the path below
  // |Δη|/(a tan α) ≈ 1e-4 here, and the contacts sit |Δs|/2 ≈ 5 µm apart along flanks whose
  // stiffness varies by ~40 % over a base pitch of ~12 mm (≈ 2e-4 relative); 1 % covers both
  // with a margin for the solver's 1e-10 tolerance.
  transmission::Scene scene = test::PaperScene();
  const double ds = -10e-6;
  const compliance::ElasticMaterial steel{
      scene.material.youngs_modulus, scene.material.poisson_ratio, scene.stage.planet.face_width,
      compliance::PlaneAssumption::kPlaneStrain};
  const compliance::InfluenceTableOptions defaults;
  geometry::GearSpec thin = scene.stage.planet;
  thin.thickness_error = ds;
  CHECK(compliance::InfluenceTableKey(thin, steel, defaults) ==
        compliance::InfluenceTableKey(scene.stage.planet, steel, defaults));

  const geometry::Stage nominal_stage(scene.stage);
  double a_sp = 0, a_pr = 0;
  for (const auto& m : nominal_stage.meshes())
    if (m.planet == 0) (m.kind == geometry::MeshKind::kSunPlanet ? a_sp : a_pr) = m.pressure_angle;
  const double eta = ds / (std::cos(a_sp) + std::cos(a_pr));
  auto mean_l = [&](transmission::Scene sc) {
    const geometry::Stage stage(sc.stage);
    const transmission::StageModel model(stage, test::Compliance("paper_stage.toml"),
                                         transmission::SetupFromScene(sc));
    const auto r = transmission::Sweep(model, sc.loads,
                                       transmission::SweepAngles(0.0, stage.mesh_cycle(), 24), {});
    const auto s = transmission::SummariseSweep(r, 3);
    REQUIRE(s.converged == 24);
    return s.lsr_mean;
  };
  transmission::Scene with_thickness = scene, with_pin = scene;
  with_thickness.stage.planet_thickness_errors = {ds, 0.0, 0.0};
  with_pin.stage.pin_errors = {{0.0, eta}, {}, {}};
  const auto lt = mean_l(with_thickness), lp = mean_l(with_pin);
  double worst = 0;
  for (int i = 0; i < 3; ++i)
    worst = std::max(worst, std::abs(lt[i] - lp[i]) / std::abs(1.0 / 3 - lp[0]));
  CHECK(lt[0] < 1.0 / 3);  // the thinner planet carries less
  CHECK(worst <= 0.01);
  VerifyRow("planet 1 thinner by 10 um (nominal tables, gap on the flanks): mesh-cycle mean LSR",
            "tangential pin error of the same path error, eta = " + Sci(eta * 1e6) + " um",
            "LSR_1 " + std::to_string(lt[0]) + " (pin: " + std::to_string(lp[0]) + ")",
            Sci(worst) + " of 1/3 - LSR_1", "1 %", worst <= 0.01);
}
