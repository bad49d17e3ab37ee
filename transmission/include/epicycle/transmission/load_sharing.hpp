// The load-sharing read-out of the paper (eq. 4), one definition for the quasi-static driver
// (StageModel::LoadSharing) and the dynamic samples (dynamics::Simulate).
#pragma once

#include <vector>

namespace epicycle::transmission {

/// LSR_i = T_mesh,i / (−T_in) [-], per planet: the moment on the sun of planet i's sun-planet mesh
/// T_mesh,i [N·m] over the input torque T_in [N·m] on the sun, which those moments balance (hence
/// the sign). Ideal sharing: 1/n each.
std::vector<double> LoadSharingRatios(const std::vector<double>& sun_mesh_torques,
                                      double input_torque);

}  // namespace epicycle::transmission
