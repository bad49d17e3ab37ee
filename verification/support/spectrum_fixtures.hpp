// A stage's rotation frequencies from its teeth alone (ring fixed, planets equally spaced and
// (z_s + z_r)/n whole), for the tests of the characteristic lines and their plots, without a
// geometry: f_c = f_s z_s/(z_s + z_r), f_m = z_r f_c, f_s − f_c, f_m/z_p (docs/model.md §9
// "Fault frequencies").
#pragma once

#include "epicycle/dynamics/spectrum.hpp"

namespace epicycle::test {

inline dynamics::StageFrequencies KinematicFrequencies(int z_s, int z_p, int z_r, int planets,
                                                       double sun_hz) {
  dynamics::StageFrequencies f;
  f.sun_teeth = z_s;
  f.planet_teeth = z_p;
  f.ring_teeth = z_r;
  f.planets = planets;
  f.symmetric = (z_s + z_r) % planets == 0;
  f.sun = sun_hz;
  f.carrier = sun_hz * z_s / (z_s + z_r);
  f.mesh = z_r * f.carrier;
  f.sun_relative = sun_hz - f.carrier;
  f.planet_relative = f.mesh / z_p;
  return f;
}

}  // namespace epicycle::test
