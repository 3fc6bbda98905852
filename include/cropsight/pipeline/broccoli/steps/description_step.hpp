#pragma once
// Segments → described candidates, the broccoli detector's features step (StageTimer
// "features"): each segment of the clustering takes a slot of the candidate pool, its indices
// sorted ascending, and gets its feature vector (features::FeatureSet, e.g. VFH; read from the
// cloud's points in metres and its normals, camera frame). With detection.min_normal_points > 0
// a candidate with fewer points that have a normal is not described (never a head), and with
// detection.split_oversized_above > 0 a larger one is neither described nor classified (only the
// crease split looks inside it). The feature vectors reuse the pool's buffers.
#include <cstddef>
#include <string>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/features/feature_set.hpp"
#include "cropsight/pipeline/broccoli/candidate.hpp"

namespace cropsight::pipeline::broccoli::steps {

class DescriptionStep {
 public:
  /// `features`: a FeatureSet spec; throws Error("config", ...) when it is not one.
  DescriptionStep(const std::string& features, features::FeatureConfig options, int min_normal_points,
                  int oversized_above);

  std::size_t dimension() const { return feature_set_.dimension(); }

  /// Fills `pool` with one candidate per segment, in order (candidate k = segment k); the
  /// segments' index lists are swapped with the slots' old ones. Needs the cloud's normals on the
  /// segments' pixels.
  void run(std::vector<Segment>& segments, const OrganizedCloud& cloud, CandidatePool& pool, StageTimer& timer) const;

  /// The features of `c` (and its normal count when min_normal_points asks for it).
  void describe(const OrganizedCloud& cloud, Candidate& c) const;

 private:
  features::FeatureSet feature_set_;
  features::FeatureConfig options_;
  int min_normal_points_;
  int oversized_above_;
};

}  // namespace cropsight::pipeline::broccoli::steps
