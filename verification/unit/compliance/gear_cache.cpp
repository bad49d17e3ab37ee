// The disk cache of influence tables: a valid file is loaded and gives the same table; a damaged,
// truncated or stale file is detected, reported and rebuilt, never used; the key follows every
// field that defines a table.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "epicycle/compliance/influence_cache.hpp"
#include "fe_fixtures.hpp"
#include "stage_fixtures.hpp"
#include "test_meshes.hpp"

using namespace epicycle;
using namespace epicycle::compliance;

namespace {

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() /
           ("epicycle-ilt-test-" +
            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code e;
    std::filesystem::remove_all(path, e);
  }
};

InfluenceTableOptions Coarse() { return test::CoarseTableOptions(); }

void FlipByte(const std::string& file, std::streamoff at) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(at);
  char c = 0;
  f.get(c);
  f.seekp(at);
  f.put(static_cast<char>(c ^ 0x5a));
}

}  // namespace

TEST_CASE("Influence-table cache: build, load, damaged and stale files", "[unit][gear]") {
  const transmission::Scene scene = test::PaperScene();
  const geometry::Gear gear(scene.stage.sun);
  const ElasticMaterial steel{scene.material.youngs_modulus, scene.material.poisson_ratio,
                              scene.stage.sun.face_width, PlaneAssumption::kPlaneStrain};
  const InfluenceTableOptions options = Coarse();
  TempDir dir;
  CacheReport report;
  const InfluenceTable built =
      LoadOrBuildInfluenceTable(gear, steel, options, dir.path.string(), &report);
  CHECK(report.outcome == CacheOutcome::kBuilt);
  const std::string file = report.file;
  REQUIRE(std::filesystem::exists(file));

  const auto t0 = std::chrono::steady_clock::now();
  const InfluenceTable loaded =
      LoadOrBuildInfluenceTable(gear, steel, options, dir.path.string(), &report);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  CHECK(report.outcome == CacheOutcome::kLoaded);
  testing::Figure("cache: coarse sun table loaded in " + testing::Sci(ms) + " ms (" +
                  std::to_string(std::filesystem::file_size(file)) + " bytes)");
  // The loaded table is the built one, bit for bit, at and between grid points.
  const double smax = built.arc_length_max();
  for (const auto& [a, b] :
       {std::pair<FlankPosition, FlankPosition>{{0, 1, 0.3 * smax}, {2, -1, 0.7 * smax}},
        {{1, -1, 0.5 * smax}, {1, -1, 0.5 * smax}}}) {
    CHECK(loaded.Influence(a, b) == built.Influence(a, b));
  }
  CHECK(loaded.join_depth() == built.join_depth());
  CHECK(loaded.Locate(built.grid().position[3], 0, 1).arc_length ==
        built.Locate(built.grid().position[3], 0, 1).arc_length);

  SECTION("a damaged payload is detected by its checksum and rebuilt") {
    FlipByte(file, 200);
    const InfluenceTable again =
        LoadOrBuildInfluenceTable(gear, steel, options, dir.path.string(), &report);
    CHECK(report.outcome == CacheOutcome::kRebuilt);
    CHECK_THAT(report.message, Catch::Contains("damaged: checksum") && Catch::Contains("rebuilt") &&
                                   Catch::Contains("not used"));
    CHECK(again.Influence({0, 1, 0.1 * smax}, {0, 1, 0.9 * smax}) ==
          built.Influence({0, 1, 0.1 * smax}, {0, 1, 0.9 * smax}));
    LoadOrBuildInfluenceTable(gear, steel, options, dir.path.string(), &report);
    CHECK(report.outcome == CacheOutcome::kLoaded);  // the replaced file is valid
  }
  SECTION("a truncated file is detected") {
    std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
    LoadOrBuildInfluenceTable(gear, steel, options, dir.path.string(), &report);
    CHECK(report.outcome == CacheOutcome::kRebuilt);
    CHECK_THAT(report.message, Catch::Contains("damaged: truncated"));
  }
  SECTION("a bad magic is detected") {
    FlipByte(file, 0);
    LoadOrBuildInfluenceTable(gear, steel, options, dir.path.string(), &report);
    CHECK(report.outcome == CacheOutcome::kRebuilt);
    CHECK_THAT(report.message, Catch::Contains("bad magic"));
  }
  SECTION("a cache file that cannot be replaced fails with the system's reason") {
    // A directory (not empty) where the file goes: the rename of the written file onto it fails.
    std::filesystem::remove(file);
    std::filesystem::create_directories(file + "/taken");
    try {
      LoadOrBuildInfluenceTable(gear, steel, options, dir.path.string(), &report);
      FAIL("no failure");
    } catch (const std::runtime_error& e) {
      CHECK_THAT(e.what(), Catch::Contains("cannot rename") && Catch::Contains(file) &&
                               !Catch::Contains("Success"));
      CHECK_THAT(e.what(),
                 Catch::Contains("Is a directory") || Catch::Contains("Directory not empty"));
    }
    for (const auto& f : std::filesystem::directory_iterator(dir.path))
      CHECK(f.path().extension() != ".tmp");  // the written file removed
  }
  SECTION("a file of another table under this table's name is stale") {
    InfluenceTableOptions other = options;
    other.join_depth = 0.5 * built.join_depth();
    const std::string other_file =
        InfluenceTableFile(dir.path.string(), InfluenceTableKey(gear.spec(), steel, other));
    std::filesystem::copy_file(file, other_file);
    const InfluenceTable t =
        LoadOrBuildInfluenceTable(gear, steel, other, dir.path.string(), &report);
    CHECK(report.outcome == CacheOutcome::kRebuilt);
    CHECK_THAT(report.message, Catch::Contains("stale: built for key"));
    CHECK(t.join_depth() == other.join_depth);
  }
}

