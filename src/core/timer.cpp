#include "cropsight/core/timer.hpp"

namespace cropsight {

void StageTimer::add(const std::string& name, double ms) {
  for (auto& s : stages_) {
    if (s.name == name) {
      s.total_ms += ms;
      ++s.count;
      return;
    }
  }
  stages_.push_back({name, ms, 1});
}

double StageTimer::total_ms() const {
  double t = 0;
  for (const auto& s : stages_) t += s.total_ms;
  return t;
}

}  // namespace cropsight
