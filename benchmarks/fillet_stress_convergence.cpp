// Mesh convergence of the root stress (docs/model.md §9): the largest tensile and compressive
// fillet stress σ_tt of a gear body under one normal flank load, for the influence tables' default
// mesh and meshes refined uniformly ([model] mesh_refinement 2, 3) and along the fillet alone
// (GearMeshOptions::fillet_elements 10, 20). The load: 1000 N along the inward normal at three
// quarters of the flank grid of tooth 0's σ = +1 flank (near the outer point of single contact).
//
//   build/benchmarks/fillet_stress_convergence SCENE [GEAR]
// SCENE a pair or stage scene; GEAR gear1 or gear2 of a pair, sun, planet or ring of a stage
// (default: gear1, or the sun).
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"

using namespace epicycle;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fillet_stress_convergence SCENE [GEAR]\n");
    return 2;
  }
  const transmission::Scene scene = transmission::ReadScene(argv[1]);
  const bool stage = scene.kind == transmission::SceneKind::kStage;
  const std::string which = argc > 2 ? argv[2] : (stage ? "sun" : "gear1");
  geometry::GearSpec spec;
  if (stage && (which == "sun" || which == "planet" || which == "ring")) {
    spec = which == "sun" ? scene.stage.sun : which == "planet" ? scene.stage.planet
                                                                : scene.stage.ring;
  } else if (!stage && (which == "gear1" || which == "gear2")) {
    spec = which == "gear1" ? scene.pair.gear1 : scene.pair.gear2;
  } else {
    std::fprintf(stderr, "fillet_stress_convergence: GEAR = '%s': must be %s\n", which.c_str(),
                 stage ? "sun, planet or ring" : "gear1 or gear2");
    return 2;
  }
  const geometry::Gear gear(spec);
  std::printf("%s, gear '%s' (z = %d, m = %.3f mm), 1000 N normal load on tooth 0\n",
              scene.name.c_str(), gear.name().c_str(), gear.teeth(), gear.module() * 1e3);
  std::printf("%-28s %9s %14s %14s\n", "mesh", "elements", "tension [MPa]", "compr. [MPa]");
  const std::vector<std::pair<int, int>> meshes = {{1, 5}, {1, 10}, {1, 20}, {2, 5}, {3, 5}};
  for (const auto& [refinement, fillet] : meshes) {
    compliance::GearMeshOptions o;
    o.refinement = refinement;
    o.fillet_elements = fillet;
    compliance::GearBodyMesh body = compliance::BuildGearMesh(gear, o);
    compliance::LinearElasticModel model(
        std::move(body.mesh),
        compliance::ElasticMaterial{scene.material.youngs_modulus, scene.material.poisson_ratio,
                                    spec.face_width, compliance::PlaneAssumption::kPlaneStrain});
    model.FixNodeSet("hub");
    model.Factorize();
    const int i = body.grid.num_points() * 3 / 4;
    Eigen::VectorXd f = model.ZeroLoads();
    model.AddNodalForce(body.grid_nodes[0][0][i], -1000.0 * body.grid.normal[i], &f);
    const Eigen::VectorXd u = model.Solve(f);
    double tension = 0.0, compression = 0.0;
    for (const char* set : {"fillet0+", "fillet0-"}) {
      const auto& edges = model.mesh().EdgeSet(set);
      for (int e = 0; e < static_cast<int>(edges.size()); ++e)
        for (double xi : {-1.0, 0.0, 1.0}) {
          const double s = model.SurfaceStress(u, set, compliance::EdgePoint{e, xi});
          tension = std::max(tension, s);
          compression = std::min(compression, s);
        }
    }
    std::printf("refinement %d, fillet %2d      %9d %14.3f %14.3f\n", refinement, fillet,
                model.mesh().num_elements(), tension / 1e6, compression / 1e6);
  }
  return 0;
}
