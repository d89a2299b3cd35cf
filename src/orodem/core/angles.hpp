// Angle constants shared by the measures, the calibration and the CLI.
#pragma once

#include <numbers>

namespace orodem {

inline constexpr double kPi = std::numbers::pi;           // [rad]
inline constexpr double kDeg = 180.0 / std::numbers::pi;  // degrees per radian [deg/rad]

}  // namespace orodem
