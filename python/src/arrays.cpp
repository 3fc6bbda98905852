#include "arrays.hpp"

#include <cstring>

namespace cropsight::python {

namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// The argument as an array without conversion: anything else is a TypeError naming it.
py::array as_array(const py::handle& value, const std::string& name, const std::string& wanted) {
  if (!py::isinstance<py::array>(value))
    throw py::type_error(name + ": expected a numpy " + wanted + ", got " + describe(value));
  return py::reinterpret_borrow<py::array>(value);
}

// A C-contiguous array of T, copied by numpy only when the layout needs it; a different dtype is
// refused (a silent cast of depth or colour would hide a wrong input).
template <typename T>
py::array_t<T, py::array::c_style> checked(const py::array& a, const std::string& name, const std::string& wanted) {
  if (!a.dtype().is(py::dtype::of<T>())) throw py::type_error(name + ": expected a " + wanted + ", got " + describe(a));
  return py::array_t<T, py::array::c_style>::ensure(a);
}

}  // namespace

std::string describe(const py::handle& value) {
  if (py::isinstance<py::array>(value)) {
    const auto a = py::reinterpret_borrow<py::array>(value);
    return std::string(py::str(a.dtype())) + " array of shape " + shape_text(a);
  }
  return std::string(py::str(value.get_type().attr("__name__"))) + " object";
}

DepthImage depth_from_array(const py::handle& value, const std::string& name) {
  const std::string wanted = "uint16 array of shape (H, W) (raw depth units)";
  const py::array a = as_array(value, name, wanted);
  if (a.ndim() != 2 || a.shape(0) < 1 || a.shape(1) < 1)
    throw py::value_error(name + ": expected a " + wanted + ", got " + describe(a));
  const auto c = checked<std::uint16_t>(a, name, wanted);
  DepthImage img(int(c.shape(1)), int(c.shape(0)));
  std::memcpy(img.data.data(), c.data(), img.data.size() * sizeof(std::uint16_t));
  return img;
}

ColorImage color_from_array(const py::handle& value, const std::string& name) {
  const std::string wanted = "uint8 array of shape (H, W, 3) (RGB)";
  const py::array a = as_array(value, name, wanted);
  if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1)
    throw py::value_error(name + ": expected a " + wanted + ", got " + describe(a));
  const auto c = checked<std::uint8_t>(a, name, wanted);
  static_assert(sizeof(Rgb8) == 3);
  ColorImage img(int(c.shape(1)), int(c.shape(0)));
  std::memcpy(static_cast<void*>(img.data.data()), c.data(), img.data.size() * 3);
  return img;
}

std::vector<float> points_from_array(const py::handle& value, const std::string& name, int columns, int& rows) {
  const std::string wanted = "float32 or float64 array of shape (N, " + std::to_string(columns) + ")";
  const py::array a = as_array(value, name, wanted);
  if (a.ndim() != 2 || a.shape(1) != columns)
    throw py::value_error(name + ": expected a " + wanted + ", got " + describe(a));
  if (!a.dtype().is(py::dtype::of<float>()) && !a.dtype().is(py::dtype::of<double>()))
    throw py::type_error(name + ": expected a " + wanted + ", got " + describe(a));
  const auto c = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  rows = int(c.shape(0));
  return {c.data(), c.data() + c.size()};
}

Eigen::Vector3d vector3_from(const py::handle& value, const std::string& name) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 1 || a.shape(0) != 3)
    throw py::value_error(name + ": expected 3 numbers (x, y, z), got " + describe(value));
  return {a.at(0), a.at(1), a.at(2)};
}

py::array image_view(const DepthImage& image, py::handle owner) {
  return view(image.data.data(), {image.height, image.width}, owner);
}

py::object color_view(const ColorImage& image, py::handle owner) {
  if (image.empty()) return py::none();
  return view(reinterpret_cast<const std::uint8_t*>(image.data.data()), {image.height, image.width, 3}, owner);
}

py::array gray_view(const GrayImage& image, py::handle owner) {
  return view(image.data.data(), {image.height, image.width}, owner);
}

py::dict stage_ms_dict(const StageTimer& timer) {
  py::dict d;
  for (const auto& s : timer.stages()) d[py::str(s.name)] = s.total_ms;
  return d;
}

}  // namespace cropsight::python
