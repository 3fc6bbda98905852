#pragma once
// Field-map metrics (Kusumam et al. §6.4): how well the heads of a map match the true heads.
//
// Matching: one-to-one, by the Hungarian algorithm on distances: among all matchings whose pairs
// are within `radius_m` (default 5 cm) it takes one with the most pairs and, among those, the
// smallest total distance. (A greedy closest-first matching can pair a map head with the "wrong"
// truth and leave a neighbour unmatched; the optimum never matches fewer.) Distances are measured
// in the ground plane (field X–Y) by default, because a map head sits at the centroid of the
// head's visible top while the truth may be the plant's centre; `use_z` measures in 3D.
//
//   map_precision  = matched / map heads         (NaN with an empty map)
//   map_recall     = matched / true heads        (NaN without true heads)
//   duplicate_rate = duplicates / map heads, a duplicate being an unmatched map head within
//                    radius_m of a true head that another map head matched (the same head
//                    mapped twice); NaN with an empty map
//   count_error    = map heads − true heads (signed); count_error_rel = count_error / true heads
//
// Ignore regions (optional `ignore`: heads that exist but are too little seen to be required; the
// broccoli evaluator passes those no frame shows with map_min_visible_points points): an unmatched map head
// that is not a duplicate and lies within radius_m of one is `ignored`, neither a true nor a false
// head, the rule the detection AP's visible figures use. precision_visible = matched / (map heads
// − ignored); `precision` keeps counting such a head as false. Recall never depends on them.
#include <Eigen/Core>
#include <vector>

namespace cropsight::eval {

struct MapMatchConfig {
  double radius_m = 0.05;  ///< paper: 5 cm
  bool use_z = false;      ///< false: distance in field X–Y only
};

struct MapMatch {
  int map_index = 0, truth_index = 0;
  double distance_m = 0.0;
};

struct MapMetrics {
  int map_heads = 0, true_heads = 0, matched = 0, duplicates = 0;
  int ignored = 0;  ///< unmatched, non-duplicate map heads at an ignore region
  double precision = 0.0, recall = 0.0, duplicate_rate = 0.0;
  double precision_visible = 0.0;  ///< matched / (map heads − ignored); NaN when that is 0
  int count_error = 0;
  double count_error_rel = 0.0;
  double mean_distance_m = 0.0;   ///< over matched pairs (NaN when none)
  std::vector<MapMatch> matches;  ///< ordered by map index
};

/// Minimum-cost assignment of rows to columns (rectangular allowed): returns for each row the
/// column assigned, or -1 when rows outnumber columns and the row got none. cost is row-major
/// rows × cols. Exposed for tests.
std::vector<int> hungarian(const std::vector<double>& cost, int rows, int cols);

/// Positions in metres, one frame for all three lists (the field frame).
MapMetrics map_metrics(const std::vector<Eigen::Vector3d>& map, const std::vector<Eigen::Vector3d>& truth,
                       const MapMatchConfig& cfg = {}, const std::vector<Eigen::Vector3d>& ignore = {});

}  // namespace cropsight::eval
