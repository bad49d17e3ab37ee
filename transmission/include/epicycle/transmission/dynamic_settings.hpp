// Settings of the dynamic model (docs/model.md §7) as the scene's [dynamics] and [lubricant]
// tables give them (docs/scenes.md), read once by the scene reader into these typed SI values;
// the dynamics layer builds its model from them and a command line may override them.
#pragma once

#include "epicycle/io/units.hpp"
#include "epicycle/transmission/friction.hpp"

namespace epicycle::transmission {

/// Settings of the dynamic model with their units. Defaults are the scene's defaults.
struct DynamicSettings {
  /// |ω_s| [rad/s], > 0 (scene: sun_speed_rpm, default 1500 rpm); the sun turns the way its input
  /// torque drives it.
  double sun_speed = io::RpmToRadPerSecond(1500.0);
  /// false: the sun carries the input torque T_s (its speed follows); true: the sun turns at
  /// exactly ω_s (speed-controlled, the input torque is the reaction; needs a free carrier).
  bool sun_speed_driven = false;
  bool carrier_free = false;          ///< false: carrier turned at ω_s z_s/(z_s + z_r)
  double carrier_stiffness = 0;       ///< k_c [N/m] of the carrier's bearing; 0: translation held
  double carrier_damping = 0;         ///< c_c [N·s/m]
  double carrier_load_inertia = 0;    ///< added to the carrier's inertia when free [kg·m²]
  double mesh_damping_ratio = 0.05;   ///< ζ [-], in [0, 1]
  double mesh_damping = 0;            ///< c_m [N·s/m]; > 0 replaces ζ
  double sun_bearing_damping = 0;     ///< c_s [N·s/m] (elastic sun)
  double planet_bearing_damping = 0;  ///< c_p [N·s/m] (elastic pins)
  bool ring_elastic = false;
  double ring_stiffness = 0;            ///< k_r [N/m]
  double ring_damping = 0;              ///< c_r [N·s/m]
  double ring_torsional_stiffness = 0;  ///< k_rt [N·m/rad]
  double ring_torsional_damping = 0;    ///< c_rt [N·m·s/rad]
  FrictionOptions friction;             ///< law, coefficient and lubricant

  /// Rules: ω_s finite and > 0; dampings, the carrier's stiffness and load inertia finite and
  /// ≥ 0; ζ in [0, 1]; a speed-driven sun needs a free carrier; an elastic ring needs k_r ≥ 0 and
  /// k_rt > 0; the friction options valid (FrictionOptions::Validate).
  /// @throws std::invalid_argument naming the field (its scene key), its value and the rule.
  void Validate() const;
};

}  // namespace epicycle::transmission
