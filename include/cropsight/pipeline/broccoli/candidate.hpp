#pragma once
// A cluster of one frame as the broccoli detector sees it (pixels, features, score, decision),
// and the pool the detector keeps them in from frame to frame.
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "cropsight/core/segment.hpp"

namespace cropsight::pipeline::broccoli {

/// One cluster of one frame.
struct Candidate {
  Segment segment;              ///< pixel indices (ascending) + centroid (m, camera) + boxes
  std::vector<float> features;  ///< concatenated features (FeatureSet order)
  float score = 0.0f;           ///< classifier score (0 when no model)
  bool head = false;            ///< score > threshold + margin
  int normal_points = -1;       ///< points of the segment with a normal (-1: not counted, min_normal_points 0)
  bool described = true;        ///< normal_points >= detection.min_normal_points (else never a head)
  bool oversized = false;       ///< over detection.split_oversized_above: not described, only split
  bool proposed = false;        ///< a head proposed by the depth CNN (cnn.model): no features, not classified
};

/// The candidates of one frame in a pool that only grows: a slot keeps the buffers (features,
/// pixel indices) an earlier frame left in it, so that once warm a frame allocates no candidate.
/// Growing the pool invalidates references to its candidates.
class CandidatePool {
 public:
  std::span<Candidate> active() { return {pool_.data(), count_}; }
  std::span<const Candidate> active() const { return {pool_.data(), count_}; }
  std::size_t size() const { return count_; }
  Candidate& operator[](std::size_t k) { return pool_[k]; }
  const Candidate& operator[](std::size_t k) const { return pool_[k]; }

  /// Starts a frame of `n` candidates (their slots hold whatever an earlier frame left there).
  void reset(std::size_t n) {
    if (pool_.size() < n) pool_.resize(n);
    count_ = n;
  }
  /// One more candidate at the end (a slot an earlier frame may have used).
  Candidate& append() {
    if (pool_.size() <= count_) pool_.resize(count_ + 1);
    return pool_[count_++];
  }
  /// Removes candidate k: the last candidate takes its slot.
  void remove(std::size_t k) { std::swap(pool_[k], pool_[--count_]); }

 private:
  std::vector<Candidate> pool_;
  std::size_t count_ = 0;
};

}  // namespace cropsight::pipeline::broccoli
