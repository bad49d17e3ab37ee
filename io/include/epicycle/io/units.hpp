// Unit conversions shared by every layer: one expression for each, so that the same input gives
// the same bits wherever it is converted.
#pragma once

#include <numbers>

namespace epicycle::io {

/// ω per n: π/30 [rad/s per rpm] (one revolution per minute is 2π rad in 60 s).
inline constexpr double kRadPerSecondPerRpm = std::numbers::pi / 30.0;

/// ω [rad/s] of a speed n [rpm]: ω = n · (π/30); 30 rpm gives π exactly.
constexpr double RpmToRadPerSecond(double rpm) { return rpm * kRadPerSecondPerRpm; }
/// n [rpm] of a speed ω [rad/s]: n = 30 ω / π.
constexpr double RadPerSecondToRpm(double rad_per_second) {
  return rad_per_second * 30.0 / std::numbers::pi;
}

/// Revolutions per second [1/s] of a speed n [rpm]: n / 60.
constexpr double RpmToRevolutionsPerSecond(double rpm) { return rpm / 60.0; }

}  // namespace epicycle::io
