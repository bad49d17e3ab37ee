// Linear isotropic elastic material of a 2D body: plane stress or plane strain, thickness b.
#pragma once

#include <string>

#include <Eigen/Core>

namespace epicycle::compliance {

/// How a 2D elastic body is idealised. The same choice must be made here (FE structural term) and
/// in the local contact term (solvers::PlaneAssumption); docs/compliance.md argues for plane strain
/// as the default of wide steel spur gears.
enum class PlaneAssumption { kPlaneStrain, kPlaneStress };

/// "plane strain" / "plane stress".
std::string ToString(PlaneAssumption plane);

/// Isotropic linear elastic material and the out-of-plane thickness of a 2D model.
///
/// Stress–strain law σ = D ε with σ = (σxx, σyy, τxy), ε = (εxx, εyy, γxy):
///
///   plane stress (σzz = 0):
///     D = E/(1−ν²) · [[1, ν, 0], [ν, 1, 0], [0, 0, (1−ν)/2]]
///   plane strain (εzz = 0, σzz = ν(σxx + σyy)):
///     D = E/((1+ν)(1−2ν)) · [[1−ν, ν, 0], [ν, 1−ν, 0], [0, 0, (1−2ν)/2]]
///
/// Plane strain equals plane stress with E' = E/(1−ν²) and ν' = ν/(1−ν).
struct ElasticMaterial {
  double youngs_modulus = 0.0;  ///< E [Pa], > 0 and finite
  double poisson_ratio = 0.0;   ///< ν [-], in [0, 0.5)
  double thickness = 0.0;       ///< b [m], face width of the 2D body, > 0 and finite
  PlaneAssumption plane = PlaneAssumption::kPlaneStrain;  ///< idealisation (default: see docs)

  /// @throws std::invalid_argument naming the field, its value and the rule when E ≤ 0,
  ///         ν ∉ [0, 0.5), b ≤ 0 or any of them is not finite.
  void Validate() const;

  /// D [Pa], the 3×3 matrix above.
  Eigen::Matrix3d ElasticityMatrix() const;

  /// The plane-stress-equivalent modulus E' [Pa]: E for plane stress, E/(1−ν²) for plane strain.
  double EffectiveModulus() const;
  /// The plane-stress-equivalent Poisson ratio ν' [-]: ν for plane stress, ν/(1−ν) for plane
  /// strain.
  double EffectivePoissonRatio() const;
};

}  // namespace epicycle::compliance
