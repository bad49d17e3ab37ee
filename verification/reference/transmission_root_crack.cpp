// A root crack in a scene (the [[damage.crack]] table, docs/model.md §9 "Root crack"): the tables
// of the drivers hold the cracked body's rows (compliance::DamagedInfluence) beside the healthy
// table, cached on disk like it; and in a quasi-static sweep of the paper stage the cracked sun
// tooth is found again where the rigid kinematics puts it in mesh with each planet in turn.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "epicycle/compliance/influence_cache.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/stage_model.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using test::Figure;

namespace {

constexpr double kPi = std::numbers::pi;

// A crack on the loaded (σ = −1: the sun torque is negative) side of sun tooth `tooth`.
std::string SunCrack(int tooth, const std::string& start, double depth_mm) {
  return "\n[[damage.crack]]\ngear = \"sun\"\ntooth = " + std::to_string(tooth) +
         "\nside = \"-\"\n" + start + "\ndepth_mm = " + std::to_string(depth_mm) +
         "\nangle_deg = 45\n";
}

transmission::Scene CrackedPaper(const std::string& crack) {
  return transmission::ParseScene(test::SceneText("paper_stage.toml") + crack, "cracked.toml");
}

}  // namespace

TEST_CASE("root crack in a scene: the stage's rows are the cracked body's, placed as asked",
          "[reference][crack]") {
  const transmission::Scene scene = CrackedPaper(SunCrack(2, "start = \"iso_30deg\"", 1.0));
  const geometry::Stage stage(scene.stage);
  const transmission::FeStageCompliance fe(scene, stage, test::CachedTables());
  const compliance::DamagedInfluence* d = fe.tables().Damaged(transmission::kSunBody);
  REQUIRE(d != nullptr);
  for (int b = transmission::kRingBody; b < fe.tables().size(); ++b)
    CHECK(fe.tables().Damaged(b) == nullptr);  // the ring and every planet stay healthy
  // Placed at ISO's 30° point of the nominal sun, the rest as written.
  CHECK(d->crack().start_arc == compliance::IsoCriticalFilletArc(stage.sun()));
  CHECK(d->crack().tooth == 2);
  CHECK(d->crack().side == -1);
  CHECK(d->HoldsLoadsOn(1));
  CHECK(d->HoldsLoadsOn(3));
  CHECK_FALSE(d->HoldsLoadsOn(4));
  // The same rows as the compliance level builds them from the crack directly (the tables'
  // options: the scene's [model] on the defaults): bit-identical influence.
  const compliance::InfluenceTable& healthy = fe.tables().Table(transmission::kSunBody);
  compliance::InfluenceTableOptions o;
  const compliance::ElasticMaterial material{
      scene.material.youngs_modulus, scene.material.poisson_ratio, scene.stage.sun.face_width,
      compliance::PlaneAssumption::kPlaneStrain};
  const compliance::DamagedInfluence direct =
      compliance::DamagedInfluence::Build(stage.sun(), material, d->crack(), o);
  const int n = healthy.grid().num_points();
  for (int load : {1, 2, 3, 7})
    for (int response : {2, 3, 9}) {
      const compliance::FlankPosition a{load, -1, healthy.grid().arc_length[n / 2]};
      const compliance::FlankPosition r{response, 1, healthy.grid().arc_length[n / 3]};
      CHECK((d->Influence(healthy, a, r) - direct.Influence(healthy, a, r)).norm() == 0.0);
    }
  // Placed at the largest root tension of a tip load: on the fillet, near ISO's point (the
  // literature's 30°-tangent rule is the standard's approximation of that point).
  const transmission::Scene largest = CrackedPaper(SunCrack(2, "", 1.0));
  const transmission::FeStageCompliance fl(largest, stage, test::CachedTables());
  const double arc = fl.tables().Damaged(transmission::kSunBody)->crack().start_arc;
  Figure("root crack in the sun: start at the largest tip-load tension " +
         std::to_string(arc * 1e3) + " mm along the fillet, ISO's 30-degree point " +
         std::to_string(compliance::IsoCriticalFilletArc(stage.sun()) * 1e3) + " mm");
  CHECK(arc > 0.0);
  CHECK(std::abs(arc - compliance::IsoCriticalFilletArc(stage.sun())) <
        0.25 * scene.stage.sun.module);
}

