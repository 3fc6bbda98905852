#pragma once
// Point-cloud semantic segmentation networks on libtorch (CPU): PointNet++ with multi-scale
// grouping and PointResNet (Luo et al.: three set-abstraction layers whose MLPs are residual
// "ResMLP" blocks, feature propagation back to every point). libtorch stays inside the backend
// plugin libcropsight_nn_torch.so (src/nn/torch/), which the first PointSegmenter built or loaded
// in a process loads with dlopen (looked for in the program's ../lib/, beside the program, in the
// build tree, then on the loader's path; $CROPSIGHT_NN_BACKEND names it explicitly); without it
// the constructor and load() throw Error. This header only declares the configuration and a pimpl.
//
// Input clouds are normalised to the unit sphere (geometry::normalize_unit_sphere) before they
// reach the network, both in training and in segmentation.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cropsight/core/cloud.hpp"
#include "cropsight/core/config.hpp"
#include "cropsight/core/threads.hpp"

namespace cropsight::nn {

struct PointNetConfig {
  std::string arch = "pointresnet";  ///< "pointresnet" | "pointnet2" (MSG)
  std::string features = "xyzrgbn";  ///< "xyz" | "xyzn" | "xyzrgb" | "xyzrgbn" (paper Table 3)
  int num_classes = 6;
  int num_points = 2048;  ///< points per network pass (paper: 4096 for PointNet++-style nets)
  int sa1_points = 512, sa2_points = 128, sa3_points = 32;  ///< set-abstraction centroids
  int k1 = 32, k2 = 32, k3 = 16;                            ///< neighbours grouped per centroid (MSG adds k/2 scales)
  int width = 32;                                           ///< base channel width (SA1 = 2w, SA2 = 4w, SA3 = 8w)
  double dropout = 0.3;

  // Training
  int epochs = 40;
  int batch_size = 8;
  double lr = 1e-3;       ///< Adam initial learning rate
  double lr_decay = 0.7;  ///< multiplied every lr_step epochs
  int lr_step = 10;
  double weight_decay = 1e-4;
  double class_weight_power = 0.5;  ///< CE weight = (median share / class share)^power
  double lovasz_weight = 0.0;       ///< > 0 adds this × Lovász-softmax (an IoU surrogate) to the CE loss
  bool augment = true;              ///< rotation about the vertical (y) axis, scaling, jitter, colour jitter
  double scale_min = 0.85, scale_max = 1.15;
  double jitter_sigma = 0.005, colour_jitter = 0.05;
  int val_every = 5;  ///< epochs between validation passes (0 = never)
  int threads = 2;    ///< at::set_num_threads (the machine has two cores)
  std::uint64_t seed = 1;
  std::string checkpoint;  ///< path written after each epoch (empty = none); resumed when present

  template <class V>
  void visit(V& v) {
    v("arch", arch, "pointresnet | pointnet2 (paper: PointResNet, Luo et al.)");
    v("features", features, "xyz | xyzn | xyzrgb | xyzrgbn (paper: 9 features, Table 3)");
    v("num_points", num_points, "count; points per network pass (ours: 2048 for CPU)",
      Range::at_least(8, "the set abstractions need a few points to group"));
    v("sa1_points", sa1_points, "count; SA1 centroids", Range::at_least(4));
    v("sa2_points", sa2_points, "count; SA2 centroids", Range::at_least(2));
    v("sa3_points", sa3_points, "count; SA3 centroids", Range::at_least(1));
    v("k1", k1, "count; SA1 neighbours", Range::at_least(1));
    v("k2", k2, "count; SA2 neighbours", Range::at_least(1));
    v("k3", k3, "count; SA3 neighbours", Range::at_least(1));
    v("width", width, "count; base channel width", Range::at_least(1));
    v("dropout", dropout, "probability; dropout before the classifier", Range::within(0, 1).open_above());
    v("epochs", epochs, "count; training epochs", Range::at_least(1));
    v("batch_size", batch_size, "count; clouds per step", Range::at_least(2, "BatchNorm needs two clouds per step"));
    v("lr", lr, "1; Adam learning rate (PointNet++: 1e-3)", Range::above(0));
    v("lr_decay", lr_decay, "1; learning-rate factor every lr_step epochs (PointNet++: 0.7)",
      Range::within(0, 1).open_below());
    v("lr_step", lr_step, "epochs; learning-rate decay period", Range::at_least(1));
    v("weight_decay", weight_decay, "1; Adam L2", Range::at_least(0));
    v("class_weight_power", class_weight_power, "1; inverse-frequency CE weight exponent", Range::at_least(0));
    v("lovasz_weight", lovasz_weight, "1; weight of the Lovasz-softmax term added to CE (ours; 0 = CE only, the paper)",
      Range::at_least(0));
    v("augment", augment, "bool; rotation/scale/jitter/colour augmentation");
    v("val_every", val_every, "epochs; validation period (0 = never)", Range::at_least(0));
    v("threads", threads, "count; libtorch intra-op threads", Range::within(1, kMaxThreads));
    v("seed", seed, "1; random seed");
  }

