#pragma once
// Broccoli head sizing (Kusumam et al., "3D-vision based detection, localisation and sizing of
// broccoli heads in the field", §4.4).
//
// Two estimators of the head diameter from the head's 3D points (metres, camera frame: x right,
// y down, z forward; the camera looks straight down at the crop):
//
//  * bounding box: the width of the points along the camera x axis, max(x) - min(x). A head seen
//    from above shows its full width across the image, so this is the diameter unless leaves
//    hide an edge (then it underestimates) or noise adds outliers (then it overestimates).
//  * convex hull: the 3D convex hull of the points (our Quickhull, checked against qhull through PCL
//    in tests/measure/test_quickhull.cpp; `sizing.hull_engine: qhull` uses PCL's), the centroid of the hull
//    vertices, and the mean distance of the hull vertices to that centroid as the radius
//    (diameter = 2 × radius). Only the visible cap of the head is sampled, so the centroid
//    sits inside the cap and this estimator underestimates systematically (the paper reports a
//    median error of −22 mm); the bias correction below removes such offsets.
//
// Bias correction: d_corrected = scale · d + offset_mm, one (scale, offset) per estimator, learnt
// by a robust line fit from heads with measured diameters (fit_size_bias) and stored in the config
// (the keys sizing.bbox_scale, sizing.bbox_offset_mm, sizing.hull_scale, sizing.hull_offset_mm)
// or in a model file. The defaults (1, 0) leave the raw estimate unchanged, as in the paper.
//
// Harvestable: the chosen (corrected) diameter lies inside the market window
// [market_min_mm, market_max_mm].
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cropsight/core/config.hpp"

namespace cropsight {
struct OrganizedCloud;
}

namespace cropsight::measure {

enum class SizeEstimator { bounding_box, convex_hull };
/// Who builds the 3D hull: our allocation-free Quickhull (default, 4× faster on heads (bench_tracking)) or qhull
/// through pcl::ConvexHull (the library the paper used). Both give the same vertices except for
/// ties between exactly coplanar points; ours hands over to qhull when it cannot build a hull.
enum class HullEngine { quickhull, qhull };
HullEngine parse_hull_engine(const std::string& text, const std::string& where = "sizing.hull_engine");

/// Parses "bbox" / "bounding_box" / "hull" / "convex_hull"; throws Error(where, ...) otherwise.
SizeEstimator parse_size_estimator(const std::string& text, const std::string& where = "sizing.estimator");
const char* to_string(SizeEstimator e);

struct HeadSizeConfig {
  std::string estimator = "hull";         ///< which estimator gives `diameter_mm` (bbox | hull)
  bool compute_hull = true;               ///< false skips the hull (hull_mm stays 0) when only bbox is used
  std::string hull_engine = "quickhull";  ///< quickhull | qhull (see HullEngine)
  int min_points = 20;                    ///< heads with fewer valid points are not measured
  int hull_max_points = 500;              ///< > 0: the hull sees every k-th point so that at most this many remain
  bool hull_prefilter = true;             ///< organised clouds: qhull sees only the row/column hull candidates
  double bbox_scale = 1.0, bbox_offset_mm = 0.0;  ///< bias correction of the bounding box
  double hull_scale = 1.0, hull_offset_mm = 0.0;  ///< bias correction of the convex hull
  double market_min_mm = 100.0;                   ///< harvestable window, lower end
  double market_max_mm = 180.0;                   ///< harvestable window, upper end

