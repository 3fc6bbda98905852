#include "cropsight/tracking/field_transform.hpp"

#include <Eigen/LU>
#include <sstream>

#include "cropsight/core/error.hpp"

namespace cropsight::tracking {

FieldTransform FieldTransform::parse(const std::string& text, const std::string& where) {
  std::string s = text;
  for (char& c : s)
    if (c == ',') c = ' ';
  std::istringstream in(s);
  std::string axis;
  FieldTransform t;
  t.rotation.setZero();
  int row = 0;
  while (in >> axis) {
    if (row == 3) throw Error(where, "expects three axes such as 'x,-y,-z', got '" + text + "'");
    double sign = 1.0;
    if (axis.size() == 2 && (axis[0] == '-' || axis[0] == '+')) {
      sign = axis[0] == '-' ? -1.0 : 1.0;
      axis = axis.substr(1);
    }
    if (axis != "x" && axis != "y" && axis != "z")
      throw Error(where, "unknown axis '" + axis + "' in '" + text + "' (use x, y, z with an optional sign)");
    t.rotation(row, axis[0] - 'x') = sign;
    ++row;
  }
  if (row != 3) throw Error(where, "expects three axes such as 'x,-y,-z', got '" + text + "'");
  if (std::abs(t.rotation.determinant() - 1.0) > 1e-9)
    throw Error(where, "'" + text + "' is not a proper rotation (repeated axis or a mirror)");
  return t;
}

}  // namespace cropsight::tracking
