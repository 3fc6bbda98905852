#pragma once
// The state of the one target a harvest loop follows (TargetTracker, target_tracker.hpp): plain
// C++17, so that the potato pipeline's results reach the ROS nodes (built as C++17) as they are.
#include <array>

namespace cropsight::tracking {

enum class TargetState { selecting, detected, tracked, lost };
constexpr std::array<const char*, 4> config_names(TargetState) { return {"selecting", "detected", "tracked", "lost"}; }

}  // namespace cropsight::tracking