  /// Throws Error(where, "'FIELD' must be ..., got VALUE") for the first field out of range: the
  /// Ranges declared in visit() (counts below their minimum, lr not finite and positive, dropout
  /// outside [0, 1), threads outside 1..kMaxThreads ...), then the rules visit() cannot declare
  /// (an unknown arch or feature set, num_classes >= 2, the augmentation ranges): such values
  /// crashed or hung libtorch, or trained nothing without a word.
  void validate(const std::string& where) const;
};

/// One epoch's record.
struct EpochLog {
  int epoch = 0;
  double loss = 0;
  double train_acc = 0;  ///< on the sampled training points
  double val_miou = -1;  ///< -1 when not validated this epoch
  double seconds = 0;
  double lr = 0;
};

class PointSegmenter {
 public:
  explicit PointSegmenter(const PointNetConfig& cfg);
  ~PointSegmenter();
  PointSegmenter(PointSegmenter&&) noexcept;
  PointSegmenter& operator=(PointSegmenter&&) noexcept;

  /// Trains for cfg.epochs (continuing from cfg.checkpoint when it exists). `on_epoch` is
  /// called after each epoch. Clouds need labels and, depending on `features`, normals/colours.
  std::vector<EpochLog> train(const std::vector<Cloud>& train, const std::vector<Cloud>& val,
                              const std::function<void(const EpochLog&)>& on_epoch = {});

  /// Labels of every point: the cloud is split into random disjoint chunks of num_points
  /// (padded), each chunk is one network pass, so every point gets its own prediction.
  /// Deterministic (fixed seed). `passes_out` (optional) receives the number of passes.
  /// `votes` > 1: test-time augmentation — the cloud is covered `votes` times, each with another
  /// chunking and rotated by 2πv/votes about the vertical (y) axis, class probabilities averaged
  /// (`votes` times the passes). Throws Error for votes < 1.
  /// `proba` (optional) receives the per-point class probabilities (cloud size × num_classes,
  /// row-major; averaged over the votes).
  std::vector<int> segment(const Cloud& cloud, int* passes_out = nullptr, int votes = 1,
                           std::vector<float>* proba = nullptr) const;

  /// Paper variant: one pass on `num_points` samples, labels carried back to every point by
  /// nearest neighbour. The sample is drawn at random (seeded, deterministic) like the training
  /// samples by default; `farthest` = true takes farthest-point samples instead, whose even
  /// spatial density differs from what the network was trained on (on the shared clouds it lost
  /// the whole of label 0).
  std::vector<int> segment_sampled(const Cloud& cloud, bool farthest = false) const;

  /// The paper variant's two halves, for callers with their own carry-back: the num_points
  /// indices of one pass (random, seeded, or farthest-point; repeated when the cloud is smaller)
  /// and the network's labels at exactly num_points given indices (throws Error otherwise).
  /// `pass` > 0 draws another sample (seed + pass; farthest-point from another start) and
  /// `angle_rad` rotates the input about the vertical (y) axis, for test-time augmentation.
  std::vector<int> sample_for_pass(const Cloud& cloud, bool farthest = false, int pass = 0) const;
  /// `proba` (optional) receives the class probabilities (num_points × num_classes, row-major).
  std::vector<int> predict_at(const Cloud& cloud, const std::vector<int>& idx, float angle_rad = 0.f,
                              std::vector<float>* proba = nullptr) const;
  /// Several passes at once: pass p is predict_at(cloud, idx[p], angle_rad[p], &(*proba)[p]), with
  /// the same labels and probabilities, the passes spread over `threads` threads (each pass on
  /// one thread: the small layers of these networks gain little from splitting one pass).
  /// `proba` (optional) receives one probability matrix per pass.
  std::vector<std::vector<int>> predict_passes(const Cloud& cloud, const std::vector<std::vector<int>>& idx,
                                               const std::vector<float>& angle_rad, int threads,
                                               std::vector<std::vector<float>>* proba = nullptr) const;

  /// One training step on fixed inputs (no augmentation, no sampling when the cloud already has
  /// num_points points): returns (loss, accuracy). Used by the tests to show learning works.
  std::pair<double, double> train_step(const std::vector<Cloud>& batch);

  void save(const std::filesystem::path& path) const;  ///< atomic
  static PointSegmenter load(const std::filesystem::path& path, int threads = 2);
  const PointNetConfig& config() const;
  std::size_t parameter_count() const;

 private:
  PointSegmenter();  // load()
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Feature channels of a feature name ("xyzrgbn" → 9). Throws Error on an unknown name.
int feature_channels(const std::string& features);

}  // namespace cropsight::nn
