#pragma once
// 3D position, metric size and ripeness of one 2D detection (the potato paper, §3.4 and §3.5.1).
//
// The paper deprojects the box centre with the camera intrinsics at the depth of the one centre
// pixel. Here the depth is by default the median of the valid pixels in a central window of the
// box (robust to the D415's holes and to a root crossing the centre); `sampling: centre_pixel`
// keeps the paper's reading. Camera frame: x right, y down, z forward, metres.
//
// The depth read at the box centre is the potato's front surface. The gripper needs the centre,
// which lies one semi-axis behind it along the view. `centre_offset: profile` (default) fits an
// ellipsoid cap to the visible surface inside the potato's silhouette (the pixels whose depth lies
// between just in front of the surface and one box length behind it): its centre's distance and its
// semi-axis along the view, i.e. the thickness the silhouette cannot show, from the surface's
// curvature. `silhouette` takes that semi-axis to be the silhouette's semi-minor axis (a round
// cross-section; the fallback when the fit fails or gives a thickness no potato has). `half_width`
// takes half the box's smaller side (wrong for a potato lying at an angle: the axis-aligned box is
// wider than the potato); `surface` keeps the paper's point. With `silhouette_grow` > 0 the
// silhouette also takes the depth region connected to it just beyond the box, so a box that cuts
// off an end of the potato does not cut its silhouette.
//
// Thread-safety: locate() may run on several threads at once (its scratch buffers are thread_local).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/measure/position_result.hpp"

namespace cropsight::measure {

enum class DepthSampling { median_window, centre_pixel };
constexpr std::array<const char*, 2> config_names(DepthSampling) { return {"median_window", "centre_pixel"}; }

enum class CentreOffset { silhouette, half_width, surface, profile };
constexpr std::array<const char*, 4> config_names(CentreOffset) {
  return {"silhouette", "half_width", "surface", "profile"};
}

/// The ray the centre lies on: through the box centre (paper) or through the silhouette's centroid.
enum class CentreRay { box, silhouette };
constexpr std::array<const char*, 2> config_names(CentreRay) { return {"box", "silhouette"}; }

struct PositionConfig {
  DepthSampling sampling = DepthSampling::median_window;
  double window_fraction = 0.3;      ///< window side as a fraction of the box's width and height
  int window_min_px = 3;             ///< smallest window side, pixels
  double min_depth_m = 0.25;         ///< D415's minimum usable range
  double max_depth_m = 3.0;          ///< farther depths are not trusted
  double min_valid_fraction = 0.25;  ///< of the window's pixels that must have a depth
  CentreOffset centre_offset = CentreOffset::profile;
  double silhouette_near_m = 0.01;  ///< silhouette pixels may lie this much in front of the surface depth
  int silhouette_min_px = 20;       ///< fewer silhouette pixels: fall back to half_width
  double silhouette_grow = 0.1;     ///< the silhouette may reach this fraction of the box's sides beyond it
  double silhouette_step_m = 0.01;  ///< largest depth step between neighbouring silhouette pixels, m
  int silhouette_opening_px = 5;    ///< > 1: opening of the silhouette (with silhouette_grow > 0), px
  CentreRay ray = CentreRay::silhouette;
  double profile_max_radius = 0.85;  ///< profile fit: pixels inside this normalised radius of the silhouette
  double profile_max_ratio = 1.5;    ///< profile fit: thickness within this factor of the silhouette's minor axis

