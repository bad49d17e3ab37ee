// Contact search of the whole paper stage at one position (6 meshes, both flanks, gap window
// 100 µm), and the rigid poses it needs, as generated (Arg 0) and with 10 µm parabolic tip relief
// on every gear and a class-6 set of sun pitch deviations (Arg 1: the relieved flanks' tip
// contacts take a Newton solve). Reports the number of contacts found as a counter. Gear
// generation: the paper's sun, and an undercut 12-tooth gear (its crossing found by scan and
// bisection).
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"

using namespace epicycle;

namespace {

geometry::StageSpec PaperSpec() {
  std::ifstream in(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
  std::ostringstream s;
  s << in.rdbuf();
  return transmission::ParseScene(s.str(), "paper_stage.toml").stage;
}

const geometry::Stage& PaperStage() {
  static const geometry::Stage stage(PaperSpec());
  return stage;
}

const geometry::Stage& ModifiedStage() {
  static const geometry::Stage stage = [] {
    geometry::StageSpec s = PaperSpec();
    s.sun.modification.tip = {10e-6, 37.0e-3, geometry::ReliefShape::kParabolic};
    s.planet.modification.tip = {10e-6, 52.5e-3, geometry::ReliefShape::kParabolic};
    s.ring.modification.tip = {10e-6, 136.5e-3, geometry::ReliefShape::kParabolic};
    s.sun.pitch_deviations = geometry::iso::RandomPitchDeviations(16, s.sun.module, 6, 1);
    return geometry::Stage(s);
  }();
  return stage;
}

void BM_StageContactSearch(benchmark::State& state) {
  const geometry::Stage& st = state.range(0) == 0 ? PaperStage() : ModifiedStage();
  geometry::ContactSearchOptions opt;
  opt.gap_window = 100e-6;
  const double phi = 0.37 * st.mesh_cycle();
  std::size_t found = 0;
  for (auto _ : state) {
    const geometry::StagePoses p = st.Poses(phi);
    found = 0;
    for (int i = 0; i < st.planets(); ++i) {
      for (auto kind : {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
        auto c = st.Contacts(p, i, kind, opt);
        found += c.size();
        benchmark::DoNotOptimize(c.data());
      }
    }
  }
  state.counters["contacts"] = static_cast<double>(found);
}
BENCHMARK(BM_StageContactSearch)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_OneMeshContactSearch(benchmark::State& state) {
  const geometry::Stage& st = PaperStage();
  const geometry::StagePoses p = st.Poses(0.37 * st.mesh_cycle());
  geometry::ContactSearchOptions opt;
  for (auto _ : state) {
    auto c = st.Contacts(p, 0, geometry::MeshKind::kPlanetRing, opt);
    benchmark::DoNotOptimize(c.data());
  }
}
BENCHMARK(BM_OneMeshContactSearch)->Unit(benchmark::kMicrosecond);

void BM_GearGeneration(benchmark::State& state) {
  geometry::GearSpec spec = PaperStage().spec().sun;
  if (state.range(0) == 1) {  // ISO 53 A tool, z = 12, x = 0: undercut
    spec.teeth = 12;
    spec.module = 4e-3;
    spec.pressure_angle = geometry::Rad(20.0);
    spec.profile_shift = 0;
    spec.tip_radius = 0;
    spec.tip_round_radius = 0;
    spec.hub_radius = 8e-3;
    spec.rack = geometry::RackCutter{5e-3, 4e-3, 1.52e-3};
  }
  if (geometry::Gear(spec).undercut() != (state.range(0) == 1)) state.SkipWithError("undercut?");
  for (auto _ : state) {
    geometry::Gear g(spec);
    benchmark::DoNotOptimize(&g);
  }
}
BENCHMARK(BM_GearGeneration)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
