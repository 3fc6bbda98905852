#pragma once
// The classical potato detector ("classical" backend): colour foreground, optional
// range foreground, an opening that removes strings and roots, connected components, one box
// and one score per blob. Written for speed (a few ms per 416x416 image on one core).
//
// Colour: a potato's skin is a narrow cluster in CIELAB chroma (a*, b*) — yellow-brown, well
// away from the white sheets, grey window frames, dark clothes and blue objects that surround it,
// all of which sit near the neutral axis or on the other side of it. The cluster is a 2D Gaussian
// (mean and covariance of a*, b* in OpenCV's 8-bit Lab scale, 128 = neutral); a pixel is
// foreground when its Mahalanobis distance is below `max_colour_distance`. Lightness only bounds
// out black and blown-out pixels, because shading on a potato changes L far more than chroma.
// Defaults: the Gaussian fitted to the inner ellipses (70 % of the box) of the annotated potatoes
// of both shared real scenes: the 32 of the 11 detection images (about 1 m, in front of a sheet)
// and the 15 orientation shots (0.3 m, a white board; boxes drawn for this in
// data/potato-orientation-boxes). A fit on one scene alone misses the other's skin colour
// (docs/pipelines/potatoes.md, "Detection").
//
// Touching potatoes: a blob whose outline has a notch deeper than `split_concavity_depth` x its
// inscribed radius is cut from that notch to where the parts come out most convex, when both parts
// are nearly convex (two potatoes touching along a wide edge leave such notches but no neck in the
// distance transform; a ragged blob of clutter cut anywhere stays ragged).
//
// Score: a potato stands out from what is behind it (darker than the white sheet, lighter than a
// dark root chamber), while clutter of potato colour (wooden furniture, clothes in the room beside
// the sheet) is about as light as its surroundings; so the score weighs the blob's colour likelihood
// and convexity by how much its lightness differs from the background ring around it, either way
// (`contrast_scale`; 0 turns this off).
//
// Geometry: sizes are fractions of the image's shorter side, so the same preset serves 416x416
// crops and 640x480 frames at the same field of view.
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"

namespace cropsight::pipeline::potato {

struct BlobConfig {
  // Colour model: OpenCV 8-bit Lab (a*, b* offset by 128).
  double mean_a = 137.00;  ///< fitted on the shared images of both real scenes (see above)
  double mean_b = 153.19;
  double cov_aa = 15.22, cov_ab = 11.64, cov_bb = 43.22;
  double max_colour_distance = 3.0;  ///< Mahalanobis; 3 keeps 99 % of the fitted potato pixels
  /// A pixel's saturation, chroma / lightness (chroma: distance of (a*, b*) from the neutral
  /// (128, 128); both 8-bit Lab, compared in whole units), must reach this. The Gaussian is long
  /// towards neutral (shaded skin), which lets in a potato's own shadow on a white board at close
  /// range (saturation 0.12-0.14 there, the skin 0.2-0.4; the board 0.01): a shaded potato is dark
  /// but keeps its colour. 0 = off.
  double min_saturation = 0.13;
  int min_lightness = 20;   ///< 8-bit L; darker pixels (shadows, clothes) are background
  int max_lightness = 235;  ///< brighter ones (specular highlights of the sheet) too
  // Range foreground (used only when the input has metric depth).
  double depth_min_m = 0.2;      ///< the D415 returns nothing nearer; nearer returns are noise
  double depth_max_m = 1.2;      ///< beyond: the sheet / the room (harvest approach at 0.3-0.5 m)
  bool keep_depth_holes = true;  ///< pixels without depth keep their colour decision
  // Morphology and blob rules (fractions of the image's shorter side / of its area).
  double opening_fraction = 0.015;    ///< opening kernel side / short side; strings are ~0.7 % wide
  double closing_fraction = 0.01;     ///< closing kernel (fills eyes and dark spots), 0 = none
  double min_area_fraction = 0.0008;  ///< blobs smaller than this fraction of the image are dropped
  double max_aspect = 4.0;            ///< blob's rotated box long/short side above this = a bundle of roots
  double min_solidity = 0.6;          ///< part area / convex hull area
  double min_score = 0.05;            ///< detections below this score are not reported
  // Touching potatoes (see above); chosen on the 11 shared images (AP50 flat for depth 0.3-0.6).
  double split_concavity_depth = 0.5;     ///< notch depth / inscribed radius that splits; 0 = never
  double split_min_part_fraction = 0.15;  ///< each part holds at least this fraction of the blob
  double split_min_part_solidity = 0.9;   ///< each part is nearly convex (AP50 flat for 0-0.9)
  int split_max_depth = 2;                ///< cuts applied again to the parts: up to 2^depth potatoes
  // Contrast with the background ring (see above); AP50 flat for scales 3-10 on the shared images.
  double contrast_scale = 5.0;            ///< 8-bit L; logistic scale of |ring L - blob L|; 0 = off
  double contrast_ring_fraction = 0.012;  ///< ring width / short image side (5 px at 416)
  // Box completion over the depth surface (with metric depth only; see below).
  double depth_completion = 1.0;           ///< fraction of the box's sides it may grow beyond each; 0 = off
  double depth_completion_band_m = 0.05;   ///< m; within this of the blob's median depth
  double depth_completion_step_m = 0.01;   ///< m; largest depth step between neighbouring pixels
  double depth_completion_same_iou = 0.7;  ///< completed boxes overlapping more are one potato