  template <class V>
  void visit(V& v) {
    v("sampling", sampling,
      "median_window | centre_pixel; depth of the box centre: median of the valid pixels of a central window "
      "(ours) or the one centre pixel (paper §3.5.1)");
    v("window_fraction", window_fraction, "fraction of the box's width/height; median window side (not in the paper)",
      Range::within(0.0, 1.0).open_below());
    v("window_min_px", window_min_px, "px; smallest median window side (not in the paper)", Range::at_least(1));
    v("min_depth_m", min_depth_m, "m; depth_ok false nearer than this (D415 minimum range, about 0.25 m)",
      Range::at_least(0.0));
    v("max_depth_m", max_depth_m, "m; depth_ok false farther than this (not in the paper)", Range::above(0.0));
    v("min_valid_fraction", min_valid_fraction,
      "fraction; depth_ok false when fewer of the window's pixels have a depth (not in the paper)",
      Range::within(0.0, 1.0));
    v("centre_offset", centre_offset,
      "silhouette | profile | half_width | surface; report the potato's centre: surface depth + the silhouette's "
      "semi-minor axis (ours), the centre of the ellipsoid fitted to the visible surface (ours: its thickness "
      "from the surface's curvature), + half the box's smaller metric side (ours, older), or the surface point "
      "(paper)");
    v("silhouette_near_m", silhouette_near_m,
      "m; a box pixel belongs to the silhouette from this much in front of the surface depth (a root in front of "
      "the potato is nearer; not in the paper)",
      Range::at_least(0.0));
    v("silhouette_min_px", silhouette_min_px,
      "px; fewer silhouette pixels fall back to centre_offset half_width (not in the paper)", Range::at_least(3));
    v("silhouette_grow", silhouette_grow,
      "fraction of the box's width/height; > 0: the silhouette is the depth region connected to the median "
      "window, reaching up to this far beyond each side of the box (a box that cuts off part of the potato); 0: "
      "every in-band pixel of the box (not in the paper)",
      Range::within(0.0, 1.0));
    v("silhouette_opening_px", silhouette_opening_px,
      "px; with silhouette_grow > 0, an opening of this size removes strings, roots and sprouts from the silhouette; "
      "< 2 = none (not in the paper)",
      Range::at_least(0));
    v("silhouette_step_m", silhouette_step_m,
      "m; with silhouette_grow > 0, neighbouring silhouette pixels differ in depth by at most this (not in the "
      "paper)",
      Range::above(0.0));
    v("profile_max_radius", profile_max_radius,
      "fraction of the silhouette's equivalent ellipse; centre_offset profile fits the visible surface inside it "
      "(the rim's depth is noisy and often missing; not in the paper)",
      Range::within(0.0, 1.0).open_below().open_above());
    v("profile_max_ratio", profile_max_ratio,
      "factor; centre_offset profile keeps a fitted thickness within this factor of the silhouette's semi-minor "
      "axis, else falls back to silhouette (not in the paper)",
      Range::at_least(1.0));
    v("ray", ray,
      "box | silhouette; x and y: the ray through the box centre (paper) or through the centroid of the "
      "silhouette (ours; needs centre_offset silhouette)");
  }
  /// Rules between fields; throws Error(where, ...).
  void validate(const std::string& where) const;
};

/// Locates `box` in `depth_m` (metres, 0 = no depth, registered to the image the box is in).
/// Without usable depth, depth_ok is false and xyz/size stay 0.
Position3D locate(const Detection2D& box, const Image<float>& depth_m, const CameraIntrinsics& camera,
                  const PositionConfig& cfg = {});

/// Paper §3.4: a potato is ripe when its box area at its depth reaches the threshold.
struct RipenessConfig {
  double ripeness_threshold_m2 = 0.0;  ///< m²; paper RIPENESS_THRES

  template <class V>
  void visit(V& v) {
    v("ripeness_threshold_m2", ripeness_threshold_m2,
      "m^2; box area at the potato's depth a ripe potato reaches (paper RIPENESS_THRES = 0 in the authors' "
      "run_vision.py: every potato is ripe; e.g. 0.0025 = a 5 x 5 cm box)",
      Range::at_least(0.0));
  }
};

/// True when the position has usable depth and its box area reaches the threshold.
inline bool is_ripe(const Position3D& p, const RipenessConfig& cfg) {
  return p.depth_ok && double(p.area_m2) >= cfg.ripeness_threshold_m2;
}

/// Metric depth (m) of a raw depth image: value * camera.depth_scale, 0 stays 0.
Image<float> depth_in_metres(const DepthImage& depth, double depth_scale);

}  // namespace cropsight::measure
