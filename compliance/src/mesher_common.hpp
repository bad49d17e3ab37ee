// What both meshers (mapped, gmsh) say about a Region: patch labels, points and the corner rule,
// so that their messages name things the same way.
#pragma once

#include <array>
#include <sstream>
#include <string>

#include <Eigen/Core>

#include "epicycle/compliance/mesher.hpp"

namespace epicycle::compliance::internal {

inline constexpr std::array<const char*, 4> kSideNames = {"bottom", "right", "top", "left"};

/// "patch 3 ('fillet')".
inline std::string PatchLabel(const Region& region, int p) {
  std::string s = "patch " + std::to_string(p);
  if (!region.patches[p].name.empty()) s += " ('" + region.patches[p].name + "')";
  return s;
}

/// "(x, y) m" with 9 significant digits.
inline std::string Point(const Eigen::Vector2d& x) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << x.x() << ", " << x.y() << ") m";
  return s.str();
}

/// The first corner of patch p where two adjacent side curves do not meet within `tolerance` [m],
/// as a message naming the patch, the corner, both points and the rule; empty if all four meet.
inline std::string PatchCornerMismatch(const Region& region, int p, double tolerance) {
  const auto& s = region.patches[p].sides;
  struct CornerPair {
    int a;
    double ta;
    int b;
    double tb;
    const char* name;
  };
  const CornerPair pairs[4] = {{0, 0.0, 3, 0.0, "(u, v) = (0, 0)"},
                               {0, 1.0, 1, 0.0, "(u, v) = (1, 0)"},
                               {2, 0.0, 3, 1.0, "(u, v) = (0, 1)"},
                               {2, 1.0, 1, 1.0, "(u, v) = (1, 1)"}};
  for (const auto& c : pairs) {
    const Eigen::Vector2d xa = s[c.a](c.ta);
    const Eigen::Vector2d xb = s[c.b](c.tb);
    if ((xa - xb).norm() > tolerance) {
      std::ostringstream msg;
      msg << PatchLabel(region, p) << ": corner " << c.name << ": the " << kSideNames[c.a]
          << " side gives " << Point(xa) << " but the " << kSideNames[c.b] << " side gives "
          << Point(xb) << "; the rule is that the four sides meet at the corners (bottom(0) = "
          << "left(0), bottom(1) = right(0), top(0) = left(1), top(1) = right(1)) within "
          << tolerance << " m";
      return msg.str();
    }
  }
  return {};
}

}  // namespace epicycle::compliance::internal
