#pragma once
// The libtorch-free half of nn::CenterNet (include/cropsight/nn/center_net.hpp): the letterboxed
// input blob, the training targets (CenterNet's Gaussian centre heatmap, sizes, offsets, masks) and
// the decoding of the heads into boxes. Plain arrays, so that tests can check encoding and decoding
// on hand-made tensors and the OpenCV DNN path can decode the same heads. The public face of the
// decoding, boxes and masks in image pixels, is cropsight/nn/center_decode.hpp.
#include <cstdint>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/nn/center_net.hpp"
#include "nn/onnx_decode.hpp"

namespace cropsight::nn {

/// The heads' stride: one output cell is 4 x 4 input pixels.
inline constexpr int kCenterStride = 4;

/// The letterbox pad grey and the blob scaling: blob = RGB / 255, channel-major (3, H, W).
inline constexpr int kCenterPad = 114;

/// `image` letterboxed to input_w x input_h (Letterbox::fit, letterbox mode) as the network's
/// float blob; `lb` receives the geometry.
std::vector<float> center_blob(const ColorImage& image, int input_w, int input_h, Letterbox* lb);

/// The blob of the mirrored image: each row of each channel reversed. The letterbox is centred, so
/// this is the blob of the horizontally flipped image (up to a pixel of rounding in the padding).
std::vector<float> mirrored_blob(const std::vector<float>& blob, int input_w, int input_h);

/// Flip test (CenterNet's `flip_test`, CenterNetConfig::flip_test): `h` (heads of the image) averaged
/// with `mirrored` (heads of the mirrored blob) mirrored back: the centre heatmap, the sizes and the
/// mask scores; the sub-cell offsets stay `h`'s (CenterNet's code does the same). Throws Error when
/// the shapes differ.
void merge_mirrored_heads(CenterNetHeads& h, const CenterNetHeads& mirrored);

/// The mask head of `h` (the heads of an input_w x input_h blob) as an extra mask pass
/// (CenterNetConfig::mask_inputs); the other heads are dropped.
CenterNetHeads::MaskPass mask_pass(CenterNetHeads h, int input_w, int input_h);

/// One image's targets at the output resolution (ow x oh cells), channel-major like the heads.
struct CenterTargets {
  std::vector<float> heatmap;       ///< classes * oh * ow, Gaussian peaks (exactly 1 at a centre)
  std::vector<std::int64_t> index;  ///< max_objects: y * ow + x of each object's centre cell
  std::vector<float> size;          ///< max_objects * 2: (w, h) in cells
  std::vector<float> offset;        ///< max_objects * 2: centre minus its cell corner, in cells
  std::vector<float> reg_mask;      ///< max_objects: 1 for an object, 0 for padding
  std::vector<float> mask;          ///< classes * oh * ow in {0, 1}; empty = no mask supervision
};

/// CenterNet's Gaussian radius (gaussian_radius of its code, min_overlap 0.7): the largest
/// corner shift that keeps IoU >= min_overlap with a box of h x w cells (the three-case bound).
float gaussian_radius(float h, float w, float min_overlap = 0.7f);

/// Draws a Gaussian of `radius` (sigma = (2 radius + 1) / 6) centred on cell (cx, cy) into `hm`
/// (ow x oh), keeping the maximum with what is there.
void draw_gaussian(float* hm, int ow, int oh, int cx, int cy, int radius);

/// Targets of boxes given in input pixels (already letterboxed); boxes outside the output grid
/// or smaller than a pixel are skipped, at most max_objects are kept (in order). `masks` are
/// per-class masks already at the output resolution (ow x oh, non-zero = inside) or empty.
CenterTargets encode_targets(const std::vector<Detection2D>& input_boxes, const std::vector<GrayImage>& masks,
                             int classes, int ow, int oh, int max_objects);

/// Decoding: a cell is a peak of its class when its score is the maximum of its 3 x 3
/// neighbourhood (CenterNet's max-pool equality); peaks with score >= threshold, the top_k over
/// all classes by score (ties: lower class, then row-major cell first), each a box
/// ((x + dx) -/+ w / 2, (y + dy) -/+ h / 2) * stride in input pixels mapped back through `lb`.
/// Boxes that clipping empties are dropped. Highest score first.
std::vector<Detection2D> decode_heads(const CenterNetHeads& heads, const Letterbox& lb, float threshold, int top_k);

}  // namespace cropsight::nn
