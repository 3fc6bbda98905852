#pragma once
// The project's own 2D detector with masks: CenterNet ("Objects as Points", Zhou et
// al. 2019), trained from scratch on the CPU. A small BatchNorm backbone (strided Conv-BN-ReLU
// blocks to stride 32) with an FPN-lite path back to stride 4 (nearest upsampling, 1x1 lateral
// convs, Add) feeds four heads at stride 4: a per-class centre heatmap (sigmoid; penalty-reduced
// focal loss), box size and centre offset (L1 at the object centres), and a per-class semantic
// mask (sigmoid; binary cross-entropy). Decoding: 3x3 max-pool peaks of the heatmap, the top K over
// all classes, no NMS. Built only from Conv, BatchNorm, ReLU, Add, nearest Resize and Sigmoid so
// that it exports to an ONNX graph OpenCV's DNN module runs.
//
// Like nn::PointSegmenter, the network lives in the libtorch plugin libcropsight_nn_torch.so,
// loaded on first use (point_segmenter.hpp says where it is looked for); this header declares the
// configuration, the training data and a pimpl only.
//
// Frames and units: images are 8-bit RGB; boxes are image pixels, continuous corners
// (core/detection2d.hpp). Each image is letterboxed to the network input (aspect kept, centred on
// grey 114, nn::Letterbox of onnx_decode.hpp) and fed as RGB / 255; boxes come back in the
// original image's pixels.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cropsight/core/config.hpp"
#include "cropsight/core/detection2d.hpp"
#include "cropsight/core/image.hpp"

namespace cropsight::nn {

/// A comma-separated list of names, split at commas, spaces and tabs around each name trimmed,
/// empty names dropped (the class_names keys of the detectors).
std::vector<std::string> split_class_names(const std::string& list);

struct CenterNetConfig {
  std::string class_names = "object";         ///< comma-separated; class id = position
  int input_width = 256, input_height = 256;  ///< pixels, multiples of 32 (the backbone's stride)
  int width = 16;                             ///< base channels: stages w, 2w, 4w, 8w, 8w; FPN and heads 2w
  int max_objects = 64;                       ///< objects per training image (the rest are dropped)

  // Loss weights (CenterNet: heatmap 1, size 0.1, offset 1); mask 1.
  double size_weight = 0.1, offset_weight = 1.0, mask_weight = 1.0;
  /// Weight of a soft Dice loss on the mask head, added to its cross-entropy (inside mask_weight):
  /// 1 - (2 sum(p t) + 1) / (sum p + sum t + 1) per class over the batch's masked images, averaged
  /// over classes. Cross-entropy per pixel lets a class of a few pixels (a peduncle: 0.1 % of an
  /// image) weigh almost nothing; Dice weighs each class by its own overlap (V-Net, Milletari et
  /// al. 2016). 0: cross-entropy only (models written before the key).
  double mask_dice_weight = 0.0;

  // Training
  int epochs = 60;
  int batch_size = 4;
  double lr = 1e-3;  ///< Adam; cosine decay to lr/20 over the epochs
  double weight_decay = 1e-4;
  int threads = 1;  ///< at::set_num_threads
  std::uint64_t seed = 1;

  // Decoding
  double score_threshold = 0.1;  ///< heatmap peak score kept
  int top_k = 100;               ///< peaks kept per image over all classes
  /// Per class, in class_names order, comma-separated: the mask-head score a pixel needs to be
  /// inside the class's mask; empty = 0.5 for every class. `train detector` and
  /// `tune-mask-thresholds` set it to each class's best-IoU threshold on the training images
  /// (calibrate_mask_thresholds, detector_eval.hpp): a thin class such as a peduncle may never
  /// score 0.5. Models written before this key load with it empty.
  std::string mask_thresholds;
  /// How the stride-4 mask head is brought back to image pixels: "bilinear" interpolates the scores
  /// between the four nearest cell centres (as semantic segmentation and Mask R-CNN upsample
  /// their mask logits), "nearest" takes the cell under the pixel centre (one cell covers 10x10
  /// pixels of a 1280x720 image at 512x288 input: blocky edges, a peduncle one cell wide).
  /// Models written before this key load with "nearest", the mapping their thresholds were
  /// calibrated for; new models and `tune-mask-thresholds` use "bilinear".
  std::string mask_upsampling = "bilinear";
  /// Flip test (CenterNet's `--flip_test`): the heads are averaged with those of the mirrored
  /// image (heatmap, sizes, masks), twice the inference time for steadier scores. Models written
  /// before this key load with false.
  bool flip_test = false;
  /// Multi-scale mask test: further inference inputs, comma-separated "WxH" (multiples of 32). The
  /// network runs again at each (with the flip test when flip_test is on) and a pixel's mask score
  /// is the mean of the main input's and these inputs' scores, each brought to the image by
  /// mask_upsampling; the boxes come from the main input alone (detect() runs only that). A
  /// larger input gives the stride-4 mask head finer cells (a peduncle 1-2 cells wide at 640x352)
  /// while the boxes stay at the size the model was trained for. Empty: one input (models
  /// written before the key load with it empty).
  std::string mask_inputs;
  /// Whether the mask_inputs passes use the flip test too (when flip_test is on): off halves
  /// their cost. Models written before the key load with true.
  bool mask_inputs_flip_test = true;

