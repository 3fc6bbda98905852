#pragma once
// FrameBuffers <-> RgbdFrame (the library's frame), shared by the bridge's runners and sequence I/O.
#include <string>

#include "cropsight/bridge/frame_buffers.hpp"
#include "cropsight/core/rgbd_frame.hpp"

namespace cropsight::bridge {

/// R G B bytes (width*height*3) <-> the library's colour image.
ColorImage color_from_rgb(const std::vector<std::uint8_t>& rgb, int width, int height);
std::vector<std::uint8_t> rgb_from_color(const ColorImage& color);

CameraIntrinsics to_intrinsics(const CameraModel& c);
CameraModel to_camera_model(const CameraIntrinsics& c);
/// Validates the camera and the buffer sizes; throws Error("frame N", ...) naming the problem.
RgbdFrame to_rgbd_frame(const FrameBuffers& f);
FrameBuffers to_frame_buffers(const RgbdFrame& f);

}  // namespace cropsight::bridge
