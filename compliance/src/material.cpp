#include "epicycle/compliance/material.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace epicycle::compliance {

std::string ToString(PlaneAssumption plane) {
  return plane == PlaneAssumption::kPlaneStrain ? "plane strain" : "plane stress";
}

void ElasticMaterial::Validate() const {
  auto fail = [](const char* field, double value, const char* rule) {
    std::ostringstream msg;
    msg.precision(12);
    msg << "ElasticMaterial." << field << " = " << value << ": " << rule;
    throw std::invalid_argument(msg.str());
  };
  if (!std::isfinite(youngs_modulus) || youngs_modulus <= 0.0) {
    fail("youngs_modulus", youngs_modulus, "Young's modulus E [Pa] must be finite and > 0");
  }
  // ν = 0.5 makes plane strain incompressible (D singular); ν < 0 is not a gear material.
  if (!std::isfinite(poisson_ratio) || poisson_ratio < 0.0 || poisson_ratio >= 0.5) {
    fail("poisson_ratio", poisson_ratio, "Poisson's ratio must lie in [0, 0.5)");
  }
  if (!std::isfinite(thickness) || thickness <= 0.0) {
    fail("thickness", thickness, "thickness b [m] must be finite and > 0");
  }
  if (plane != PlaneAssumption::kPlaneStrain && plane != PlaneAssumption::kPlaneStress) {
    fail("plane", static_cast<double>(static_cast<int>(plane)),
         "must be PlaneAssumption::kPlaneStrain or kPlaneStress");
  }
}

double ElasticMaterial::EffectiveModulus() const {
  return plane == PlaneAssumption::kPlaneStress
             ? youngs_modulus
             : youngs_modulus / (1.0 - poisson_ratio * poisson_ratio);
}

double ElasticMaterial::EffectivePoissonRatio() const {
  return plane == PlaneAssumption::kPlaneStress ? poisson_ratio
                                                : poisson_ratio / (1.0 - poisson_ratio);
}

Eigen::Matrix3d ElasticMaterial::ElasticityMatrix() const {
  const double e = youngs_modulus;
  const double nu = poisson_ratio;
  Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
  if (plane == PlaneAssumption::kPlaneStress) {
    const double c = e / (1.0 - nu * nu);
    d(0, 0) = c;
    d(1, 1) = c;
    d(0, 1) = c * nu;
    d(1, 0) = c * nu;
    d(2, 2) = c * (1.0 - nu) / 2.0;
  } else {
    const double c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
    d(0, 0) = c * (1.0 - nu);
    d(1, 1) = c * (1.0 - nu);
    d(0, 1) = c * nu;
    d(1, 0) = c * nu;
    d(2, 2) = c * (1.0 - 2.0 * nu) / 2.0;
  }
  return d;
}

}  // namespace epicycle::compliance