TEST_CASE("Influence-table cache: the key follows what defines a table", "[unit][gear]") {
  const transmission::Scene scene = test::PaperScene();
  const geometry::GearSpec spec = scene.stage.sun;
  const ElasticMaterial steel{207e9, 0.3, 0.025, PlaneAssumption::kPlaneStrain};
  const InfluenceTableOptions o;
  const std::uint64_t key = InfluenceTableKey(spec, steel, o);
  auto differs = [&](geometry::GearSpec s, ElasticMaterial m, InfluenceTableOptions p) {
    return InfluenceTableKey(s, m, p) != key;
  };
  geometry::GearSpec s = spec;
  s.profile_shift += 1e-12;
  CHECK(differs(s, steel, o));
  s = spec;
  s.hub_radius *= 1.01;
  CHECK(differs(s, steel, o));
  s = spec;
  s.rack->tip_radius *= 1.01;
  CHECK(differs(s, steel, o));
  ElasticMaterial m = steel;
  m.plane = PlaneAssumption::kPlaneStress;
  CHECK(differs(spec, m, o));
  m = steel;
  m.poisson_ratio = 0.29;
  CHECK(differs(spec, m, o));
  InfluenceTableOptions p = o;
  p.mesh.refinement = 2;
  CHECK(differs(spec, steel, p));
  p = o;
  p.join_depth = 1e-3;
  CHECK(differs(spec, steel, p));
  p = o;
  p.join_depth_factor = 1.0 + 1e-12;
  CHECK(differs(spec, steel, p));
  // With an explicit h the factor is not used, and does not change the table.
  InfluenceTableOptions explicit_h = o, explicit_h_factor = o;
  explicit_h.join_depth = explicit_h_factor.join_depth = 1e-3;
  explicit_h_factor.join_depth_factor = 0.5;
  CHECK(InfluenceTableKey(spec, steel, explicit_h) ==
        InfluenceTableKey(spec, steel, explicit_h_factor));
  // Neither the name, the thickness error (the table is the nominal body's, NominalBody) nor the
  // solve batch changes the table.
  s = spec;
  s.name = "another name";
  s.thickness_error = -20e-6;
  p = o;
  p.batch = 7;
  CHECK_FALSE(differs(s, steel, p));
}
