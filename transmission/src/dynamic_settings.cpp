// Rules of the dynamic model's settings (dynamic_settings.hpp).
#include "epicycle/transmission/dynamic_settings.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "epicycle/io/number_format.hpp"
#include "epicycle/io/units.hpp"

namespace epicycle::transmission {

void DynamicSettings::Validate() const {
  auto fail = [](const std::string& field, double v, const std::string& rule) {
    throw std::invalid_argument("dynamics: " + field + " = " + io::Num(v) + ": " + rule);
  };
  if (!std::isfinite(sun_speed) || !(sun_speed > 0))
    fail("sun_speed_rpm", io::RadPerSecondToRpm(sun_speed),
         "must be > 0 (the sun and the carrier are driven at a speed)");
  auto non_negative = [&](const std::string& field, double v) {
    if (!std::isfinite(v) || v < 0) fail(field, v, "must be finite and >= 0");
  };
  non_negative("carrier_load_inertia_kgm2", carrier_load_inertia);
  non_negative("mesh_damping_Ns_per_m", mesh_damping);
  non_negative("sun_bearing_damping_Ns_per_m", sun_bearing_damping);
  non_negative("planet_bearing_damping_Ns_per_m", planet_bearing_damping);
  non_negative("ring_damping_Ns_per_m", ring_damping);
  non_negative("ring_torsional_damping_Nms_per_rad", ring_torsional_damping);
  non_negative("carrier_stiffness_N_per_um", carrier_stiffness * 1e-6);
  non_negative("carrier_damping_Ns_per_m", carrier_damping);
  if (sun_speed_driven && !carrier_free)
    throw std::invalid_argument(
        "dynamics: sun = \"speed\" needs carrier = \"torque\": with both the sun and the "
        "carrier turned at prescribed speeds nothing carries the load");
  if (!(mesh_damping_ratio >= 0 && mesh_damping_ratio <= 1))
    fail("mesh_damping_ratio", mesh_damping_ratio, "must lie in [0, 1]");
  if (ring_elastic) {
    if (!(ring_stiffness >= 0) || !std::isfinite(ring_stiffness))
      fail("ring_stiffness_N_per_um", ring_stiffness * 1e-6,
           "must be >= 0 (0: the ring floats in translation)");
    if (!(ring_torsional_stiffness > 0) || !std::isfinite(ring_torsional_stiffness))
      fail("ring_torsional_stiffness_Nm_per_rad", ring_torsional_stiffness,
           "an elastic ring needs it > 0");
  }
  friction.Validate();
}

}  // namespace epicycle::transmission
