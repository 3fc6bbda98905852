#pragma once
// The mask head of nn::CenterNet brought back to the pixels of the image it was computed on (the
// masks of center_decode.hpp and the threshold calibration of detector_eval.hpp read the same
// scores). Each image pixel centre is mapped through the letterbox into the head's cells; bilinear
// mixes the two cell centres around it per axis, nearest takes the cell under it.
#include <vector>

#include "cropsight/nn/center_net.hpp"

namespace cropsight::nn {

/// The mask head's cells around each image column and row, through the letterbox: the scores of
/// cells x0 and x1 mixed with weight wx on x1 (rows the same). Nearest: the cell under the pixel
/// twice, weight 0.
struct CellMap {
  std::vector<int> x0, x1, y0, y1;
  std::vector<float> wx, wy;
};

/// The mask scores of one image at its pixels, class by class and row by row: the main mask head's
/// and, with CenterNetConfig::mask_inputs, each extra pass's, each brought to the image through its
/// own letterbox and averaged (multi-scale test). Refers to `heads`, which must outlive it.
class MaskScores {
 public:
  /// Throws Error("detector", ...) when a mask head's size does not match its cells.
  MaskScores(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w, int image_h);

  /// Scores (0..1) of class c along image row v (image_w values, valid until the next call).
  const float* row(int c, int v);
  /// As row(), but only pixels [u0, u1) of the row are computed (0 <= u0, u1 <= image_w): the
  /// returned array is indexed by u as row()'s, and holds stale values outside the span.
  const float* span(int c, int v, int u0, int u1);

 private:
  struct Pass {
    CellMap cells;
    const float* mask = nullptr;
    int out_w = 0, out_h = 0;
  };
  void add(const std::vector<float>& mask, int out_w, int out_h, int input_w, int input_h, bool bilinear, int image_w,
           int image_h);
  int classes_;
  std::vector<Pass> passes_;
  std::vector<float> line_, row_;
};

}  // namespace cropsight::nn
