#include "epicycle/transmission/run_arguments.hpp"

#include <stdexcept>

#include "epicycle/geometry/plane.hpp"

namespace epicycle::transmission {

std::vector<double> CheckedCarrierAngles(const std::string& name, const std::vector<double>& deg) {
  const auto count = static_cast<double>(deg.size());
  if (!kSweepPositions.Holds(count))
    throw std::invalid_argument(name + ": " + std::to_string(deg.size()) +
                                " angles: " + kSweepPositions.Describe());
  std::vector<double> rad;
  rad.reserve(deg.size());
  for (double d : deg) rad.push_back(geometry::Rad(CheckArgument(name, d, kCarrierAngleDeg)));
  return rad;
}

}  // namespace epicycle::transmission
