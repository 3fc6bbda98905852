#pragma once
// One configuration struct for the broccoli head detector (every stage; YAML presets
// configs/broccoli-{oes,org,fec}-{uk,spain}.yaml; --set key=value on the CLI). Defaults are the
// papers' values; each field's documentation names its source:
//   [montes]  Montes, Le Louëdec, Cielniak, Duckett, "Real-time detection of broccoli crops in 3D
//             point clouds for autonomous robotic harvesting", IROS 2020 (OES / ORG / FEC)
//   [kusumam] Kusumam, Krajník, Pearson, Duckett, Cielniak, "3D-vision based detection,
//             localization, and sizing of broccoli heads in the field", J. Field Robotics 2017
#include <array>
#include <cstdint>
#include <string>

#include "cropsight/core/config.hpp"
#include "cropsight/features/feature_set.hpp"
#include "cropsight/geometry/depth_filter.hpp"
#include "cropsight/geometry/integral_normals.hpp"
#include "cropsight/geometry/organized_edges.hpp"
#include "cropsight/geometry/statistical_outlier.hpp"
#include "cropsight/learning/classifier.hpp"
#include "cropsight/pipeline/broccoli/depth_denoise.hpp"
#include "cropsight/segmentation/euclidean_clustering.hpp"
#include "cropsight/segmentation/organized_clustering.hpp"

namespace cropsight::pipeline::broccoli {

/// Statistical outlier removal before Euclidean clustering (FEC variant only).
struct OutlierStageConfig {
  bool enabled = true;
  geometry::StatisticalOutlierConfig sor;

  template <class V>
  void visit(V& v) {
    v("enabled", enabled, "run statistical outlier removal before FEC clustering (paper: yes, [kusumam] §4.1)");
    sor.visit(v);  // flat: outliers.mean_k, outliers.std_mul
  }
};

/// The detector's decision rules.
struct DetectionConfig {
  float score_margin = 0.0f;              ///< added to the classifier's threshold (0 SVM, 0.5 KNN)
  int min_normal_points = 0;              ///< clusters with fewer points with a normal are not classified
  float grow_tolerance = 0.0f;            ///< m; > 0: a head's mask grows over unclustered neighbours (0 = off)
  float grow_radius = 0.1f;               ///< m; ... within this distance of the head cluster's centroid
  float split_concave_angle_deg = 0.0f;   ///< degrees; > 0: rejected clusters are split at concave creases (0 = off)
  int split_concave_step = 3;             ///< pixels between the two normals the crease rule compares
  float split_score_margin = 0.0f;        ///< added to the head threshold for the pieces of a split
  int split_min_points = 2000;            ///< points; smaller clusters are not split
  float split_score_window = 0.0f;        ///< only clusters scoring within this of the threshold are split (0 = all)
  float split_max_piece_fraction = 0.8f;  ///< pieces holding more of their cluster are not classified
  int split_oversized_above = 0;          ///< points; > 0: larger clusters skip the classifier and go to the split
  bool split_accepted = false;            ///< accepted clusters are split too; a piece must outscore its cluster

