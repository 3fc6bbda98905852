#pragma once
// Cloud: an unorganised point set. Positions in metres unless a producer documents otherwise
// (e.g. the grape dataset's unit-sphere normalised coordinates). Optional channels are empty
// when absent; when present they have one entry per point.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace cropsight {

struct Cloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  ///< unit normals
  std::vector<Eigen::Vector3f> colors;   ///< r, g, b in [0, 1]
  std::vector<int> labels;               ///< class or instance ids

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_colors() const { return !colors.empty(); }
  bool has_labels() const { return !labels.empty(); }
  /// Throws cropsight::Error(where, ...) when channel sizes disagree or a value is not finite.
  void validate(const std::string& where) const;
};

}  // namespace cropsight
