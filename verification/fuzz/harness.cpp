#include "harness.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
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

namespace {

// Every subcommand of `app`, nested ones included.
void AllSubcommands(CLI::App* app, std::vector<CLI::App*>* out) {
  for (CLI::App* sub : app->get_subcommands([](CLI::App*) { return true; })) {
    out->push_back(sub);
    AllSubcommands(sub, out);
  }
}

// The parsed subcommands of `app`, nested ones included.
void ParsedSubcommands(const CLI::App* app, std::vector<const CLI::App*>* out) {
  for (const CLI::App* sub : app->get_subcommands()) {
    out->push_back(sub);
    ParsedSubcommands(sub, out);
  }
}

// The program's command line with no command behind it: each callback replaced by nothing.
CLI::App& Program() {
  static CLI::App* app = [] {
    auto* a = new CLI::App("epicycle");
    app::RegisterCommands(*a);
    std::vector<CLI::App*> subs;
    AllSubcommands(a, &subs);
    for (CLI::App* sub : subs) sub->callback([] {});
    return a;
  }();
  return *app;
}

}  // namespace

void FuzzOptions(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kMaxArgs = 64, kMaxArg = 256;
  std::vector<std::string> args{"epicycle"};
  std::string arg;
  for (std::size_t i = 0; i <= size; ++i) {
    if (i == size || data[i] == '\n') {
      if (arg.size() > kMaxArg || args.size() >= kMaxArgs) return;
      args.push_back(arg);
      arg.clear();
    } else {
      arg.push_back(static_cast<char>(data[i]));
    }
  }
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  CLI::App& app = Program();
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {  // usage errors, --help and --version
    return;
  } catch (const std::invalid_argument&) {  // an option outside its range (app/options.hpp)
    return;
  }
  std::vector<const CLI::App*> parsed;
  ParsedSubcommands(&app, &parsed);
  for (const CLI::App* sub : parsed)
    for (const CLI::Option* opt : sub->get_options()) {
      const std::string type = opt->get_type_name();
      if (type.find("FLOAT") == std::string::npos && type.find("INT") == std::string::npos)
        continue;
      for (const std::string& r : opt->results()) {
        char* end = nullptr;
        const double v = std::strtod(r.c_str(), &end);
        if (!r.empty() && end == r.c_str() + r.size() && !std::isfinite(v))
          Finding("a numeric option accepted a value that is not finite");
      }
    }
}

}  // namespace epicycle::fuzz