  template <class V>
  void visit(V& v) {
    v("class_names", class_names, "comma-separated class names, indexed by class id");
    v("input_width", input_width, "pixels; network input width", Range::within(32, 4096).multiple_of(32));
    v("input_height", input_height, "pixels; network input height", Range::within(32, 4096).multiple_of(32));
    v("width", width, "channels; base width of the backbone", Range::within(4, 256));
    v("max_objects", max_objects, "count; objects per training image", Range::at_least(1));
    v("size_weight", size_weight, "loss weight of the size head (CenterNet: 0.1)", Range::at_least(0));
    v("offset_weight", offset_weight, "loss weight of the offset head (CenterNet: 1)", Range::at_least(0));
    v("mask_weight", mask_weight, "loss weight of the mask head", Range::at_least(0));
    v("mask_dice_weight", mask_dice_weight,
      "weight of the soft Dice term added to the mask head's cross-entropy (0: none)", Range::at_least(0));
    v("epochs", epochs, "count; training epochs", Range::at_least(1));
    v("batch_size", batch_size, "images per step", Range::at_least(1));
    v("lr", lr, "Adam learning rate", Range::above(0));
    v("weight_decay", weight_decay, "Adam L2 weight decay", Range::at_least(0));
    v("threads", threads, "count; libtorch threads", Range::within(1, 256));
    v("seed", seed, "random seed (weights, shuffling, augmentation)");
    v("score_threshold", score_threshold, "heatmap score a peak needs", Range::within(0, 1));
    v("top_k", top_k, "count; peaks kept per image", Range::at_least(1));
    v("mask_thresholds", mask_thresholds,
      "per class, comma-separated: mask head score a pixel needs, each in (0, 1) (empty: 0.5 for every class)");
    v("mask_upsampling", mask_upsampling,
      "bilinear | nearest: mask head scores interpolated between cell centres, or the cell under each pixel "
      "(mask_thresholds are calibrated for one of them)");
    v("flip_test", flip_test,
      "bool; average the heads with those of the mirrored image (CenterNet's flip test; twice the inference time)");
    v("mask_inputs", mask_inputs,
      "further inference inputs for the mask head, comma-separated WxH (multiples of 32); mask scores averaged "
      "over them and the main input (multi-scale test); empty: none");
    v("mask_inputs_flip_test", mask_inputs_flip_test,
      "bool; the mask_inputs passes use the flip test too when flip_test is on (false: one pass each)");
  }
  /// The Ranges above, at least one class name, mask_thresholds empty or one number in (0, 1)
  /// per class, mask_upsampling bilinear or nearest. Throws Error(where).
  void validate(const std::string& where = "detector") const;
  /// mask_thresholds per class id (0.5 each when empty). Throws Error like validate().
  std::vector<float> mask_threshold_values(const std::string& where = "detector") const;
  /// mask_inputs as (width, height) pairs, each a multiple of 32 in [32, 4096]. Throws Error like validate().
  std::vector<std::pair<int, int>> mask_input_sizes(const std::string& where = "detector") const;
  /// Whether the mask_inputs passes run with the flip test.
  bool mask_passes_flip() const { return flip_test && mask_inputs_flip_test; }
  /// class_names split at commas, spaces trimmed.
  std::vector<std::string> names() const;
  int num_classes() const { return int(names().size()); }
};

/// One training or validation image: boxes (Detection2D::score ignored) and, optionally, a
/// per-class semantic mask: mask[c] is the pixels of class c (non-zero = inside), each
/// image-sized; empty = no mask supervision for this image.
struct DetectionSample {
  ColorImage image;
  std::vector<Detection2D> boxes;
  std::vector<GrayImage> masks;
  std::string name;  ///< for messages and results (file name)
};

/// The network's four heads for one image, at stride 4 of the input (out_w = input_width / 4).
/// heatmap and mask are sigmoid scores in [0, 1]; size is (w, h) and offset (dx, dy) in output
/// cells; each is channel-major: [channel][y][x].
struct CenterNetHeads {
  int classes = 0, out_w = 0, out_h = 0;
  std::vector<float> heatmap, size, offset, mask;
  /// The mask head at one of CenterNetConfig::mask_inputs (input_w x input_h pixels, letterboxed like
  /// the main input; out_w = input_w / 4), sigmoid scores [class][y][x].
  struct MaskPass {
    int input_w = 0, input_h = 0, out_w = 0, out_h = 0;
    std::vector<float> mask;
  };
  std::vector<MaskPass> extra_masks;  ///< one per mask_inputs entry, in order; empty without
};

/// Per-epoch progress of train().
struct DetectorEpochLog {
  int epoch = 0;                                                                     ///< 1-based
  double loss = 0, heatmap_loss = 0, size_loss = 0, offset_loss = 0, mask_loss = 0;  ///< means over the steps
  double val_ap50 = -1;  ///< mean over classes of VOC all-point AP at IoU 0.5 on the validation images; -1 = none
  double seconds = 0;
};

struct DetectorLosses {
  double total = 0, heatmap = 0, size = 0, offset = 0, mask = 0;
};

class CenterNet final : public Detector2D {
 public:
  /// A freshly initialised network (weights from cfg.seed). Throws Error (bad config, no plugin).
  explicit CenterNet(const CenterNetConfig& cfg);
  ~CenterNet() override;
  CenterNet(CenterNet&&) noexcept;
  CenterNet& operator=(CenterNet&&) noexcept;