  template <class V>
  void visit(V& v) {
    v("score_margin", score_margin,
      "score units; a cluster is a head when score > classifier threshold + margin (0: the classifier's own "
      "decision, as in [montes])");
    v("min_normal_points", min_normal_points,
      "points; a cluster with fewer points that have a normal has no shape descriptor (VFH reads normals; "
      "integral-image normals are undefined within normal_smoothing_size of the image border and next to depth "
      "changes): it is never a head (lowest score) and is left out of training (ours; 0 = classify every cluster)",
      Range::at_least(0));
    v("grow_tolerance", grow_tolerance,
      "m; when > 0, a cluster classified as a head grows over the valid pixels that no cluster holds (fragments "
      "below min_size, NaN-boundary pixels), joining 4-neighbours closer than this: a rough or noisy head that the "
      "clustering broke into one kept piece and debris gets its whole mask back (ours; 0 = off, the "
      "paper's masks). Only the mask, box and centroid change; the score is the kept piece's",
      Range::at_least(0.0));
    v("grow_radius", grow_radius,
      "m; grown pixels lie within this distance of the head cluster's centroid (ours; 0.1 m: a 180 mm head seen "
      "from a piece off its centre)",
      Range::above(0.0));
    v("split_concave_angle_deg", split_concave_angle_deg,
      "degrees; when > 0 (OES with a model), every cluster classified as no head is split again along its concave "
      "creases (normals this far apart that lean towards each other, LCCP's convexity rule): a head that the "
      "clustering joined to a leaf at the same depth comes apart where the leaf runs into it. The pieces are "
      "classified, and when one is a head they replace the cluster (ours; 0 = off, the paper's clusters)",
      Range::within(0.0, 179.0));
    v("split_concave_step", split_concave_step,
      "pixels between the two points whose normals the crease rule compares (ours; 3)", Range::at_least(1));
    v("split_score_margin", split_score_margin,
      "score units; a piece of a split cluster is a head when its score exceeds the head threshold (with "
      "score_margin) plus this: pieces cut from leaves are more often taken for heads than whole clusters (ours)");
    v("split_min_points", split_min_points,
      "points; rejected clusters smaller than this are not split (ours: on the wide validation fields every head "
      "recovered by a split came from a cluster of 2300 points or more; on uk-2001 the stage took 1.83-1.93 ms per "
      "frame at 2000 against 2.11-2.45 ms at 1500)",
      Range::at_least(1));
    v("split_score_window", split_score_window,
      "score units; when > 0, only clusters whose score lies within this of the head threshold are split (rejected "
      "ones below it; with split_accepted, accepted ones above it): a leaf with a head in it scores between a leaf "
      "and a head (ours, for speed; 0 = every such cluster)",
      Range::at_least(0.0));
    v("split_max_piece_fraction", split_max_piece_fraction,
      "fraction; a piece holding more than this share of its cluster's points is the rejected cluster again and "
      "is not classified (ours: the recovered heads held 0.10-0.59 of theirs; at 0.8, 23 % of the pieces on the wide "
      "validation fields are not classified)",
      Range::within(0.0, 1.0));
    v("split_oversized_above", split_oversized_above,
      "points; when > 0 (with split_concave_angle_deg), a cluster larger than this is not described or classified "
      "(no head is that large: the paper's oes.max_size 10000) but goes to the concave-crease split whatever its "
      "score, so that a head inside a large leaf region can come out of it; raise oes.max_size above this for "
      "such regions to reach the detector (ours; 0 = off)",
      Range::at_least(0));
    v("split_accepted", split_accepted,
      "bool; with split_concave_angle_deg, clusters classified as heads (of split_min_points or more) are split "
      "too, and replaced by their pieces when a piece is a head that scores above the whole cluster: a head "
      "joined to a leaf that the classifier still takes for a head comes out of it (ours: on the "
      "randomised validation fields kappa + AP50 0.017 higher, chosen for the general model; false = only rejected "
      "clusters are split, as before 2026-12-06)");
  }
};

/// A depth CNN that proposes heads where the clustering accepted none (ours): the
/// project's CenterNet with masks (nn/center_onnx.hpp), one class "head", run on the frame's depth
/// encoded by encode_depth_for_cnn (depth_encoding.hpp). Each box's mask pixels that hold a point
/// of the cloud become one candidate, kept when it overlaps no accepted head; it is a head (its
/// score just above the classifier's threshold, ordered among proposals by the CNN's score), so
/// every proposal ranks after the classifier's heads. Off by default: about 55 ms per 512 x 424
/// frame on one core (docs/pipelines/broccoli-heads.md).
struct CnnConfig {
  std::string model;         ///< .onnx written by `cropsight export-detector`; empty = off
  float min_score = 0.7f;    ///< CNN box score (0..1) a proposal needs (0.7: chosen on validation)
  float max_overlap = 0.3f;  ///< point-set IoU; a proposal overlapping an accepted head more is dropped
  int min_points = 30;       ///< points of the cloud a proposal needs

  template <class V>
  void visit(V& v) {
    v("model", model,
      "path; the head CNN as ONNX (cropsight export-detector; models/broccoli-head-cnn.onnx), relative to the "
      "working directory; empty = off (the paper's pipeline)");
    v("min_score", min_score, "0..1; CNN box score a proposal needs", Range::within(0.0, 1.0));
    v("max_overlap", max_overlap,
      "0..1; point-set IoU above which a proposal duplicates an accepted head (or an earlier proposal) and is "
      "dropped",
      Range::within(0.0, 1.0));
    v("min_points", min_points, "points; a proposal with fewer valid points of the cloud is dropped",
      Range::at_least(1));
  }
};

/// Range-aware detection (docs/experiments/2026-12-02-broccoli-generalisation.md): the
/// paper's fixed 0.5-1.0 m depth window and its point and distance thresholds assume one camera
/// height. These options tie them to the soil instead, estimated per frame from the depth image:
/// the farthest surfaces (a high percentile of the valid depths) are the soil.
struct RangeConfig {
  bool soil_relative = false;           ///< depth window's far end = soil depth - min_height_above_soil
  float soil_percentile = 0.97f;        ///< fraction; the soil depth is this percentile of valid depths
  float min_height_above_soil = 0.25f;  ///< m; points nearer the soil than this are dropped
  float reference_range = 0.0f;         ///< m; > 0: scale OES thresholds by the heads' range over this
  float head_height = 0.45f;            ///< m; the heads' typical height above the soil (their range = soil - this)
  bool extend_only = false;             ///< with soil_relative: the far end never comes nearer than depth.max_depth

