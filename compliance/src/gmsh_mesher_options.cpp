// The gmsh mesher's options and constructor, the same in builds with and without gmsh.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "epicycle/compliance/gmsh_mesher.hpp"

namespace epicycle::compliance {

void GmshMesherOptions::Validate() const {
  if (algorithm != 5 && algorithm != 6) {
    throw std::invalid_argument(
        "GmshMesherOptions.algorithm = " + std::to_string(algorithm) +
        ": must be 6 (Frontal-Delaunay) or 5 (Delaunay), gmsh's 2D triangle algorithms that are "
        "recombined into quadrilaterals");
  }
  auto check = [](const char* field, double value) {
    if (!std::isfinite(value) || value <= 0.0 || value >= 1e-3) {
      std::ostringstream msg;
      msg << "GmshMesherOptions." << field << " = " << value
          << ": must be finite, > 0 and < 1e-3 (relative to the region size)";
      throw std::invalid_argument(msg.str());
    }
  };
  check("merge_tolerance", merge_tolerance);
  check("corner_tolerance", corner_tolerance);
}

GmshMesher::GmshMesher(GmshMesherOptions options) : options_(options) { options_.Validate(); }

}  // namespace epicycle::compliance
