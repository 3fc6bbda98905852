#pragma once
// Growing a region over a depth surface: the one flood fill that the potato position (the
// silhouette past a box) and the classical detector (a box completed over the potato's depth)
// share. Header-only: the callers' predicates inline.
#include <cmath>
#include <utility>
#include <vector>

#include "cropsight/core/image.hpp"

namespace cropsight::measure {

/// Grows from the pixels on `stack` (already marked by the caller) to their 8-neighbours inside
/// [u0, u1) x [v0, v1) whose depth (metres) differs by at most `step` from the pixel they are
/// reached from, that `admit(u, v)` accepts and that `mark(u, v)` newly marks (it returns false for
/// a pixel already in the region). Each newly marked pixel is grown from in turn; `stack` ends empty.
template <class Admit, class Mark>
void flood_depth(const Image<float>& depth_m, int u0, int v0, int u1, int v1, float step,
                 std::vector<std::pair<int, int>>& stack, Admit&& admit, Mark&& mark) {
  while (!stack.empty()) {
    const auto [u, v] = stack.back();
    stack.pop_back();
    const float d = depth_m.at(u, v);
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du) {
        const int uu = u + du, vv = v + dv;
        if (uu < u0 || vv < v0 || uu >= u1 || vv >= v1 || !admit(uu, vv)) continue;
        if (std::abs(depth_m.at(uu, vv) - d) <= step && mark(uu, vv)) stack.emplace_back(uu, vv);
      }
  }
}

}  // namespace cropsight::measure
