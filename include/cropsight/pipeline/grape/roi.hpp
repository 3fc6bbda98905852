#pragma once
// Grape pipeline, stages 1-3 (Luo et al.): the region of interest of a bunch from its 2D
// detection and its peduncle's (Eq. 1), the coloured point cloud of that region (Algorithm 1),
// its normals and its unit-sphere normalisation (grape_roi_clouds: the whole of stages 1-3 on
// one frame). Pixels: x = column, y = row, origin top-left. Points: camera frame, metres.
#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <vector>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/cloud.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/geometry_types.hpp"
#include "cropsight/core/image.hpp"
#include "cropsight/pipeline/grape/frame_result.hpp"

namespace cropsight::pipeline::grape {

struct RoiConfig {
  int bunch_category = 1;     ///< COCO category id of bunches (dataset: 1)
  int peduncle_category = 2;  ///< COCO category id of peduncles (dataset: 2)
  float min_score = 0.5f;     ///< detections below are ignored
  double z_min = 0.001;       ///< m; nearest depth kept (paper: 0.001 m, Luo et al. Algorithm 1)
  double z_max = 3.0;         ///< m; farthest depth kept (paper: 3.0 m, Luo et al. Algorithm 1)
  int normal_k = 30;          ///< KNN-PCA normal neighbours (paper: 30, Luo et al. 2.3)

  template <class V>
  void visit(V& v) {
    v("bunch_category", bunch_category, "id; COCO category of grape bunches (dataset: 1)", Range::at_least(0));
    v("peduncle_category", peduncle_category, "id; COCO category of peduncles (dataset: 2)", Range::at_least(0));
    v("min_score", min_score, "1; detections with a lower score are ignored", Range::within(0, 1));
    v("z_min", z_min, "m; nearest depth kept (paper: 0.001 m, Luo et al. Algorithm 1)", Range::at_least(0));
    v("z_max", z_max, "m; farthest depth kept (paper: 3.0 m, Luo et al. Algorithm 1)", Range::above(0));
    v("normal_k", normal_k, "count; KNN-PCA normal neighbours (paper: 30, Luo et al. 2.3)",
      Range::within(3, kMaxNormalK, "a normal needs three points; a larger k makes KNN-PCA quadratic"));
  }

  /// Most normal neighbours accepted: a normal needs a local patch, and a k near the cloud size
  /// makes the KNN-PCA quadratic (normal_k = 10^8 ran for hours).
  static constexpr int kMaxNormalK = 1000;
  /// Throws Error(where, "'z_max' must be greater than 5 (z_min), got 1") for the first field out
  /// of the Range declared in visit(), or for the rules between fields: the two categories
  /// differ, z_min < z_max.
  void validate(const std::string& where) const;
};

/// Eq. 1: the ROI spanning a bunch box g and its peduncle box p:
/// X = X_g, Y = Y_p, W = W_g, H = Y_g + H_g - Y_p.
Box2D roi_from_boxes(const Box2D& bunch, const Box2D& peduncle);

/// ROIs of every bunch: each bunch is paired with the peduncle box whose horizontal centre lies
/// within the bunch's columns and whose top is above the bunch's top, nearest first (Eq. 1);
/// a bunch without a peduncle keeps its own box. Overlapping ROIs are then merged into their
/// union until none overlap. The result is clipped to the image (width × height).
std::vector<Box2D> grape_rois(const std::vector<Detection>& detections, int width, int height,
                              const RoiConfig& cfg = {});

/// Merges boxes that overlap (intersection area > 0) into their bounding union, repeatedly.
std::vector<Box2D> merge_overlapping(std::vector<Box2D> boxes);

/// Algorithm 1: deprojects every pixel of `roi` whose depth z satisfies z_min < z < z_max with
/// `cam`, attaching its colour scaled to [0, 1] (when `color` is non-empty, same size as depth).
/// Throws Error("roi cloud", ...) on size mismatch.
Cloud roi_cloud(const DepthImage& depth, const ColorImage& color, const CameraIntrinsics& cam, const Box2D& roi,
                const RoiConfig& cfg = {});

/// One ROI's cloud, ready for a grape segmentation model: coloured, KNN-PCA normals oriented to
/// the camera centre, normalised to the unit sphere, labels 0. p_m = p * scale + centroid maps a
/// point back to metres in the camera frame.
struct RoiCloud {
  Box2D box;
  Cloud cloud;
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  ///< m, camera frame
  float scale = 1.f;                                   ///< m per unit
};

/// A metric cloud (m, camera frame) made ready for a grape segmentation model as stage 3 makes
/// every ROI cloud: KNN-PCA normals oriented to the camera centre (cfg.normal_k neighbours, at
/// most the cloud size) unless it has normals, then the unit-sphere normalisation; labels 0.
RoiCloud segmenter_input(Cloud cloud, const RoiConfig& cfg = {});

/// Stages 1-3 of one RGB-D frame.
struct RoiFrame {
  std::vector<RoiCloud> rois;      ///< in grape_rois() order; ROIs with fewer than 3 points dropped
  std::vector<Detection> outside;  ///< bunch / peduncle detections wholly outside the image (skipped)
};

/// Stages 1-3 on one frame: ROIs from `detections` (Eq. 1, overlapping ones merged), each ROI's
/// coloured cloud (Algorithm 1), its normals (cfg.normal_k neighbours, at most the cloud size,
/// oriented to the camera centre) and its unit-sphere normalisation. Detections of other
/// categories are ignored; those wholly outside the image are listed in `outside` (a box of
/// another image or size would otherwise vanish without a word). Throws Error on a size mismatch
/// of depth, colour and camera, and for a config out of range (cfg.validate).
RoiFrame grape_roi_clouds(const DepthImage& depth, const ColorImage& color, const CameraIntrinsics& cam,
                          const std::vector<Detection>& detections, const RoiConfig& cfg = {});

/// Detections from a COCO-style JSON file: either a full COCO file ("annotations" array) or a
/// results array; each entry needs "bbox" [x, y, w, h] and "category_id" ("score" optional).
/// When `image_id` >= 0 only that image's entries are kept. Throws Error(path, ...).
std::vector<Detection> read_coco_detections(const std::filesystem::path& path, long image_id = -1);
/// The same file read once, its detections by image_id (-1: entries without one), each image's in
/// file order. Throws Error(path, ...) as read_coco_detections.
std::map<long, std::vector<Detection>> read_coco_detections_by_image(const std::filesystem::path& path);

}  // namespace cropsight::pipeline::grape
