#include "epicycle/transmission/load_sharing.hpp"

namespace epicycle::transmission {

std::vector<double> LoadSharingRatios(const std::vector<double>& sun_mesh_torques,
                                      double input_torque) {
  std::vector<double> lsr;
  lsr.reserve(sun_mesh_torques.size());
  for (double t : sun_mesh_torques) lsr.push_back(t / -input_torque);
  return lsr;
}

}  // namespace epicycle::transmission
