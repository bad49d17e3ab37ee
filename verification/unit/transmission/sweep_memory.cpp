// The memory a quasi-static sweep keeps per position (transmission::ResultBytes) and the refusal
// of a sweep whose results the machine cannot hold (CheckSweepMemory): on the paper's stage, one
// solved position's bytes against the contact problem it holds, and the largest sweep allowed by
// a given memory against the one position more that is refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

#include "epicycle/transmission/quasistatic.hpp"
#include "fe_fixtures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;

TEST_CASE("a sweep whose results exceed half the memory is refused with the estimate",
          "[unit][transmission]") {
  const transmission::Scene scene = test::PaperScene();
  const geometry::Stage stage(scene.stage);
  const transmission::StageModel model(stage, test::Compliance("paper_stage.toml"),
                                       transmission::SetupFromScene(scene));
  const transmission::PositionResult r =
      transmission::SolvePosition(model, 0.0, scene.loads, transmission::QuasiStaticOptions{});
  REQUIRE(r.converged);
  // At least the N×N compliance of its problem and the result itself; the rest (contacts, local
  // terms, labels, equalities) is O(N): well below a further N² doubles for N of about 30.
  const std::size_t n = r.problem.contacts.size();
  const std::size_t floor_bytes = n * n * sizeof(double) + sizeof(transmission::PositionResult);
  const std::size_t bytes = transmission::ResultBytes(r);
  CHECK(bytes >= floor_bytes);
  CHECK(bytes <= floor_bytes + n * n * sizeof(double) + 64 * n * sizeof(double) + 4096);
  // With 1 GB of memory, at most floor(0.5 GB / bytes) positions.
  const std::size_t memory = 1000000000, most = 500000000 / bytes;
  CHECK_NOTHROW(transmission::CheckSweepMemory(r, most, memory));
  try {
    transmission::CheckSweepMemory(r, most + 1, memory);
    FAIL("not refused");
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    CHECK_THAT(m, Catch::Matchers::Contains("a sweep of " + std::to_string(most + 1) +
                                            " positions keeps about 0.5 GB"));
    CHECK_THAT(m, Catch::Matchers::Contains(std::to_string(n) + " potential contacts"));
    CHECK_THAT(m, Catch::Matchers::Contains("at most " + std::to_string(most) + " positions"));
  }
  CHECK(transmission::AvailableMemoryBytes() > 0);
}
