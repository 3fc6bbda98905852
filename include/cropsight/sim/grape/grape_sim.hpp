#pragma once
// The grape-bunch simulator (docs/simulator.md, "Grape bunches"): one bunch's ROI cloud as the
// grape pipeline's stages 1-3 would cut it from an RGB-D frame, written in the grape dataset's
// text format (io/grape_text.hpp) with the true label of every point, so that the shipped grape
// segmenters and the cut point can be run and scored without the real clouds.
//
// The scene: a bunch of berries (spheres) hanging from a peduncle (a chain of small spheres),
// one to three leaves (flat ellipses) beside it, and a grey backdrop with holes, seen by a pinhole
// RGB-D camera. Every pixel of the bunch's region of interest becomes one point, as Algorithm 1
// deprojects one: berries (label 1), peduncle (2), leaf (3), backdrop (4), mixed-depth pixels
// along silhouettes (5, "noise"), and pixels without a depth return (0), which sit at the camera
// centre, as all label-0 points of the shared clouds sit at one position.
//
// Frames: the scene is built in the camera frame (x right, y down, z forward; metres). The cloud
// is written in the frame the shared clouds use, as far as their statistics show it (y up, z
// toward the camera: the camera frame turned 180 degrees about x; docs/simulator.md says how this
// was read from the data), then normalised to the unit sphere. A point p of the written cloud maps
// back to the camera frame, in metres, by p_camera = R (p * scale + centroid), R = diag(1, -1, -1).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/config.hpp"

namespace cropsight::sim {

/// The dataset's label ids, as the segmenters predict them.
enum GrapeLabel : int {
  kGrapeNoReturn = 0,
  kGrapeBerry = 1,
  kGrapePeduncle = 2,
  kGrapeLeaf = 3,
  kGrapeBackdrop = 4,
  kGrapeNoise = 5
};
inline constexpr int kGrapeLabels = 6;

struct GrapeSimConfig {
  double focal_px = 900;                                           ///< px; pinhole focal length (fx = fy)
  double distance_min = 0.45, distance_max = 0.6;                  ///< m; camera to the bunch's axis
  double backdrop_min = 0.35, backdrop_max = 0.6;                  ///< m; backdrop behind the bunch's axis
  double backdrop_holes = 0.7;                                     ///< fraction of the backdrop without a return
  double bunch_length_min = 0.09, bunch_length_max = 0.15;         ///< m; top of the bunch to its tip
  double bunch_radius_min = 0.025, bunch_radius_max = 0.035;       ///< m; radius at the shoulders
  int berries_min = 50, berries_max = 90;                          ///< berries tried (overlapping ones dropped)
  double berry_radius_min = 0.005, berry_radius_max = 0.0075;      ///< m
  double peduncle_length_min = 0.015, peduncle_length_max = 0.03;  ///< m; above the bunch
  double peduncle_radius = 0.0035;                                 ///< m
  int leaves_min = 1, leaves_max = 4;
  double leaf_size_min = 0.025, leaf_size_max = 0.045;  ///< m; a leaf's longer semi-axis
  double depth_noise = 0.0015;  ///< m; depth noise sigma at 1 m, growing with the square of depth
  double color_noise = 0.02;    ///< colour noise sigma, colour units [0, 1]
  int edge_band_px = 2;         ///< px; pixels this close to a depth jump get a mixed depth (label 5)
  double edge_jump = 0.05;      ///< m; depth step between neighbours that makes a silhouette

