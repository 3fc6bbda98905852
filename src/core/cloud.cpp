#include "cropsight/core/cloud.hpp"

#include "cropsight/core/error.hpp"

namespace cropsight {

void Cloud::validate(const std::string& where) const {
  const std::size_t n = points.size();
  if (!normals.empty() && normals.size() != n) throw Error(where, "normals count differs from point count");
  if (!colors.empty() && colors.size() != n) throw Error(where, "colour count differs from point count");
  if (!labels.empty() && labels.size() != n) throw Error(where, "label count differs from point count");
  for (std::size_t i = 0; i < n; ++i)
    if (!points[i].allFinite()) throw Error(where, "point " + std::to_string(i) + " is not finite");
}

}  // namespace cropsight
