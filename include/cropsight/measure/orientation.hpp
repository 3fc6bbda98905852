#pragma once
// The length axis of a potato seen from above (paper §3.5.2 and Table 4.3): inside a
// detector's box, widened by a margin, the potato is segmented and the angle of its long axis is
// measured, so that the gripper can close across it.
//
// Segmentation (OrientationSegmentation):
//   canny:  the paper's fast pipeline: grey, bilateral filter, Canny, then the largest closed
//           edge contour filled; on RGB the region's grey levels are first stretched to the full
//           range (canny_stretch_percent), so that the fixed thresholds hold on dim shots too;
//   kmeans: the paper's accurate pipeline: cv::kmeans with 2 clusters on the pixels' colour; the
//           potato is the cluster that holds fewer of the widened box's border pixels (the
//           margin puts background on the border);
//   ours:   one scalar per pixel that separates potato from background by a stated rule, Otsu's
//           threshold on it, on RGB a closing that bridges the gap a string crossing the potato
//           cuts, a morphological opening that removes strings and roots (thinner than the
//           opening), and the connected component nearest the box centre with its holes
//           filled. The scalar: on colourised depth, nearness decoded from the colour map's hue
//           (red = near ... blue = far; black = no depth = background), because the potato hangs
//           in front of everything else in its box; on RGB, the chroma distance (Lab a*, b*) from
//           the median colour of the box border, because the board is white or grey whatever the
//           light and shadows change lightness, not chroma.
// Axis (OrientationAxis):
//   pca:     principal axis of the mask's pixel centres;
//   ellipse: cv::fitEllipse on the mask's largest outer contour.
//
// Frames and units: image pixels, x right, y down, continuous coordinates (pixel (u, v) spans
// [u, u + 1) x [v, v + 1), as Detection2D). The angle is trigonometric: counter-clockwise from the
// image x axis as the image is viewed (so y up), in radians, in [0, π) — the axis has no head or
// tail.
#include <array>
#include <cstddef>
#include <string>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::measure {

enum class OrientationSegmentation { canny, kmeans, ours };
constexpr std::array<const char*, 3> config_names(OrientationSegmentation) { return {"canny", "kmeans", "ours"}; }
enum class OrientationAxis { pca, ellipse };
constexpr std::array<const char*, 2> config_names(OrientationAxis) { return {"pca", "ellipse"}; }
/// What the image is: a camera RGB image, or the RealSense colourised depth PNG used as an image
/// (near = red, far = blue, black = no depth), as the paper does.
enum class OrientationInput { rgb, depth };
constexpr std::array<const char*, 2> config_names(OrientationInput) { return {"rgb", "depth"}; }

/// Every parameter of the three segmentations and two axis fits. The paper (§3.5.2) names the
/// steps (bilateral filter, Canny, threshold; k-means with 2 clusters; PCA) but not their values,
/// so the defaults are documented choices, each saying why.
struct OrientationConfig {
  OrientationSegmentation segmentation = OrientationSegmentation::ours;
  OrientationAxis axis = OrientationAxis::pca;
  OrientationInput input = OrientationInput::depth;
  double box_margin = 0.15;  ///< fraction of the box's width (height) added left and right (top and bottom)
  // canny
  int bilateral_diameter = 9;
  double bilateral_sigma_color = 75, bilateral_sigma_space = 75;
  double canny_low = 50, canny_high = 150;
  int canny_close_iterations = 2;
  double canny_stretch_percent = 1.0;
  // kmeans
  int kmeans_attempts = 3;
  int kmeans_max_iterations = 10;
  double kmeans_epsilon = 1.0;
  int kmeans_seed = 22;
  // ours
  double ours_opening_fraction = 0.12;
  double ours_closing_fraction = 0.12;
  int ours_black_value = 40;
  /// ours: a root or string across the potato cuts its mask in two. Besides the part nearest the
  /// box centre, every part that lies mostly (>= 80 %) inside the detector's box and holds at least
  /// this fraction of that part's pixels is kept. 0 = the nearest part alone.
  double ours_part_fraction = 0.2;
  /// ours, input=depth: no-depth pixels inside the detector's box that survive an elliptic opening
  /// of this fraction of the box's smaller side, and whose component touches the potato mask, join
  /// it. 0 = off.
  double ours_no_depth_fill_fraction = 0.2;
  // all
  int border_px = 2;
  int min_mask_pixels = 30;

