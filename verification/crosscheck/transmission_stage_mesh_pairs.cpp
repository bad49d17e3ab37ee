// Planet 1's meshes of a built stage as gear pairs on the stage's own tables (StageMeshPairs,
// mesh_stiffness.hpp): what method C's c_γ of a sliced stage's rating and the dynamic model's
// modal mesh stiffness take. The reference is the pair built from the scene on its own: the mesh's
// setup without the damage, a GearPair of its specs and an FePairCompliance whose tables are
// built (or read from the cache) for the pair from the healthy scene (ComputeHealthyMeshStiffness,
// the route `epicycle stiffness` takes for the healthy teeth beside a damaged run).
//
// Tolerance: none (==). Both sides hold the same tables' doubles (one key per body, the cache
// stores the doubles as computed) and run the same assembly and contact solves on them, so every
// operation is the same on the same operands; the one body whose table differs in its key is the
// cracked sun's (its stage table also tabulates fillet stresses, for placing the crack), and the
// fillet stresses are extra columns of the same FE solves, not a change of the compliance.
#include <catch2/catch.hpp>

#include <array>
#include <string>

#include "epicycle/transmission/mesh_stiffness.hpp"
#include "fe_fixtures.hpp"

using namespace epicycle;

namespace {

struct Built {
  transmission::Scene scene;
  geometry::Stage stage;
  transmission::FeStageCompliance compliance;
  explicit Built(const std::string& file)
      : scene(transmission::ParseScene(test::SceneText(file), file)),
        stage(scene.stage),
        compliance(scene, stage, test::CachedTables()) {}
};

}  // namespace

TEST_CASE(
    "A stage's mesh pair on the stage's tables shares them and equals the pair built from "
    "the healthy scene",
    "[crosscheck][transmission][mesh_stiffness]") {
  // A cracked sun (tooth 0, damaged rows beside its table) and a run-out planet 1.
  const Built b("paper_stage_runout_crack.toml");
  REQUIRE(b.compliance.tables().Damaged(transmission::kSunBody) != nullptr);
  const transmission::StageMeshPairs pairs(b.scene, b.stage, b.compliance);
  transmission::Scene healthy = b.scene;
  healthy.damage = {};
  const std::array<std::array<int, 2>, 2> bodies{
      {{transmission::kSunBody, transmission::PlanetBody(0)},
       {transmission::PlanetBody(0), transmission::kRingBody}}};
  const std::array<std::string, 2> names{"sun-planet1", "planet1-ring"};
  constexpr int kPositions = 6;
  std::array<double, 2> reference{};
  for (std::size_t m = 0; m < 2; ++m) {
    const transmission::StageMeshPairs::Mesh& mesh = *pairs.meshes()[m];
    CHECK(mesh.name == names[m]);
    CHECK(mesh.setup.damage.pits.empty());
    // Shared, not rebuilt: the stage's table objects themselves, without the crack's rows.
    for (int g = 0; g < 2; ++g) {
      CHECK(&mesh.compliance.tables().Table(g) == &b.compliance.tables().Table(bodies[m][g]));
      CHECK(mesh.compliance.tables().Damaged(g) == nullptr);
    }
    CHECK(mesh.compliance.tables().messages().empty());  // nothing built or read

    // The reference pair, from the scene.
    transmission::MeshPairSetup setup = transmission::MakeMeshPair(b.scene, &b.stage, names[m]);
    setup.damage = {};
    const geometry::GearPair pair(setup.spec);
    const transmission::FePairCompliance own(healthy, pair, test::CachedTables(), setup.gears);
    CHECK(mesh.setup.torque == setup.torque);
    CHECK(mesh.setup.gap_window == setup.gap_window);
    geometry::ContactSearchOptions search;
    search.gap_window = setup.gap_window;
    int compared = 0;
    for (int k = 0; k < 5; ++k) {
      const double angle = k * 2 * geometry::kPi / pair.gear1().teeth() / 5;
      const geometry::PairPoses poses = pair.Poses(angle);
      const auto contacts = pair.Contacts(poses, search);
      const Eigen::MatrixXd shared = mesh.compliance.Matrix(mesh.pair, poses, contacts);
      const Eigen::MatrixXd built = own.Matrix(pair, poses, contacts);
      REQUIRE(shared.rows() == built.rows());
      CHECK((shared.array() == built.array()).all());
      compared += static_cast<int>(contacts.size());
    }
    CHECK(compared > 5);  // at least one contact per pose on average: the matrices say something

    transmission::MeshStiffnessOptions opt;
    opt.positions = kPositions;
    const transmission::MeshStiffnessResult r =
        transmission::ComputeHealthyMeshStiffness(b.scene, setup, pair, test::CachedTables(), opt);
    REQUIRE(r.failed == 0);
    reference[m] = r.mean_stiffness / geometry::ContactFaceWidth(pair.gear1(), pair.gear2());
  }
  // Method C's c_γ [N/m²] and the modal mesh stiffness [N/m] over the same samples.
  const std::array<double, 2> c = transmission::MeanMeshStiffnessPerWidth(pairs, kPositions);
  const std::array<double, 2> k = transmission::MeanMeshStiffness(pairs, kPositions);
  for (std::size_t m = 0; m < 2; ++m) {
    CHECK(c[m] == reference[m]);
    const geometry::GearPair& pair = pairs.meshes()[m]->pair;
    CHECK(k[m] / geometry::ContactFaceWidth(pair.gear1(), pair.gear2()) == c[m]);
    // ISO 6336-1's c_γα of steel spur gears lies near 20 N/(mm·µm): the model's is of that order.
    CHECK(c[m] > 5e9);
    CHECK(c[m] < 5e10);
  }
}
