#include "harness.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/studies/sampling.hpp"
#include "epicycle/studies/study.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::fuzz {

namespace {

// Inputs larger than any real file only slow the fuzzer down.
constexpr std::size_t kMaxBytes = 1 << 16;
// Problems up to the size of a 3-planet stage are solved; larger ones are only read.
constexpr long kMaxSolvedContacts = 60;

[[noreturn]] void Finding(const char* what) {
  std::fprintf(stderr, "epicycle fuzz finding: %s\n", what);
  std::abort();
}

}  // namespace

void FuzzScene(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxBytes) return;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const transmission::Scene scene = transmission::ParseScene(text, "fuzz.toml");
    if (scene.kind == transmission::SceneKind::kStage) {
      const geometry::Stage stage(scene.stage);
    } else {
      const geometry::GearPair pair(scene.pair);
    }
    for (const std::string& w : scene.warnings) {
      if (w.empty()) Finding("empty warning");
    }
  } catch (const std::invalid_argument&) {
    // Bad input, named: the expected outcome.
  }
}

void FuzzContactProblem(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxBytes) return;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const solvers::ContactProblemFile file = solvers::ParseContactProblemFile(text, "fuzz.json");
    const solvers::ContactProblem problem(file.data);
    if (problem.num_contacts() > kMaxSolvedContacts) return;
    auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
    solvers::ContactOptions options;
    options.max_iterations = 100;
    solvers::ContactSolution solution;
    const solvers::ContactReport report = solver->Solve(problem, options, &solution);
    if (report.status == solvers::ContactStatus::kConverged) {
      if (!solution.force.allFinite() || !solution.multiplier.allFinite())
        Finding("a converged solve with non-finite forces or multipliers");
      if ((solution.force.array() < 0).any()) Finding("a converged solve with a negative force");
    }
  } catch (const std::invalid_argument&) {
  }
}

void FuzzStudy(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxBytes) return;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const studies::StudySpec study =
        studies::ParseStudy(text, "fuzz.toml", EPICYCLE_SCENES_DIR "/studies");
    if (study.Cases() < 1) Finding("a study without cases");
    for (const long k : {0L, study.Cases() - 1}) {
      const std::vector<double> values = studies::SampleCase(study, k);
      if (values.size() != study.Columns().size()) Finding("a case without a value per column");
      for (double v : values)
        if (!std::isfinite(v)) Finding("a sampled value that is not finite");
    }
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace epicycle::fuzz