  const CenterNetConfig& config() const;
  std::size_t parameter_count() const;

  /// One Adam step on these images (letterboxed, targets encoded; no augmentation).
  DetectorLosses train_step(const std::vector<const DetectionSample*>& batch);
  /// cfg.epochs epochs over `train` (shuffled with cfg.seed, batches of cfg.batch_size), AP50 on
  /// `val` after each epoch when it is not empty. `augment` (may be empty) turns each drawn sample
  /// into the one trained on (`draw` seeds it). on_epoch is called after each epoch. With a
  /// `checkpoint` path, weights, optimiser state and epochs done are written there after each
  /// epoch, and an existing checkpoint is resumed from (each epoch draws from seed and epoch
  /// alone, so a resumed run ends with the weights of an uninterrupted one).
  std::vector<DetectorEpochLog> train(
      const std::vector<DetectionSample>& train, const std::vector<DetectionSample>& val,
      const std::function<DetectionSample(const DetectionSample&, std::uint64_t draw)>& augment,
      const std::function<void(const DetectorEpochLog&)>& on_epoch, const std::filesystem::path& checkpoint = {});

  /// The heads on one image (eval mode).
  CenterNetHeads heads(const ColorImage& image) const;
  /// Boxes in image pixels, highest score first (Detector2D).
  std::vector<Detection2D> detect(const DetectorInput& in) override;
  std::vector<Detection2D> detect(const ColorImage& image) const;
  std::vector<std::string> class_names() const override;

  /// Replaces the per-class mask thresholds (config().mask_thresholds): one per class, each in
  /// (0, 1); save() and export_onnx() write them. Throws Error on a wrong count or value.
  void set_mask_thresholds(const std::vector<float>& per_class);
  /// Replaces the inference input size (config().input_width / input_height, multiples of 32):
  /// the network is fully convolutional, so the same weights run at another resolution (a larger
  /// one gives the stride-4 mask head finer cells). save() and export_onnx() write it; a later
  /// training from this file would also train at it. Throws Error on an invalid size.
  void set_input_size(int width, int height);
  /// Replaces config().mask_upsampling ("bilinear" or "nearest"). Throws Error on another value.
  void set_mask_upsampling(const std::string& mode);
  /// Replaces config().flip_test.
  void set_flip_test(bool on);
  /// Replaces config().mask_inputs ("" for none) and mask_inputs_flip_test. Throws Error on a
  /// malformed list.
  void set_mask_inputs(const std::string& list, bool flip_test = true);

  /// Weights and configuration in one libtorch archive (written atomically).
  void save(const std::filesystem::path& path) const;
  /// The network as an ONNX graph for OpenCV DNN (center_onnx.hpp says what it holds).
  /// Throws Error(path) when the file cannot be written or cropsight was built without
  /// libonnx-dev.
  void export_onnx(const std::filesystem::path& path) const;
  /// A model written by save(); `threads` replaces the saved thread count. Throws Error naming
  /// the file (missing, not a cropsight detector, weights that do not fit).
  static CenterNet load(const std::filesystem::path& path, int threads = 1);

 private:
  CenterNet();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cropsight::nn