  template <class V>
  void visit(V& v) {
    v("estimator", estimator,
      "bbox | hull; estimator behind diameter_mm and harvestable (paper: both, §4.4; default hull: the smaller error "
      "once bias-corrected, docs/pipelines/broccoli-sizing-tracking.md)");
    v("compute_hull", compute_hull, "bool; also run the convex-hull estimator for every head");
    v("hull_engine", hull_engine,
      "quickhull | qhull; our Quickhull (tested against qhull, 4x faster) or qhull via PCL (paper's library)");
    v("min_points", min_points, "points; heads with fewer valid points are not measured (not in the paper)",
      Range::at_least(1));
    v("hull_max_points", hull_max_points,
      "points; hull of an even subsample of at most this many points (default 500: the fast setting, a third to a "
      "half of the time at the same accuracy once the bias is fitted with the same value; "
      "docs/pipelines/broccoli-sizing-tracking.md); 0 = hull of all points (the paper's option)",
      Range::at_least(0));
    v("hull_prefilter", hull_prefilter,
      "bool; organised clouds: before qhull, drop points that are not vertices of their image row's and column's "
      "2D hull (exact for a pinhole deprojection, checked per head, else all points; not in the paper: speed)");
    v("bbox_scale", bbox_scale, "1; bias correction d' = scale*d + offset of the bounding box (paper: none, 1)",
      Range::above(0));
    v("bbox_offset_mm", bbox_offset_mm, "mm; bias correction offset of the bounding box (paper: none, 0)", Range{});
    v("hull_scale", hull_scale, "1; bias correction scale of the convex hull (paper: none, 1)", Range::above(0));
    v("hull_offset_mm", hull_offset_mm, "mm; bias correction offset of the convex hull (paper: none, 0)", Range{});
    v("market_min_mm", market_min_mm,
      "mm; smallest harvestable diameter (paper: market-dependent, not given; assumption 100 mm)", Range{});
    v("market_max_mm", market_max_mm,
      "mm; largest harvestable diameter (paper: market-dependent, not given; assumption 180 mm)", Range{});
  }
};

/// Size of one head in one frame. Raw values are the estimators' outputs; `diameter_mm` is the
/// bias-corrected value of the configured estimator.
struct HeadSize {
  bool valid = false;        ///< false when the head had fewer than min_points points
  int points = 0;            ///< valid points used
  double bbox_mm = 0.0;      ///< raw bounding-box width along camera x
  double hull_mm = 0.0;      ///< raw convex-hull diameter (0 when not computed)
  int hull_vertices = 0;     ///< vertices of the 3D hull (0 when not computed)
  double diameter_mm = 0.0;  ///< corrected diameter of the chosen estimator
  bool harvestable = false;  ///< diameter_mm inside the market window
};

/// max(x) - min(x) of the points, metres (0 for an empty set).
double bounding_box_width(const std::vector<Eigen::Vector3f>& points);

/// Convex-hull diameter, metres: 2 × mean distance of the 3D hull vertices to their centroid.
/// Degenerate sets (fewer than 4 points, or all coplanar so no 3D hull exists) fall back to
/// the mean distance of all points to their centroid. `vertices` (optional) receives the count
/// of hull vertices used (0 on fallback).
double convex_hull_diameter(const std::vector<Eigen::Vector3f>& points, int* vertices = nullptr,
                            HullEngine engine = HullEngine::quickhull);

/// Every k-th point (k = ceil(n / max_points)), so that at most max_points remain; all points when
/// max_points <= 0 or n <= max_points.
std::vector<Eigen::Vector3f> stride_subsample(const std::vector<Eigen::Vector3f>& points, int max_points);

/// Applies the configured estimators, bias correction and market window.
class HeadSizer {
 public:
  explicit HeadSizer(const HeadSizeConfig& cfg = {});
  const HeadSizeConfig& config() const { return cfg_; }
  SizeEstimator estimator() const { return estimator_; }
  HullEngine hull_engine() const { return engine_; }

  HeadSize measure(const std::vector<Eigen::Vector3f>& points) const;
  /// Measures the valid points of `cloud` at `indices` (pixel indices). With hull_prefilter (and
  /// hull_max_points 0) qhull sees only the points that are vertices of their image row's and
  /// column's 2D hull — the same hull vertices at ~1/10 of the points when the cloud is a pinhole
  /// deprojection (checked; src/measure/hull_candidates.hpp has the argument).
  HeadSize measure(const OrganizedCloud& cloud, const std::vector<int>& indices) const;
  /// Corrects a raw diameter (mm) of estimator `e`.
  double correct(SizeEstimator e, double raw_mm) const;
  /// Corrected diameter of the configured estimator from raw values (used for averaged tracks).
  double corrected(double bbox_mm, double hull_mm) const;
  bool harvestable(double diameter_mm) const;

 private:
  // `hull_candidates`: a subset holding every hull vertex of `points`, or null for all points.
  HeadSize measure_with(const std::vector<Eigen::Vector3f>& points,
                        const std::vector<Eigen::Vector3f>* hull_candidates) const;

  HeadSizeConfig cfg_;
  SizeEstimator estimator_;
  HullEngine engine_;
};

/// Correction truth = scale · estimate + offset (both mm), from the robust line estimate = a · truth
/// + b (Theil–Sen: median pairwise slope over pairs of different true diameters, median intercept;
/// the estimate carries the noise, so it is the dependent variable) inverted: scale = 1/a,
/// offset = −b/a. A few gross errors (merged clusters) do not tilt it, and the many pairs of one
/// head seen in several frames do not flatten it. Throws Error(where, ...) for fewer than 2 pairs,
/// unequal lengths, true diameters without spread, or estimates that do not grow with them.
struct BiasFit {
  double scale = 1.0, offset_mm = 0.0;
  int n = 0;
  double rms_before_mm = 0.0, rms_after_mm = 0.0;  ///< RMS error before / after correction
};
BiasFit fit_size_bias(const std::vector<double>& estimate_mm, const std::vector<double>& truth_mm,
                      const std::string& where = "size calibration");

}  // namespace cropsight::measure