TEST_CASE("root crack in a scene: the damaged rows are cached, every damaged file rebuilt",
          "[reference][crack]") {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "epicycle-crack-cache-test").string();
  std::filesystem::remove_all(dir);
  // The sun of the paper's stage alone (16 teeth: the smallest body of the scenes).
  const transmission::Scene scene = CrackedPaper(SunCrack(5, "start_arc_mm = 1.5", 1.5));
  const geometry::Stage stage(scene.stage);
  transmission::FeComplianceOptions options;
  options.cache_directory = dir;
  auto build = [&] {
    const transmission::GearTables t(scene, {&stage.sun()}, {"sun"}, options);
    REQUIRE(t.Damaged(0) != nullptr);
    const compliance::InfluenceTable& h = t.Table(0);
    const int n = h.grid().num_points();
    // A damaged row (load on the cracked tooth) and a Maxwell–Betti one (response on it).
    const Eigen::Matrix2d a = t.Damaged(0)->Influence(h, {5, -1, h.grid().arc_length[n / 2]},
                                                      {6, 1, h.grid().arc_length[n / 4]});
    const Eigen::Matrix2d b = t.Damaged(0)->Influence(h, {9, 1, h.grid().arc_length[n / 2]},
                                                      {4, -1, h.grid().arc_length[n / 4]});
    std::string log;
    for (const std::string& m : t.messages()) log += m + "\n";
    return std::make_tuple(a, b, log);
  };
  const auto [a0, b0, log0] = build();
  CHECK_THAT(log0, Catch::Contains("damaged rows of 'sun' (root crack in tooth 5) built and "
                                   "written to"));
  const auto [a1, b1, log1] = build();
  CHECK_THAT(log1, Catch::Contains("damaged rows of 'sun' (root crack in tooth 5) loaded from"));
  CHECK(a1 == a0);  // bit-exact through the file
  CHECK(b1 == b0);
  std::string file;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string().rfind("damaged-", 0) == 0) file = e.path().string();
  REQUIRE(!file.empty());
  // Every corruption named and rebuilt: a flipped payload byte, a truncation, a stale format.
  const auto size = std::filesystem::file_size(file);
  struct Corruption {
    std::string what, expected;
  };
  for (const Corruption& c :
       {Corruption{"flip", "damaged: checksum"}, Corruption{"truncate", "damaged: truncated"},
        Corruption{"format", "stale: format"}}) {
    {
      std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
      if (c.what == "flip") {
        f.seekp(static_cast<std::streamoff>(size / 2));
        f.put('\x5a');
      } else if (c.what == "format") {
        f.seekp(16);
        const std::uint32_t stale = compliance::kInfluenceTableFormat + 1;
        f.write(reinterpret_cast<const char*>(&stale), sizeof stale);
      }
    }
    if (c.what == "truncate") std::filesystem::resize_file(file, size - 100);
    const auto [a, b, log] = build();
    CHECK_THAT(log, Catch::Contains(c.expected) && Catch::Contains("were rebuilt"));
    CHECK(a == a0);
    CHECK(b == b0);
    CHECK(std::filesystem::file_size(file) == size);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("root crack in a scene: root stresses are refused on a cracked body, naming the crack",
          "[reference][crack]") {
  transmission::Scene scene = CrackedPaper(SunCrack(0, "start_arc_mm = 1.5", 1.0));
  scene.model.stresses = true;
  const geometry::Stage stage(scene.stage);
  try {
    const transmission::FeStageCompliance fe(scene, stage, test::CachedTables());
    FAIL("a cracked sun with root stresses");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Catch::Contains("cracked.toml:") &&
                             Catch::Contains("damage.crack[0].gear: a root crack on 'sun'") &&
                             Catch::Contains("not tabulated on a cracked body"));
  }
}

