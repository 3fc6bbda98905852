#pragma once
// Per-point class scores stored row-major (rows × classes): the label of each row is its
// largest score (the first on ties), as std::max_element picks.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace cropsight {

/// Argmax of every row of `scores` (rows × `classes`, row-major). `classes` must be > 0.
inline std::vector<int> argmax_rows(const float* scores, std::size_t rows, std::size_t classes) {
  std::vector<int> out(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    const float* r = scores + i * classes;
    out[i] = int(std::max_element(r, r + classes) - r);
  }
  return out;
}

}  // namespace cropsight
