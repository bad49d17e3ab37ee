// The gmsh mesher in builds without gmsh (EPICYCLE_WITH_GMSH=OFF): the class exists, Available()
// is false and BuildMesh throws, naming the build option.
#include <stdexcept>

#include "epicycle/compliance/gmsh_mesher.hpp"
#include "slit_mesh.hpp"

namespace epicycle::compliance {

bool GmshMesher::Available() { return false; }

std::string GmshMesher::LibraryVersion() { return ""; }

Mesh GmshMesher::BuildMesh(const Region&) const {
  throw std::invalid_argument(
      "gmsh mesher: this build of epicycle was not built with gmsh (EPICYCLE_WITH_GMSH=OFF); "
      "configure with -DEPICYCLE_WITH_GMSH=ON (needs libgmsh-dev) to use it, or use the mapped "
      "mesher");
}

namespace internal {

SlitMesh MeshSlitPolygon(const SlitInput&) {
  throw std::invalid_argument(
      "a root crack needs the gmsh mesher: this build of epicycle was not built with gmsh "
      "(EPICYCLE_WITH_GMSH=OFF); configure with -DEPICYCLE_WITH_GMSH=ON (needs libgmsh-dev)");
}

}  // namespace internal

}  // namespace epicycle::compliance
