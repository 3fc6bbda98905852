#pragma once
// Training augmentation for the 2D detector: what lets a network trained from scratch
// on tens of images generalise. One call turns a sample into a new one, drawn from `draw`:
//   mosaic      (probability `mosaic`) the sample and three others of the pool, each shrunk to a
//               quarter of the frame, in a 2 x 2 grid (YOLOv4);
//   copy-paste  (probability `copy_paste`) up to `paste_max` labelled instances of another pool
//               image pasted at random places, through their class mask when both images have
//               masks, else as their box (Ghiasi et al. 2021, simple copy-paste);
//   scale/crop  a random zoom in [scale_min, scale_max] about a centre shifted by up to `shift`
//               of the frame, same output size, grey 114 outside;
//   flip        (probability `flip`) left-right mirror;
//   colour      brightness, contrast and saturation each scaled by a factor in [1 - a, 1 + a].
// Boxes follow every geometric step, are clipped to the frame and dropped when less than
// `min_visible` of their area remains or they become thinner than 2 pixels; masks follow too.
#include <cstdint>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/nn/center_net.hpp"

namespace cropsight::nn {

struct DetectionAugmentConfig {
  double mosaic = 0.3, copy_paste = 0.3, flip = 0.5;
  int paste_max = 3;
  double scale_min = 0.6, scale_max = 1.4, shift = 0.2;
  double brightness = 0.25, contrast = 0.25, saturation = 0.3;
  double min_visible = 0.35;

  template <class V>
  void visit(V& v) {
    v("mosaic", mosaic, "probability of a 2x2 mosaic", Range::within(0, 1));
    v("copy_paste", copy_paste, "probability of pasting instances of another image", Range::within(0, 1));
    v("flip", flip, "probability of a left-right flip", Range::within(0, 1));
    v("paste_max", paste_max, "count; instances pasted at most", Range::at_least(0));
    v("scale_min", scale_min, "zoom factor, smallest", Range::above(0));
    v("scale_max", scale_max, "zoom factor, largest", Range::above(0));
    v("shift", shift, "fraction of the frame the zoom centre moves at most", Range::within(0, 1));
    v("brightness", brightness, "amplitude of the brightness factor", Range::within(0, 1));
    v("contrast", contrast, "amplitude of the contrast factor", Range::within(0, 1));
    v("saturation", saturation, "amplitude of the saturation factor", Range::within(0, 1));
    v("min_visible", min_visible, "fraction of a box's area that must stay in the frame", Range::within(0, 1));
  }
};

/// What `train detector` reads from a preset and --set: detector.* (the network) and augment.*
/// (the augmentation above).
struct DetectorTrainingConfig {
  CenterNetConfig detector;
  DetectionAugmentConfig augment;
};

/// `values` read into both sections over their defaults. Throws Error(where, ...) on a key of
/// neither section (a key without its section, `mask_weight` for `detector.mask_weight`, would
/// otherwise be ignored without a word) or a bad value. Not validated: the caller sets the class
/// names and its options first.
DetectorTrainingConfig detector_training_config(const ConfigMap& values, const std::string& where);

/// A new sample from `s` (see above); `pool` supplies the mosaic and copy-paste images (may
/// hold `s` itself; an empty pool skips both). Deterministic in `draw`.
DetectionSample augment_detection(const DetectionSample& s, const std::vector<DetectionSample>& pool,
                                  const DetectionAugmentConfig& cfg, std::uint64_t draw);

}  // namespace cropsight::nn
