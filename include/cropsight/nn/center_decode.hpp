#pragma once
// The heads of nn::CenterNet / nn::CenterNetOnnx (one network run: CenterNet::heads,
// CenterNetOnnx::heads) decoded into the pixels of the image they were computed on: its boxes and
// its per-class masks. A caller that wants both (the broccoli detector's CNN proposals,
// `cropsight eval detector`) runs the network once and decodes twice.
//
// Frames and units: the image is w x h pixels; boxes are image pixels, continuous corners
// (core/detection2d.hpp); masks are w x h, 255 inside and 0 outside. The heads are at stride 4 of
// the letterboxed input (center_net.hpp): each box and each mask pixel is mapped back through that
// letterbox.
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/nn/center_net.hpp"

namespace cropsight::nn {

/// The boxes of `heads` (decoded as CenterNet::detect does: cfg's score threshold and top K, no
/// NMS) in the pixels of the image_w x image_h image the heads were computed on, highest score
/// first.
std::vector<Detection2D> boxes_from_heads(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w,
                                          int image_h);

/// The mask head mapped back to an image_w x image_h image, one mask per class: each pixel centre
/// through the letterbox into the head's cells (cfg.mask_upsampling: bilinear between the cell
/// centres around it, or the nearest cell), the scores of extra mask passes (cfg.mask_inputs)
/// averaged in; 255 where the score >= threshold (0..1), 0 elsewhere. A negative threshold uses
/// the model's per-class cfg.mask_threshold_values(). Throws Error("detector", ...) when a mask
/// head's size does not match its cells.
std::vector<GrayImage> masks_from_heads(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w,
                                        int image_h, float threshold = -1.0f);

/// masks_from_heads inside the boxes only: class c's mask is computed at the pixels its boxes of
/// class c touch (each box rounded out to whole pixels, clipped to the image) and is 0 elsewhere.
/// Inside a box a pixel is what masks_from_heads gives it (the same scores, at the image's own
/// resolution, so the box's pixels are its mask's resolution); the work is the boxes' area instead
/// of the whole image's, and a stray blob of mask score outside every box of its class is dropped.
/// `boxes` are image pixels (boxes_from_heads or Detector2D::detect on the same image).
std::vector<GrayImage> masks_in_boxes(const CenterNetHeads& heads, const CenterNetConfig& cfg,
                                      const std::vector<Detection2D>& boxes, int image_w, int image_h,
                                      float threshold = -1.0f);

}  // namespace cropsight::nn
