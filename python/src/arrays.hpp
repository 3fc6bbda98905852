#pragma once
// numpy ⇄ the library's images and points. Arrays coming in are checked here, so that every
// binding refuses a wrong one the same way: TypeError for a wrong dtype, ValueError for a wrong
// shape, each one line naming the argument, the shape and the dtype it got.
//
// The library's images own their pixels (core/image.hpp: a std::vector), so an array handed in
// is copied once into one (a memcpy: C-contiguous arrays are copied in one block, others element
// by element, which numpy does for us); frames read by cropsight.read_sequence already live in
// the library and go to a pipeline without any copy. Arrays going out are views on the result
// that owns them (read-only), not copies.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "cropsight/core/image.hpp"
#include "cropsight/core/timer.hpp"

namespace cropsight::python {

namespace py = pybind11;

/// "uint16 array of shape (424, 512)" / "float object" for error lines.
std::string describe(const py::handle& value);

/// H×W uint16 (raw depth units). `name` names the argument in errors.
DepthImage depth_from_array(const py::handle& value, const std::string& name);
/// H×W×3 uint8 (RGB).
ColorImage color_from_array(const py::handle& value, const std::string& name);
/// N×`columns` float32 or float64 (copied as float), C order or not.
std::vector<float> points_from_array(const py::handle& value, const std::string& name, int columns, int& rows);
/// A 3-vector (any real dtype).
Eigen::Vector3d vector3_from(const py::handle& value, const std::string& name);

/// A read-only view of `data` (shape, C order) kept alive by `owner`.
template <typename T>
py::array view(const T* data, std::vector<py::ssize_t> shape, py::handle owner) {
  py::array out(py::dtype::of<T>(), std::move(shape), {}, data, owner);
  py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return out;
}
/// A fresh array holding a copy of `v` (small results: centroids, positions).
inline py::array_t<double> vector_array(const Eigen::Vector3d& v) {
  py::array_t<double> out(3);
  for (int i = 0; i < 3; ++i) out.mutable_at(i) = v[i];
  return out;
}
inline py::array_t<double> vector_array(const Eigen::Vector3f& v) {
  return vector_array(Eigen::Vector3d(v.cast<double>()));
}
/// Depth, colour and label images as arrays viewing `image` (owned by `owner`).
py::array image_view(const DepthImage& image, py::handle owner);
py::object color_view(const ColorImage& image, py::handle owner);  ///< None when empty
py::array gray_view(const GrayImage& image, py::handle owner);
/// A result's wall-clock stages: {stage name: ms}, in the order they first ran.
py::dict stage_ms_dict(const StageTimer& timer);

}  // namespace cropsight::python