  template <class V>
  void visit(V& v) {
    v("segmentation", segmentation,
      "canny | kmeans | ours (see measure/orientation.hpp); paper Table 4.3: canny, kmeans");
    v("axis", axis, "pca | ellipse; paper: PCA; ellipse = cv::fitEllipse");
    v("input", input, "rgb | depth (the RealSense colourised depth PNG as an image); paper Table 4.3: both");
    v("box_margin", box_margin,
      "fraction of the box side added on each side before segmenting (paper: 'widened box', value not given; 0.15 "
      "keeps a background border around a detector box that cuts the potato)",
      Range::within(0.0, 2.0));
    v("bilateral_diameter", bilateral_diameter,
      "px; canny: cv::bilateralFilter neighbourhood (paper: bilateral filter, value not given; 9 = OpenCV's "
      "documented offline choice)",
      Range::within(1, 31));
    v("bilateral_sigma_color", bilateral_sigma_color, "grey levels; canny: bilateral filter range sigma (our choice)",
      Range::above(0));
    v("bilateral_sigma_space", bilateral_sigma_space, "px; canny: bilateral filter space sigma (our choice)",
      Range::above(0));
    v("canny_low", canny_low, "grey-level gradient; canny: hysteresis low threshold (our choice, 1:3 ratio)",
      Range::at_least(0));
    v("canny_high", canny_high, "grey-level gradient; canny: hysteresis high threshold (our choice)", Range::above(0));
    v("canny_close_iterations", canny_close_iterations,
      "canny: 3x3 dilations that close gaps in the edge contour before it is filled (our choice)",
      Range::within(0, 10));
    v("canny_stretch_percent", canny_stretch_percent,
      "percent; canny, input=rgb: the region's grey levels are stretched linearly so that this share of its pixels is "
      "0 and the same share 255 before the filter, so that the Canny thresholds mean one contrast whatever "
      "the exposure (0 = no stretch, the paper's plain pipeline)",
      Range::within(0.0, 49.0));
    v("kmeans_attempts", kmeans_attempts, "kmeans: cv::kmeans restarts, best compactness kept (our choice)",
      Range::within(1, 20));
    v("kmeans_max_iterations", kmeans_max_iterations, "kmeans: iterations per attempt (our choice)",
      Range::within(1, 1000));
    v("kmeans_epsilon", kmeans_epsilon, "colour levels; kmeans: stop when centres move less (our choice)",
      Range::above(0));
    v("kmeans_seed", kmeans_seed, "kmeans: seed of OpenCV's RNG before each run, for repeatable masks",
      Range::at_least(0));
    v("ours_opening_fraction", ours_opening_fraction,
      "fraction of the box's smaller side; ours: side of the elliptic opening that removes strings and roots "
      "(strings are ~4 px wide where potatoes are ~100 px; tuned on potato 1)",
      Range::within(0.0, 0.5));
    v("ours_closing_fraction", ours_closing_fraction,
      "fraction of the box's smaller side; ours, input=rgb: side of the elliptic closing, before the opening, that "
      "bridges "
      "the gap a string crossing the potato cuts into the mask (0 = none)",
      Range::within(0.0, 0.5));
    v("ours_black_value", ours_black_value,
      "grey level; ours, input=depth: pixels whose brightest channel is below this are 'no depth' (background)",
      Range::within(0, 255));
    v("ours_part_fraction", ours_part_fraction,
      "fraction of the central part's pixels; ours: other mask parts lying mostly inside the detector's box with at "
      "least this many pixels are the same potato cut by a root or string across it, and are kept; 0 = the part "
      "nearest the box centre alone (not in the paper)",
      Range::within(0.0, 1.0));
    v("ours_no_depth_fill_fraction", ours_no_depth_fill_fraction,
      "fraction of the box's smaller side; ours, input=depth: no-depth (black) pixels inside the detector's box that "
      "survive an elliptic opening of this side (strings and the sensor's shadow band beside the potato are thinner) "
      "and touch the potato mask are potato the sensor missed, and join it; 0 = off (not in the paper)",
      Range::within(0.0, 1.0));
    v("border_px", border_px,
      "px; width of the widened box's border that stands for background (kmeans cluster rule, ours on RGB)",
      Range::within(1, 50));
    v("min_mask_pixels", min_mask_pixels, "px; fewer mask pixels = no estimate (ok = false)", Range::at_least(5));
  }
};

/// The long axis of a mask.
struct AxisEstimate {
  bool ok = false;         ///< false: too few pixels, or no contour to fit
  double angle_rad = 0;    ///< trigonometric, [0, π)
  double major_px = 0;     ///< full length of the long axis, px (pca: 4 sqrt(λ1), exact for a filled ellipse)
  double minor_px = 0;     ///< full length of the short axis, px
  std::size_t pixels = 0;  ///< mask pixels used
  /// How well the angle is defined, in [0, 1]: 1 − (minor / major)², i.e. 1 − λ2 / λ1 of the second
  /// moments (pca) or of the fitted ellipse's axes. 0 = a disc, whose long axis is any direction
  /// (the gripper may close at any angle); a 4:3 potato gives 0.44, a 2:1 one 0.75. A consumer
  /// that must trust the angle compares this with its own threshold.
  double confidence = 0;
};

/// One potato's orientation.
struct OrientationResult : AxisEstimate {
  GrayImage mask;            ///< the widened, clipped box; 255 = potato, 0 = not
  int roi_x = 0, roi_y = 0;  ///< image pixel of mask pixel (0, 0)
};

/// The pixels estimate_orientation reads for `box` in a `width` x `height` image: [x0, x1) x
/// [y0, y1), the pixels whose span meets the box widened by cfg.box_margin (and by `pad_px` more on
/// each side), clipped to the image; empty (x1 <= x0 or y1 <= y0) when it lies outside.
struct PixelRegion {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
PixelRegion orientation_region(const Detection2D& box, const OrientationConfig& cfg, int width, int height,
                               int pad_px = 0);

/// Segments the potato in `box` (widened by cfg.box_margin, clipped to the image) and measures its
/// long axis. Throws Error(where, ...) for an empty image, an empty or non-finite box, a box
/// outside the image, or (input = depth) an image that is grey, not a colourised depth map.
OrientationResult estimate_orientation(const ColorImage& image, const Detection2D& box, const OrientationConfig& cfg,
                                       const std::string& where = "image");

/// The potato mask of an already cropped region (255 = potato) by cfg.segmentation on cfg.input.
GrayImage segment_potato(const ColorImage& roi, const OrientationConfig& cfg);

/// The long axis of `mask` (non-zero = inside) by `axis`; pixel centres at (u + 0.5, v + 0.5).
AxisEstimate mask_axis(const GrayImage& mask, OrientationAxis axis, int min_pixels = 5);

/// Errors of the config's fields (Range) and between them (canny_low ≤ canny_high).
void validate(const OrientationConfig& cfg, const std::string& where = "config");

}  // namespace cropsight::measure
