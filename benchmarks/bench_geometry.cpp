// Contact search of the whole paper stage at one position (6 meshes, both flanks, gap window
// 100 µm), and the rigid poses it needs. Reports the number of contacts found as a counter.
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"

using namespace epicycle;

namespace {

const geometry::Stage& PaperStage() {
  static const geometry::Stage stage = [] {
    std::ifstream in(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
    std::ostringstream s;
    s << in.rdbuf();
    return geometry::Stage(transmission::ParseScene(s.str(), "paper_stage.toml").stage);
  }();
  return stage;
}

void BM_StageContactSearch(benchmark::State& state) {
  const geometry::Stage& st = PaperStage();
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
BENCHMARK(BM_StageContactSearch)->Unit(benchmark::kMicrosecond);

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
  const geometry::GearSpec spec = PaperStage().spec().sun;
  for (auto _ : state) {
    geometry::Gear g(spec);
    benchmark::DoNotOptimize(&g);
  }
}
BENCHMARK(BM_GearGeneration)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