  template <class V>
  void visit(V& v) {
    v("soil_relative", soil_relative,
      "replace depth.max_depth per frame by (soil depth - min_height_above_soil): the window follows the camera "
      "height (ours; off = the paper's fixed window). depth.max_depth stays in use when a frame has under 1000 valid "
      "pixels");
    v("soil_percentile", soil_percentile,
      "fraction; the soil depth of a frame is this percentile of its valid depths (the soil is the farthest "
      "surface; a canopy covering all but 3 % of the soil still leaves the estimate on the soil or the lowest leaves)",
      Range::within(0.5, 1.0));
    v("min_height_above_soil", min_height_above_soil,
      "m; with soil_relative, points less than this above the soil estimate are dropped (uk preset: 1.25 m camera "
      "with max_depth 1.0 = 0.25 m)",
      Range::within(0.0, 2.0));
    v("reference_range", reference_range,
      "m; > 0: per frame, oes.min_size / min_size_border / max_size scale by (reference_range / r)^2 and "
      "oes.distance_tolerance by r / reference_range, with r = soil depth - head_height (a head's point count falls "
      "and its point spacing grows with range); 0 = fixed thresholds (the paper). uk preset: 0.80",
      Range::within(0.0, 5.0));
    v("head_height", head_height, "m; typical head apex height above the soil for reference_range",
      Range::within(0.0, 2.0));
    v("extend_only", extend_only,
      "with soil_relative: the far end is max(depth.max_depth, soil depth - min_height_above_soil), so the window "
      "only grows for high cameras (heads beyond the paper's 1.0 m) and stays the paper's for low ones, where "
      "low heads sit less than min_height_above_soil over the soil");
  }
};

/// How ground truth is joined to clusters, for training labels and evaluation only: the detector
/// never reads these. Their keys stay "detection.*" (Config visits them under that
/// name) so that presets and the model files written before the split keep loading.
struct TruthRules {
  float min_head_fraction = 0.5f;  ///< cluster-truth rule, see broccoli/truth.hpp
  int min_truth_points = 0;        ///< AP: ground-truth heads with fewer visible points are not counted
  int visible_truth_points = 300;  ///< ap50_visible: heads with fewer visible points are ignore regions

  template <class V>
  void visit(V& v) {
    v("min_head_fraction", min_head_fraction,
      "fraction; a cluster is a true head when at least this share of its points lies on one labelled head "
      "(ours: 0.5, the majority rule)",
      Range::within(0, 1).open_below());
    v("min_truth_points", min_truth_points,
      "points; ground-truth heads with fewer visible (valid, in depth range) points are left out of AP "
      "(0 = every labelled head counts)",
      Range::at_least(0));
    v("visible_truth_points", visible_truth_points,
      "points; for ap50_visible / map50_95_visible, ground-truth heads with fewer visible points are ignore "
      "regions (COCO-style: not counted, and a detection of one is not a false positive); 300 = the field map's "
      "rule for a true head (ours; the paper does not state its rule for partly visible heads)",
      Range::at_least(0));
  }
  /// Throws Error(where, ...) for a value out of range.
  void validate(const std::string& where) const;
};

/// The clustering of [montes] §III: organised edge segmentation, organised region growing, or
/// (fast) Euclidean clustering on the unorganised cloud.
enum class Variant { oes, org, fec };
constexpr std::array<const char*, 3> config_names(Variant) { return {"oes", "org", "fec"}; }

struct DetectorConfig {
  Variant pipeline = Variant::oes;
  std::string features = "vfh";  ///< FeatureSet spec, e.g. "vfh" or "vfh,va,geom"
  geometry::DepthRangeConfig depth;
  DepthDenoiseConfig denoise;
  geometry::IntegralNormalConfig normals;
  geometry::OrganizedEdgeConfig edges;
  segmentation::OesConfig oes;
  segmentation::OrgConfig org;
  segmentation::EuclideanClusterConfig fec;
  OutlierStageConfig outliers;
  features::FeatureConfig feature_options;
  learning::ClassifierParams classifier;
  DetectionConfig detection;
  RangeConfig range;
  CnnConfig cnn;

  template <class V>
  void visit(V& v) {
    v("pipeline", pipeline,
      "oes | org | fec: organised edge segmentation, organised region growing, "
      "Euclidean clustering ([montes] §III)");
    v("features", features, "comma list of vfh, va, geom, cvfh (paper: vfh, [montes] §III-D)");
    v("depth", depth, "depth-range filter");
    v("denoise", denoise, "noise-adaptive depth denoising");
    v("normals", normals, "integral-image normals");
    v("edges", edges, "organised edges (OES)");
    v("oes", oes, "OES clustering");
    v("org", org, "ORG clustering");
    v("fec", fec, "FEC Euclidean clustering");
    v("outliers", outliers, "statistical outlier removal (FEC)");
    v("feature_options", feature_options, "feature options");
    v("classifier", classifier, "classifier (used by training; a model file records its own)");
    v("detection", detection, "decision and ground-truth rules");
    v("range", range, "range-aware depth window and thresholds (ours)");
    v("cnn", cnn, "depth CNN head proposals (ours)");
  }

  /// Throws Error(where, ...) for an unknown feature spec or a value out of range.
  void validate(const std::string& where) const;
  /// Feature block names in order, e.g. {"vfh", "va"} (the model file's "features").
  std::vector<std::string> feature_names() const;
};

}  // namespace cropsight::pipeline::broccoli
