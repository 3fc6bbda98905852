#pragma once
// A trained grape segmentation model of either kind behind one interface, plus the k-fold
// split by cloud the train / eval commands share (labelled clouds: truth.hpp).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"

namespace cropsight::pipeline::grape {

class Model {
 public:
  /// Loads a network model (*.pt, nn::PointSegmenter) or a GBDT model (XGBoost JSON written by
  /// `train grape --model gbdt`). Throws Error(path, ...) for anything else.
  static Model load(const std::filesystem::path& path, int threads = 2);
  ~Model();
  Model(Model&&) noexcept;
  Model& operator=(Model&&) noexcept;

  /// "gbdt", "pointresnet" or "pointnet2".
  const std::string& kind() const { return kind_; }
  /// Feature set of a network ("xyzrgbn" …); "gbdt-features" for the GBDT.
  const std::string& features() const { return features_; }
  /// Label of every point. The cloud is used as given (the dataset's clouds are already
  /// unit-sphere normalised; ROI clouds are normalised by the caller).
  std::vector<int> segment(const Cloud& cloud) const;
  /// Networks only: with `sampled` true, segment() runs the paper's mode — one pass on
  /// num_points samples (random like the training samples, or farthest-point with `farthest`),
  /// labels carried back to every other point — instead of one pass per disjoint chunk so that
  /// every point gets its own prediction (the default). The carry-back is the fast GBDT's
  /// (grape_carry_back): `carry_k` = 1 is the paper's nearest neighbour; larger k votes over the
  /// k nearest samples weighted by distance and colour likeness (FeatureConfig's
  /// carry_colour). Throws Error for a GBDT model, whose recipe fixes its own sampling, and for
  /// carry_k < 1.
  void set_sampled(bool sampled, bool farthest = false, int carry_k = 1);
  bool sampled() const;
  /// Networks: test-time augmentation with `votes` passes rotated by 360°/votes about the
  /// vertical axis. Every-point mode: `votes` covers of the cloud, class probabilities averaged
  /// (nn::PointSegmenter::segment); sampled mode: `votes` one-pass predictions on different
  /// samples, their class probabilities carried back to every point and summed.
  /// Throws Error for votes < 1 and for a GBDT model.
  void set_votes(int votes);
  int votes() const;

  /// Per-point class probabilities of segment() (cloud size × 6 classes, row-major, rows sum
  /// to 1): the network's averaged softmax (every point), its carried-back votes (sampled), or
  /// the GBDT's probabilities; segment() is their argmax, except for the paper's single sampled
  /// pass, which carries back the samples' hard labels.
  std::vector<float> scores(const Cloud& cloud) const;
  /// Ensemble: segment() takes the argmax of (1 − weight) · this model's scores + weight ·
  /// `partner`'s (e.g. a network and a GBDT, whose errors differ). Throws Error for a weight
  /// outside [0, 1] or a partner with another number of classes; nullptr removes the partner.
  void set_ensemble(std::shared_ptr<const Model> partner, double weight = 0.5);

 private:
  Model() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string kind_, features_;
};

/// Fold (0..K-1) of each of `n` clouds: a seeded shuffle dealt round-robin, so folds differ in
/// size by at most one. Split is by cloud, never by point.
std::vector<int> grape_folds(std::size_t n, int k, std::uint64_t seed = 1);

/// Parses "k/K" (1-based k) → (k-1, K). Throws Error(option, ...).
std::pair<int, int> parse_fold(const std::string& text, const std::string& option);

}  // namespace cropsight::pipeline::grape
