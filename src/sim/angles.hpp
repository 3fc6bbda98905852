#pragma once
// Angle constants of the simulators (one copy; five scene files had their own).
#include <numbers>

namespace cropsight::sim {
inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = std::numbers::pi / 180.0;  ///< radians per degree
}  // namespace cropsight::sim