  template <class V>
  void visit(V& v) {
    v("mean_a", mean_a, "8-bit Lab a*; potato skin colour mean (fitted on the 11 shared images)",
      Range::within(0, 255));
    v("mean_b", mean_b, "8-bit Lab b*; potato skin colour mean (fitted on the 11 shared images)",
      Range::within(0, 255));
    v("cov_aa", cov_aa, "(8-bit Lab)^2; variance of a* of the skin colour", Range::above(0));
    v("cov_ab", cov_ab, "(8-bit Lab)^2; covariance of a* and b* (the matrix must be positive definite)");
    v("cov_bb", cov_bb, "(8-bit Lab)^2; variance of b* of the skin colour", Range::above(0));
    v("max_colour_distance", max_colour_distance, "Mahalanobis distance; colour foreground threshold", Range::above(0));
    v("min_saturation", min_saturation,
      "ratio; smallest chroma / lightness of a potato pixel (chroma: distance of a*, b* from neutral 128, 128, 8-bit "
      "Lab): a shadow on a white board is as grey as the board; 0 = off (not in the paper)",
      Range::within(0, 10));
    v("min_lightness", min_lightness, "8-bit L; darker pixels are background", Range::within(0, 255));
    v("max_lightness", max_lightness, "8-bit L; brighter pixels are background", Range::within(0, 255));
    v("depth_min_m", depth_min_m, "m; nearer depth is background (D415 minimum range)", Range::at_least(0));
    v("depth_max_m", depth_max_m, "m; farther depth is background (the sheet and the room behind)", Range::above(0));
    v("keep_depth_holes", keep_depth_holes, "pixels without depth (0) keep their colour decision");
    v("opening_fraction", opening_fraction, "fraction of the short image side; opening kernel that removes strings",
      Range::within(0, 0.2));
    v("closing_fraction", closing_fraction, "fraction of the short image side; closing kernel, 0 = none",
      Range::within(0, 0.2));
    v("min_area_fraction", min_area_fraction, "fraction of the image area; smallest blob kept", Range::within(0, 1));
    v("max_aspect", max_aspect, "ratio; longest/shortest side of the blob's rotated box (before any split)",
      Range::at_least(1));
    v("min_solidity", min_solidity, "ratio; area / convex hull area of each part", Range::within(0, 1));
    v("split_concavity_depth", split_concavity_depth,
      "ratio; a blob splits at an outline notch deeper than this x its inscribed radius, 0 = never",
      Range::at_least(0));
    v("split_min_part_fraction", split_min_part_fraction, "ratio; smallest part of a split, as a fraction of the blob",
      Range::within(0, 0.5));
    v("split_min_part_solidity", split_min_part_solidity,
      "ratio; each part of a split must be at least this convex (area / convex hull area)", Range::within(0, 1));
    v("split_max_depth", split_max_depth, "count; levels of splitting (parts are split again), 0 = never",
      Range::within(0, 4));
    v("contrast_scale", contrast_scale,
      "8-bit L; score factor 1/(1 + exp(-|L_ring - L_blob|/scale)): a blob that stands out from its background ring, "
      "darker or lighter, 0 = off",
      Range::at_least(0));
    v("contrast_ring_fraction", contrast_ring_fraction,
      "fraction of the short image side; width of the background ring of the contrast factor", Range::within(0, 0.1));
    v("depth_completion", depth_completion,
      "fraction of the box's width/height; with metric depth, a blob's box grows over the depth surface connected "
      "to it (a shaded underside or dark end the colour model misses), up to this far beyond each side; 0 = off "
      "(not in the paper)",
      Range::within(0.0, 2.0));
    v("depth_completion_band_m", depth_completion_band_m,
      "m; depth completion keeps to pixels within this of the blob's median depth (not in the paper)",
      Range::above(0.0));
    v("depth_completion_step_m", depth_completion_step_m,
      "m; depth completion's largest depth step between neighbouring pixels (not in the paper)", Range::above(0.0));
    v("depth_completion_same_iou", depth_completion_same_iou,
      "IoU; completed boxes that overlap more are one potato, the better scored kept (not in the paper)",
      Range::within(0.0, 1.0).open_below());
    v("min_score", min_score, "score in [0, 1]; lower-scoring blobs are not reported", Range::within(0, 1));
  }
  /// Rules between fields (ranges are checked by check_config). Throws Error(where, ...).
  void validate(const std::string& where) const;
};

/// Implements Detector2D with one class, "potato". Score, in [0, 1] = mean colour likelihood of the
/// part's pixels (exp(-d²/2), d the Mahalanobis distance) × its solidity × the contrast factor
/// (mean 8-bit L of the background pixels within the ring around it against the part's own; 1
/// when the ring holds no background or contrast_scale = 0).
class BlobDetector final : public Detector2D {
 public:
  explicit BlobDetector(const BlobConfig& cfg = {});
  ~BlobDetector() override;
  std::vector<Detection2D> detect(const DetectorInput& in) override;
  std::vector<std::string> class_names() const override { return {"potato"}; }
  /// The foreground mask of the last detect() (255 = potato colour after morphology), for
  /// figures and tests; width x height of the last image.
  const GrayImage& last_mask() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::pipeline::potato