TEST_CASE(
    "root crack in a scene: a quasi-static sweep finds the cracked sun tooth at each planet "
    "in turn, at the kinematic angles",
    "[reference][crack]") {
  // The paper stage (16/24/65, 3 planets, ring held) over one revolution of the sun relative to
  // the carrier, φ_c ∈ [0, 2π z_s/z_r): sun tooth 0 passes each planet once. A crack of 2 mm
  // (about a quarter of the sun's root chord) on its loaded side.
  constexpr int kTooth = 0, kPerMesh = 8;
  const transmission::Scene hs = test::PaperScene();
  const transmission::Scene cs = CrackedPaper(SunCrack(kTooth, "", 2.0));
  const geometry::Stage stage(hs.stage);
  const int zs = stage.sun().teeth(), zr = stage.ring().teeth(), n = stage.planets();
  const transmission::FeStageCompliance& fh = test::Compliance("paper_stage.toml");
  const transmission::FeStageCompliance fc(cs, stage, test::CachedTables());
  const transmission::StageModel mh(stage, fh, transmission::SetupFromScene(hs));
  const transmission::StageModel mc(stage, fc, transmission::SetupFromScene(cs));
  const int positions = zs * kPerMesh;
  const double span = 2 * kPi * zs / zr;
  const std::vector<double> angles = transmission::SweepAngles(0.0, span, positions);
  transmission::QuasiStaticOptions o;
  o.threads = 2;
  const auto h = transmission::Sweep(mh, hs.loads, angles, o);
  const auto c = transmission::Sweep(mc, cs.loads, angles, o);
  // Per position: ΔTE (the cracked tooth makes its mesh more compliant: the sun turns further),
  // and from the healthy run alone which planet the cracked tooth and its neighbours load.
  std::vector<double> dte(positions);
  std::vector<int> planet_of_tooth(positions, -1);    // planet whose mesh tooth 0 carries ≥ 20 %
  std::vector<bool> neighbourhood(positions, false);  // tooth 0 or ±1 carries any load
  double peak = 0;
  for (int p = 0; p < positions; ++p) {
    REQUIRE(h[p].converged);
    REQUIRE(c[p].converged);
    dte[p] = std::abs(c[p].transmission_error) - std::abs(h[p].transmission_error);
    peak = std::max(peak, std::abs(dte[p]));
    std::vector<double> mesh(n, 0.0), own(n, 0.0);
    const auto& contacts = h[p].problem.contacts;
    for (std::size_t j = 0; j < contacts.size(); ++j) {
      const transmission::StageContact& s = contacts[j];
      const double f = h[p].solution.force(static_cast<Eigen::Index>(j));
      if (s.mesh != geometry::MeshKind::kSunPlanet || !(f > 0)) continue;
      mesh[s.planet] += f;
      const int t = s.contact.tooth_a;  // the sun is body a of a sun–planet contact
      if (t == kTooth) own[s.planet] += f;
      if (t == kTooth || t == (kTooth + 1) % zs || t == (kTooth + zs - 1) % zs)
        neighbourhood[p] = true;
    }
    for (int i = 0; i < n; ++i)
      if (own[i] >= 0.2 * mesh[i]) planet_of_tooth[p] = i;
  }
  REQUIRE(peak > 0);
  // Where neither the cracked tooth nor its neighbours carry anything, the crack is invisible:
  // the couplings two teeth away and more are the healthy table's (K = 1), so ΔTE is the
  // round-off of the two solves (the contact solver's tolerance, 1e-10 of a TE of 840 µrad:
  // 1e-13 rad; measured 1e-15). Where the tooth carries a fifth or more of its mesh, the TE
  // rises by far more than that (a loaded cracked tooth is measurably softer: its rise is largest
  // with the load at its tip, smallest near its root, where the bending arm is short); where only
  // a neighbour carries, by the neighbours' few per cent (docs/model.md §9, "Root crack").
  const double roundoff = 1e-10 * std::abs(h[0].transmission_error);
  int loaded = 0, quiet = 0;
  double lowest_loaded = 1e9, largest_quiet = 0;
  for (int p = 0; p < positions; ++p) {
    if (planet_of_tooth[p] >= 0) {
      ++loaded;
      lowest_loaded = std::min(lowest_loaded, dte[p]);
    } else if (!neighbourhood[p]) {
      ++quiet;
      largest_quiet = std::max(largest_quiet, std::abs(dte[p]));
    }
  }
  Figure("cracked sun tooth (2 mm) in a sweep of one relative revolution, " +
         std::to_string(positions) + " positions: TE rise peak " + test::Sci(peak * 1e6) +
         " urad; positions where the tooth carries >= 20 % of its mesh " + std::to_string(loaded) +
         " (smallest rise " + test::Sci(lowest_loaded / peak) + " of the peak); quiet positions " +
         std::to_string(quiet) + " (largest |dTE| " + test::Sci(largest_quiet * 1e6) + " urad)");
  CHECK(largest_quiet <= roundoff);
  CHECK(lowest_loaded >= 1e3 * roundoff);
  // The quiet positions cut the revolution into n bumps, and each bump's largest rise lies where
  // the tooth meshes with one planet, a different one for each bump.
  auto busy = [&](int p) {
    p %= positions;
    return planet_of_tooth[p] >= 0 || neighbourhood[p];
  };
  std::vector<int> bump_planet;
  for (int p0 = 0; p0 < positions; ++p0) {
    if (!busy(p0) || busy(p0 + positions - 1)) continue;  // p0 starts a bump
    int top = p0;
    for (int p = p0; busy(p) && p < p0 + positions; ++p)
      if (dte[p % positions] > dte[top % positions]) top = p;
    bump_planet.push_back(planet_of_tooth[top % positions]);
  }
  std::vector<int> sorted = bump_planet;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> expected(n);
  for (int i = 0; i < n; ++i) expected[i] = i;
  CHECK(sorted == expected);
  // n groups of positions, one per planet, each a contiguous run (cyclically) of the sweep.
  std::vector<int> first_of(n, -1), count_of(n, 0);
  for (int p = 0; p < positions; ++p) {
    const int i = planet_of_tooth[p];
    if (i < 0) continue;
    ++count_of[i];
    const int prev = planet_of_tooth[(p + positions - 1) % positions];
    if (prev != i) {
      CHECK(first_of[i] == -1);  // each planet's run starts once per revolution
      first_of[i] = p;
    }
  }
  // The kinematic angles: the sun turns by θ_rel = φ_c z_r/z_s relative to the carrier, so the
  // tooth reaches planet i when θ_rel has moved by the planets' spacing ψ_i − ψ_0 (the same
  // mesh geometry at every planet: the runs are the same shifted). Each run's centre in θ_rel
  // against planet 0's, within one position step (2π/positions of θ_rel) for the centres'
  // discretisation, in the sense the sun turns (the same sense for every planet).
  const double step = 2 * kPi / positions;
  std::vector<double> centre(n);
  for (int i = 0; i < n; ++i) {
    REQUIRE(first_of[i] >= 0);
    centre[i] = (first_of[i] + (count_of[i] - 1) / 2.0) * step;
  }
  double worst[2] = {0, 0};
  for (int sense = 0; sense < 2; ++sense)
    for (int i = 1; i < n; ++i) {
      const double psi = stage.planet_angle(i) - stage.planet_angle(0);
      double d = std::remainder((centre[i] - centre[0]) - (sense == 0 ? psi : -psi), 2 * kPi);
      worst[sense] = std::max(worst[sense], std::abs(d));
    }
  const double best = std::min(worst[0], worst[1]);
  Figure("cracked sun tooth: positions per planet " + std::to_string(count_of[0]) + "/" +
         std::to_string(count_of[1]) + "/" + std::to_string(count_of[2]) +
         "; run centres against the planets' spacing, worst " + test::Sci(best / step) +
         " position steps");
  CHECK(best <= step);
}
