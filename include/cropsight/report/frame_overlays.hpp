#pragma once
// The pictures the `detect` commands write with --overlay: what a pipeline found on one frame or
// image, drawn over what the camera saw, so that a user can look at results on data that has no
// ground truth. Pixels: x = column, y = row, origin top-left.
#include <string>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/pipeline/broccoli/frame_result.hpp"
#include "cropsight/pipeline/grape/frame_result.hpp"

namespace cropsight::report {

/// Broccoli heads on one frame: the colour image when the frame has one of the depth's size, else
/// the depth colour map (render.hpp: near red to far blue, heads stand out from the soil); each
/// accepted head's pixels tinted green with its box, the points of heads the temporal filter
/// predicted (tracked heads this frame missed) magenta.
ColorImage broccoli_frame_overlay(const RgbdFrame& frame, const pipeline::broccoli::FrameResult& result);

/// Grape bunches on one colour frame: each bunch's points (camera frame, metres) projected with
/// `camera` and coloured by the segmenter's label (berries purple, peduncle orange, leaf green,
/// others grey), the boxes used (bunch magenta, peduncle orange), each ROI green, and the cut
/// point as a white cross with its direction.
ColorImage grape_frame_overlay(const ColorImage& color, const CameraIntrinsics& camera,
                               const pipeline::grape::FrameResult& result);

/// A 2D detector's boxes with their class name and score (detect objects).
ColorImage detection_overlay(const ColorImage& image, const std::vector<Detection2D>& detections,
                             const std::vector<std::string>& class_names);

}  // namespace cropsight::report
