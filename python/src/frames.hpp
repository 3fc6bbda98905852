#pragma once
// Frames built from Python values (cropsight.Frame(...) and every process(depth=..., ...)).
#include <pybind11/pybind11.h>

#include "cropsight/core/rgbd_frame.hpp"

namespace cropsight::python {

namespace py = pybind11;

/// A frame from arrays: depth H×W uint16 (may be None for colour-only crops: then `color` gives
/// the size), colour H×W×3 uint8 or None, the camera (validated: cropsight.Error naming "camera"
/// for NaN or non-positive values), pose 3 numbers or None. The arrays' sizes must equal the
/// camera's (ValueError naming the argument).
RgbdFrame frame_from_arrays(const py::object& depth, const py::object& color, const CameraIntrinsics& camera, int index,
                            double timestamp, const py::object& pose);

/// The frame a process() call means: `frame` (a cropsight.Frame, used without a copy) or, when it
/// is None, the frame of the keyword arrays. A frame and arrays together are a TypeError.
/// Returns a pointer to the frame to use: `frame`'s own, or `storage` filled from the arrays.
const RgbdFrame& frame_argument(const py::object& frame, const py::object& depth, const py::object& color,
                                const py::object& camera, RgbdFrame& storage);

}  // namespace cropsight::python
