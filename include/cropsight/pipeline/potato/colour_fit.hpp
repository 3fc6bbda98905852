#pragma once
// Fits the classical detector's colour model (BlobConfig::mean_a … cov_bb) to annotated
// images: the a*, b* (OpenCV 8-bit Lab) of the pixels inside the inner ellipse of every box
// (axes `inner_fraction` of the box's half sides, so that the sheet, strings and the box's
// corners stay out). The shipped defaults are this fit on the 11 shared images; the tests refit it
// leaving one image out to measure the detector on an image the colour model never saw.
#include <cstdint>
#include <vector>

#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/pipeline/potato/blob_detector.hpp"

namespace cropsight::pipeline::potato {

struct ColourFit {
  double mean_a = 0, mean_b = 0, cov_aa = 0, cov_ab = 0, cov_bb = 0;  ///< 8-bit Lab units (squared)
  std::int64_t pixels = 0;
  /// Copies the model into `cfg` (the other fields untouched).
  void apply_to(BlobConfig& cfg) const;
};

/// boxes[i] are image i's boxes (pixels; corners as Detection2D). Throws Error when no pixel
/// falls inside any box.
ColourFit fit_potato_colour(const std::vector<const ColorImage*>& images,
                            const std::vector<std::vector<Detection2D>>& boxes, double inner_fraction = 0.7);

}  // namespace cropsight::pipeline::potato
