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

double StageTimer::ms(const std::string& name) const {
  for (const auto& s : stages_)
    if (s.name == name) return s.total_ms;
  return 0.0;
}

StageTimer StageTimer::since(const std::vector<Stage>& earlier) const {
  StageTimer out;
  for (const auto& s : stages_) {
    Stage d = s;
    for (const auto& e : earlier)
      if (e.name == s.name) d.total_ms -= e.total_ms, d.count -= e.count;
    if (d.count > 0) out.stages_.push_back(std::move(d));
  }
  return out;
}

std::vector<StageMs> per_frame_ms(const std::vector<StageTimer::Stage>& stages, long frames) {
  std::vector<StageMs> out;
  for (const auto& s : stages) out.push_back({s.name, frames > 0 ? s.total_ms / double(frames) : 0.0});
  return out;
}

}  // namespace cropsight