  template <class V>
  void visit(V& v) {
    v("focal_px", focal_px, "px; focal length of the pinhole camera", Range::within(100.0, 4000.0));
    v("distance_min", distance_min, "m; nearest camera-to-bunch distance", Range::within(0.2, 3.0));
    v("distance_max", distance_max, "m; farthest camera-to-bunch distance", Range::within(0.2, 3.0));
    v("backdrop_min", backdrop_min, "m; nearest backdrop behind the bunch", Range::within(0.1, 3.0));
    v("backdrop_max", backdrop_max, "m; farthest backdrop behind the bunch", Range::within(0.1, 3.0));
    v("backdrop_holes", backdrop_holes, "fraction of the backdrop without a depth return", Range::within(0.0, 1.0));
    v("bunch_length_min", bunch_length_min, "m; shortest bunch", Range::within(0.03, 0.5));
    v("bunch_length_max", bunch_length_max, "m; longest bunch", Range::within(0.03, 0.5));
    v("bunch_radius_min", bunch_radius_min, "m; narrowest bunch at its shoulders", Range::within(0.01, 0.2));
    v("bunch_radius_max", bunch_radius_max, "m; widest bunch at its shoulders", Range::within(0.01, 0.2));
    v("berries_min", berries_min, "count; fewest berries tried", Range::within(1, 1000));
    v("berries_max", berries_max, "count; most berries tried", Range::within(1, 1000));
    v("berry_radius_min", berry_radius_min, "m; smallest berry radius", Range::within(0.002, 0.03));
    v("berry_radius_max", berry_radius_max, "m; largest berry radius", Range::within(0.002, 0.03));
    v("peduncle_length_min", peduncle_length_min, "m; shortest peduncle", Range::within(0.005, 0.2));
    v("peduncle_length_max", peduncle_length_max, "m; longest peduncle", Range::within(0.005, 0.2));
    v("peduncle_radius", peduncle_radius, "m; peduncle radius", Range::within(0.0005, 0.02));
    v("leaves_min", leaves_min, "count; fewest leaves", Range::within(0, 10));
    v("leaves_max", leaves_max, "count; most leaves", Range::within(0, 10));
    v("leaf_size_min", leaf_size_min, "m; smallest leaf (longer semi-axis)", Range::within(0.005, 0.3));
    v("leaf_size_max", leaf_size_max, "m; largest leaf (longer semi-axis)", Range::within(0.005, 0.3));
    v("depth_noise", depth_noise, "m; depth noise sigma at 1 m (times depth squared)", Range::within(0.0, 0.05));
    v("color_noise", color_noise, "colour noise sigma, colours in [0, 1]", Range::within(0.0, 0.3));
    v("edge_band_px", edge_band_px, "px; band along silhouettes with mixed depth (label 5)", Range::within(0, 20));
    v("edge_jump", edge_jump, "m; depth step between neighbours that makes a silhouette", Range::above(0.0));
  }
  /// Rules between fields (each minimum at most its maximum); throws Error(where, ...).
  void validate(const std::string& where) const;
};

/// What the simulator knows about its bunch.
struct GrapeSimTruth {
  std::uint64_t seed = 0;
  double distance_m = 0;  ///< camera to the bunch's axis
  int berries = 0, leaves = 0;
  /// The cut point as pipeline::grape_cut_point defines it, from the true labels: the centroid of
  /// the visible peduncle points, m, camera frame.
  Eigen::Vector3f cut_point_m = Eigen::Vector3f::Zero();
  Eigen::Vector3f peduncle_axis = -Eigen::Vector3f::UnitY();  ///< unit, camera frame, pointing up (-y)
  int peduncle_points = 0;
  std::array<long, kGrapeLabels> label_counts{};  ///< points per label
  int roi_width = 0, roi_height = 0;              ///< px; the region of interest
};

/// One simulated ROI cloud.
struct GrapeSimCloud {
  Cloud cloud;  ///< unit sphere, dataset frame (above); normals, colours in [0, 1], true labels
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  ///< m, dataset frame (before normalisation)
  float scale = 1.f;                                   ///< m per unit of the written cloud
  GrapeSimTruth truth;

  /// A point of `cloud` in the camera frame, metres (the mapping above).
  Eigen::Vector3f to_camera(const Eigen::Vector3f& p) const;
};

/// Simulates the bunch of `seed`; the same seed and config give the same cloud on every platform.
/// Throws Error("grape simulator", ...) for an invalid config.
GrapeSimCloud simulate_grape_cloud(const GrapeSimConfig& cfg, std::uint64_t seed);

/// Writes DIR/cloud.txt (io::write_grape_text: the true labels in the label column) and
/// DIR/truth.json (seed, frame, centroid_m, scale_m, cut point, label counts; docs/simulator.md).
/// Files are written atomically into `dir`, which must exist: callers wanting all-or-nothing
/// write into an io::OutputFolder.
void write_grape_sim(const std::filesystem::path& dir, const GrapeSimCloud& sim);

}  // namespace cropsight::sim
