#include "cropsight/pipeline/broccoli/detector.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "core/cpu_dispatch.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/eval/detection_ap.hpp"  // point_set_iou
#include "cropsight/geometry/concave_creases.hpp"
#include "cropsight/geometry/depth_filter.hpp"  // valid_indices
#include "cropsight/geometry/integral_normals.hpp"
#include "cropsight/geometry/organized_edges.hpp"
#include "cropsight/geometry/statistical_outlier.hpp"
#include "cropsight/nn/center_decode.hpp"
#include "cropsight/nn/center_onnx.hpp"
#include "cropsight/pipeline/broccoli/depth_encoding.hpp"
#include "cropsight/segmentation/euclidean_clustering.hpp"
#include "cropsight/segmentation/organized_clustering.hpp"
#include "cropsight/segmentation/segment_growth.hpp"

namespace cropsight::pipeline::broccoli {

namespace {
bool same_camera(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy && a.cx == b.cx && a.cy == b.cy;
}

// Deprojection and the depth-range filter of n pixels: z = d·scale, NaN when d = 0 or outside
// [lo, hi]; x = rx·z, y = ry·z. Branch-free with restrict pointers so that it vectorises (AVX2
// clone at run time); every lane does the scalar loop's float operations (no FMA), so the values
// are bit-identical to it (tests/pipeline checks the cloud against that loop).
CROPSIGHT_AVX2_CLONES void deproject_depth(std::size_t n, const std::uint16_t* __restrict d, const float* __restrict rx,
                                           const float* __restrict ry, float scale, float lo, float hi,
                                           float* __restrict X, float* __restrict Y, float* __restrict Z) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < n; ++i) {
    const float zd = float(d[i]) * scale;
    const float z = (d[i] != 0) & (zd >= lo) & (zd <= hi) ? zd : nan;
    Z[i] = z;
    X[i] = rx[i] * z;
    Y[i] = ry[i] * z;
  }
}
// The `fraction` percentile of the valid (non-zero) raw depths, in metres, from a histogram of
// 5 mm bins over every 4th row (a quarter of the cost: the cloud stage on uk-2001 took 0.41-0.45 ms
// with every row, 0.26-0.28 ms with every 4th); NaN with fewer than 1000 valid pixels in the frame
// (estimated from the rows read).
float depth_percentile(const std::vector<std::uint16_t>& depth, int width, int height, float scale, float fraction,
                       std::vector<std::uint32_t>& hist) {
  constexpr float kBin = 0.005f;
  constexpr int kRowStep = 4;
  const float per_raw = scale / kBin;
  hist.assign(std::size_t(65535 * per_raw) + 2, 0);
  std::size_t valid = 0;
  for (int v = 0; v < height; v += kRowStep) {
    const std::uint16_t* row = depth.data() + std::size_t(v) * std::size_t(width);
    for (int u = 0; u < width; ++u)
      if (const std::uint16_t d = row[u]) ++hist[std::size_t(float(d) * per_raw)], ++valid;
  }
  if (valid * kRowStep < 1000) return std::numeric_limits<float>::quiet_NaN();
  const auto target = std::size_t(double(valid) * fraction);
  std::size_t seen = 0;
  for (std::size_t b = 0; b < hist.size(); ++b) {
    seen += hist[b];
    if (seen > target) return (float(b) + 0.5f) * kBin;
  }
  return (float(hist.size()) - 0.5f) * kBin;
}
}  // namespace

Detector::Detector(DetectorConfig cfg) : cfg_(std::move(cfg)) {
  cfg_.validate("config");
  feature_set_ = features::FeatureSet::parse(cfg_.features, "config");
  normals_ = std::make_unique<geometry::IntegralNormalEstimator>(cfg_.normals);
  if (!cfg_.cnn.model.empty()) {
    if (std::filesystem::path(cfg_.cnn.model).extension() != ".onnx")
      throw Error(cfg_.cnn.model, "cnn.model must be an .onnx file (cropsight export-detector)");
    cnn_ = std::make_unique<nn::CenterNetOnnx>(cfg_.cnn.model);
    if (cnn_->class_names() != std::vector<std::string>{"head"})
      throw Error(cfg_.cnn.model, "cnn.model must be a detector of the one class 'head'");
  }
}

Detector::~Detector() = default;

std::size_t Detector::feature_dimension() const { return feature_set_.dimension(); }

void Detector::set_model(std::shared_ptr<const learning::Model> model, const std::string& where) {
  if (model) {
    learning::require_compatible(model->info, kBroccoliTask, config_name(cfg_.pipeline), cfg_.feature_names(),
                                 int(feature_set_.dimension()), where);
  }
  model_ = std::move(model);
}

void Detector::make_cloud(const RgbdFrame& frame) {
  const int w = frame.depth.width, h = frame.depth.height;
  if (w != frame.camera.width || h != frame.camera.height)
    throw Error("frame " + std::to_string(frame.index), "depth image size differs from the camera's");
  const std::size_t n = std::size_t(w) * std::size_t(h);
  if (!same_camera(ray_camera_, frame.camera) || ray_x_.size() != n) {
    // Per-pixel ray slopes, computed once per camera: deprojection is then two multiplies.
    ray_x_.resize(n);
    ray_y_.resize(n);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        ray_x_[std::size_t(v) * w + u] = float((u - frame.camera.cx) / frame.camera.fx);
        ray_y_[std::size_t(v) * w + u] = float((v - frame.camera.cy) / frame.camera.fy);
      }
    ray_camera_ = frame.camera;
  }
  cloud_.width = w;
  cloud_.height = h;
  cloud_.x.resize(n);
  cloud_.y.resize(n);
  cloud_.z.resize(n);
  // Deprojection and the depth-range filter in one pass: the same float values as deprojecting
  // and then calling geometry::filter_depth_range (z = d·scale, NaN outside [min, max]).
  if (!(cfg_.depth.min_depth <= cfg_.depth.max_depth))
    throw Error("depth range", "min_depth must not exceed max_depth");
  // Range-aware options: the window's far end and the OES thresholds follow the soil's depth.
  float max_depth = cfg_.depth.max_depth;
  oes_frame_ = cfg_.oes;
  soil_depth_ = std::numeric_limits<float>::quiet_NaN();
  const RangeConfig& rc = cfg_.range;
  if (rc.soil_relative || rc.reference_range > 0.0f) {
    soil_depth_ =
        depth_percentile(frame.depth.data, w, h, float(frame.camera.depth_scale), rc.soil_percentile, depth_histogram_);
    if (std::isfinite(soil_depth_)) {
      if (rc.soil_relative) {
        const float floor = rc.extend_only ? cfg_.depth.max_depth : cfg_.depth.min_depth;
        max_depth = std::max(floor, soil_depth_ - rc.min_height_above_soil);
      }
      if (rc.reference_range > 0.0f) {
        const float r = std::max(cfg_.depth.min_depth + 0.1f, soil_depth_ - rc.head_height);
        const float s = r / rc.reference_range;
        auto points = [&](int p) { return p > 0 ? std::max(1, int(std::lround(float(p) / (s * s)))) : p; };
        oes_frame_.min_size = points(cfg_.oes.min_size);
        oes_frame_.min_size_border = points(cfg_.oes.min_size_border);
        oes_frame_.max_size = std::max(oes_frame_.min_size, points(cfg_.oes.max_size));
        oes_frame_.distance_tolerance = cfg_.oes.distance_tolerance * s;
      }
    }
  }
  // Noise-adaptive denoising (denoise.above > 0): only a frame noisier than the threshold is filtered.
  const std::uint16_t* depth = frame.depth.data.data();
  noise_sigma_ = std::numeric_limits<float>::quiet_NaN();
  denoised_frame_ = false;
  if (cfg_.denoise.above > 0.0f) {
    auto t = timer_.scope("denoise");
    const float scale = float(frame.camera.depth_scale);
    noise_sigma_ = estimate_depth_noise(frame.depth.data, w, h, scale, cfg_.depth.min_depth, max_depth, noise_bins_);
    if (noise_sigma_ > cfg_.denoise.above) {
      bilateral_depth(frame.depth.data, w, h, scale, cfg_.denoise.sigma_factor * noise_sigma_, cfg_.denoise.diameter,
                      cfg_.denoise.sigma_space, denoised_);
      depth = denoised_.data();
      denoised_frame_ = true;
    }
  }
  deproject_depth(n, depth, ray_x_.data(), ray_y_.data(), float(frame.camera.depth_scale), cfg_.depth.min_depth,
                  max_depth, cloud_.x.data(), cloud_.y.data(), cloud_.z.data());
  if (!frame.labels.empty()) {
    if (frame.labels.width != w || frame.labels.height != h)
      throw Error("frame " + std::to_string(frame.index), "label image size differs from the depth image");
    cloud_.labels.assign(frame.labels.data.begin(), frame.labels.data.end());
  } else {
    cloud_.labels.clear();
  }
}

void Detector::normals(std::span<const int> select) {
  auto t = timer_.scope("normals");
  normals_->compute(cloud_, select);
}

void Detector::cluster() {
  switch (cfg_.pipeline) {
    case Variant::oes:
      cluster_oes();
      return;
    case Variant::org:
      cluster_org();
      return;
    case Variant::fec:
      cluster_fec();
      return;
  }
}

void Detector::cluster_oes() {
  // OES segments without normals (unless crease edges need the curvature): the normals are then
  // computed only for the pixels of the kept segments, the only ones VFH reads.
  const bool lazy = !(cfg_.edges.high_curvature_threshold > 0.0f);
  if (!lazy) normals();
  {
    auto t = timer_.scope("edges");
    geometry::detect_organized_edges(cloud_, cfg_.edges, edges_);
  }
  {
    auto t = timer_.scope("clustering");
    segments_ = segmentation::segment_oes(cloud_, edges_, oes_frame_, flood_);
    if (oes_frame_.debris_tolerance > 0.0f) segment_debris();
  }
  if (lazy) normals(flood_.labels);
}

void Detector::segment_debris() {
  // The pixels of kept segments become a barrier (a bit no edge label uses) for the second pass.
  constexpr std::uint8_t kKept = 0x80;
  const std::size_t n = edges_.size();
  debris_edges_.resize(n);
  kept_labels_.assign(flood_.labels.begin(), flood_.labels.end());
  for (std::size_t i = 0; i < n; ++i) debris_edges_[i] = std::uint8_t(edges_[i] | (kept_labels_[i] >= 0 ? kKept : 0));
  segmentation::OesConfig second = oes_frame_;
  second.distance_tolerance = oes_frame_.debris_tolerance;
  second.barrier_labels = oes_frame_.barrier_labels | kKept;
  std::vector<Segment> more = segmentation::segment_oes(cloud_, debris_edges_, second, flood_);
  // One label image for both passes (the lazy normals select by it): second-pass ids follow the first's.
  const int offset = int(segments_.size());
  for (std::size_t i = 0; i < n; ++i)
    if (flood_.labels[i] >= 0) kept_labels_[i] = flood_.labels[i] + offset;
  flood_.labels.swap(kept_labels_);
  for (Segment& s : more) segments_.push_back(std::move(s));
}

void Detector::cluster_org() {
  normals();
  auto t = timer_.scope("clustering");
  segments_ = segmentation::segment_org(cloud_, cfg_.org, flood_);
}

void Detector::cluster_fec() {
  normals();
  valid_ = geometry::valid_indices(cloud_);
  if (cfg_.outliers.enabled) {
    auto t = timer_.scope("outliers");
    valid_ = geometry::remove_statistical_outliers(cloud_, valid_, cfg_.outliers.sor);
  }
  auto t = timer_.scope("clustering");
  segments_ = segmentation::euclidean_clusters(cloud_, valid_, cfg_.fec);
}

std::span<const Candidate> Detector::process(const RgbdFrame& frame) {
  {
    auto t = timer_.scope("cloud");
    make_cloud(frame);
  }
  cluster();
  count_ = segments_.size();
  if (candidates_.size() < count_) candidates_.resize(count_);
  {
    auto t = timer_.scope("features");
    for (std::size_t k = 0; k < count_; ++k) {
      Candidate& c = candidates_[k];
      c.proposed = false;
      std::swap(c.segment, segments_[k]);  // keeps the pool's old index buffer in segments_
      // The organised clusterings return ascending indices already; FEC's are sorted here.
      if (!std::is_sorted(c.segment.indices.begin(), c.segment.indices.end()))
        std::sort(c.segment.indices.begin(), c.segment.indices.end());
      const int oversized_above = cfg_.detection.split_oversized_above;
      c.oversized = oversized_above > 0 && int(c.segment.size()) > oversized_above;
      if (c.oversized) {
        c.described = false;  // never a head: the lowest score, and only the split looks inside it
        c.normal_points = -1;
        continue;
      }
      describe(c);
    }
  }
  {
    auto t = timer_.scope("classify");
    batch_input_.clear();
    for (std::size_t k = 0; k < count_; ++k) batch_input_.push_back(&candidates_[k]);
    classify_all(batch_input_, head_threshold());
  }
  if (cfg_.detection.split_concave_angle_deg > 0.0f && model_ && cfg_.pipeline == Variant::oes) split_at_creases();
  if (cfg_.detection.grow_tolerance > 0.0f) complete_heads();
  if (cnn_) add_cnn_heads(frame);
  return {candidates_.data(), count_};
}

void Detector::describe(Candidate& c) {
  feature_set_.compute(cloud_, c.segment.indices, cfg_.feature_options, c.features);
  c.normal_points = -1;  // not counted unless detection.min_normal_points asks for it
  c.described = true;
  if (cfg_.detection.min_normal_points > 0) {
    int with_normal = 0;
    for (int i : c.segment.indices) with_normal += std::isfinite(cloud_.nx[std::size_t(i)]) ? 1 : 0;
    c.normal_points = with_normal;
    c.described = with_normal >= cfg_.detection.min_normal_points;
  }
}

float Detector::head_threshold() const { return model_ ? model_->threshold() + cfg_.detection.score_margin : 0.0f; }

void Detector::classify(Candidate& c, float threshold) {
  // A cluster without normals has an all-zero VFH, the same vector for every such sliver: an
  // RBF SVM answers it with whatever its nearest support vector says (measured: 1.0, a head).
  if (!c.described) {
    c.score = -std::numeric_limits<float>::max();
    c.head = false;
    return;
  }
  c.score = model_ ? model_->score(c.features, scratch_) : 0.0f;
  c.head = model_ && c.score > threshold;
}

void Detector::classify_all(std::span<Candidate* const> cands, float threshold) {
  batch_.clear();
  batch_rows_.clear();
  for (Candidate* c : cands) {
    if (!model_ || !c->described) {
      classify(*c, threshold);
      continue;
    }
    batch_.push_back(c);
    batch_rows_.insert(batch_rows_.end(), c->features.begin(), c->features.end());
  }
  if (batch_.empty()) return;
  batch_scores_.resize(batch_.size());
  model_->score_rows(batch_rows_, batch_scores_, scratch_);
  for (std::size_t k = 0; k < batch_.size(); ++k) {
    batch_[k]->score = batch_scores_[k];
    batch_[k]->head = batch_scores_[k] > threshold;
  }
}

void Detector::split_at_creases() {
  auto t = timer_.scope("split");
  split_targets_.clear();
  segment_ptrs_.clear();
  crease_marks_.assign(cloud_.size(), 0);
  const DetectionConfig& dc = cfg_.detection;
  const geometry::ConcaveCreaseOptions creases{dc.split_concave_angle_deg, dc.split_concave_step};
  const float head = head_threshold();
  for (std::size_t k = 0; k < count_; ++k) {
    segment_ptrs_.push_back(&candidates_[k].segment);
    const Candidate& c = candidates_[k];
    if (!c.oversized) {
      if (!c.described || int(c.segment.size()) < dc.split_min_points) continue;
      if (c.head && !dc.split_accepted) continue;
      // Only scores near the threshold: a head joined to a leaf scores between a leaf and a head.
      if (dc.split_score_window > 0.0f && std::fabs(c.score - head) > dc.split_score_window) continue;
    }
    split_targets_.push_back(int(k));
    geometry::mark_concave_creases(cloud_, candidates_[k].segment.indices, creases, crease_marks_);
  }
  if (split_targets_.empty()) return;
  std::vector<segmentation::SplitPiece> split =
      segmentation::split_segments(cloud_, segment_ptrs_, split_targets_, crease_marks_, oes_frame_.distance_tolerance,
                                   oes_frame_.min_size, oes_frame_.max_size, split_ws_);
  // Classify the pieces; a cluster is replaced by its pieces when one of them is a head. A piece
  // that keeps most of its cluster (all of it: no crease) is that cluster again, which is no head:
  // it is not classified (saves most of the stage's time).
  const float threshold = head + dc.split_score_margin;
  if (pieces_.size() < split.size()) pieces_.resize(split.size());
  // Per candidate: kKeep, kReplace (a piece is a head), kSlotTaken (its first piece took its slot).
  enum : char { kKeep = 0, kReplace = 1, kSlotTaken = 2 };
  std::vector<char>& replace = split_replace_;
  replace.assign(count_, 0);
  split_scored_.assign(split.size(), 0);
  batch_input_.clear();
  for (std::size_t i = 0; i < split.size(); ++i) {
    Candidate& piece = pieces_[i];
    const std::size_t parent = std::size_t(split[i].parent);
    std::swap(piece.segment, split[i].segment);
    piece.oversized = piece.proposed = false;  // the slot may hold a candidate of an earlier frame
    if (double(piece.segment.size()) > double(dc.split_max_piece_fraction) * double(candidates_[parent].segment.size()))
      continue;
    describe(piece);
    batch_input_.push_back(&piece);
    split_scored_[i] = 1;
  }
  classify_all(batch_input_, threshold);
  // A head cluster (split_accepted) gives way only to a piece that is more head-like than itself.
  for (std::size_t i = 0; i < split.size(); ++i) {
    const Candidate& parent = candidates_[std::size_t(split[i].parent)];
    if (split_scored_[i] && pieces_[i].head && (!parent.head || pieces_[i].score > parent.score))
      replace[std::size_t(split[i].parent)] = kReplace;
  }
  // The replaced cluster's pixels are freed in the owner map (the completion reads it), then the
  // pieces take theirs: the first piece takes the cluster's slot, the others are appended.
  for (std::size_t k = 0; k < count_; ++k)
    if (replace[k] == kReplace)
      for (int i : candidates_[k].segment.indices) flood_.labels[std::size_t(i)] = -1;
  for (std::size_t i = 0; i < split.size(); ++i) {
    const std::size_t parent = std::size_t(split[i].parent);
    if (replace[parent] == kKeep) continue;
    if (!split_scored_[i]) {  // the large remainder beside a head piece (rare): scored now
      describe(pieces_[i]);
      classify(pieces_[i], threshold);
    }
    std::size_t at = count_;
    if (replace[parent] == kReplace) {
      at = parent;
      replace[parent] = kSlotTaken;
    } else {
      if (candidates_.size() <= count_) candidates_.resize(count_ + 1);
      ++count_;
    }
    std::swap(candidates_[at], pieces_[i]);
    for (int idx : candidates_[at].segment.indices) flood_.labels[std::size_t(idx)] = int(at);
  }
}

void Detector::complete_heads() {
  auto t = timer_.scope("completion");
  grow_order_.clear();
  segment_ptrs_.clear();
  for (std::size_t k = 0; k < count_; ++k) {
    segment_ptrs_.push_back(&candidates_[k].segment);
    if (candidates_[k].head) grow_order_.push_back(int(k));
  }
  if (grow_order_.empty()) return;
  // The most confident head claims contested debris first.
  std::stable_sort(grow_order_.begin(), grow_order_.end(),
                   [&](int a, int b) { return candidates_[std::size_t(a)].score > candidates_[std::size_t(b)].score; });
  const segmentation::SegmentGrowthOptions options{cfg_.detection.grow_tolerance, cfg_.detection.grow_radius};
  // The organised clusterings' label image is already the owner map (segment k = candidate k); it
  // is not read again after the normals.
  if (cfg_.pipeline == Variant::fec)
    segmentation::grow_into_free_pixels(cloud_, segment_ptrs_, grow_order_, options, growth_);
  else
    segmentation::grow_into_free_pixels(cloud_, segment_ptrs_, grow_order_, options, flood_.labels, growth_.queue);
}

void Detector::add_cnn_heads(const RgbdFrame& frame) {
  auto t = timer_.scope("cnn");
  const ColorImage image = encode_depth_for_cnn(frame.depth, frame.camera.depth_scale);
  const nn::CenterNetHeads heads = cnn_->heads(image);
  const nn::CenterNetConfig& net = cnn_->config();
  const std::vector<Detection2D> boxes = nn::boxes_from_heads(heads, net, image.width, image.height);
  const std::vector<GrayImage> masks = nn::masks_from_heads(heads, net, image.width, image.height);
  const CnnConfig& cc = cfg_.cnn;
  // Ranks every proposal after the classifier's heads (scores above the threshold), in the CNN's order.
  const float head = head_threshold();
  for (const Detection2D& b : boxes) {  // highest score first
    if (b.score < cc.min_score) break;
    std::vector<int> pixels = mask_points_in_box(b, masks.front(), cloud_.z);  // ascending, as Segment's
    if (int(pixels.size()) < cc.min_points) continue;
    bool duplicate = false;
    for (std::size_t k = 0; k < count_ && !duplicate; ++k)
      duplicate = candidates_[k].head && eval::point_set_iou(pixels, candidates_[k].segment.indices) > cc.max_overlap;
    if (duplicate) continue;
    // The proposal takes its pixels from the rejected clusters it overlaps (a head the clustering
    // joined to leaves): every pixel stays in one candidate; the remainder keeps its rejection.
    for (std::size_t k = 0; k < count_; ++k) {
      Segment& s = candidates_[k].segment;
      if (candidates_[k].head || !eval::point_set_iou(pixels, s.indices)) continue;
      std::vector<int>& rest = cnn_rest_;
      rest.clear();
      std::set_difference(s.indices.begin(), s.indices.end(), pixels.begin(), pixels.end(), std::back_inserter(rest));
      s.indices.swap(rest);
      summarize(s, cloud_);
    }
    // A cluster the proposal took whole is gone (the pool's last candidate takes its slot).
    for (std::size_t k = 0; k < count_;)
      if (candidates_[k].segment.indices.empty())
        std::swap(candidates_[k], candidates_[--count_]);
      else
        ++k;
    if (candidates_.size() <= count_) candidates_.resize(count_ + 1);
    Candidate& c = candidates_[count_++];
    c.segment.indices = std::move(pixels);
    summarize(c.segment, cloud_);
    c.features.clear();
    c.normal_points = -1;
    c.described = false;
    c.oversized = false;
    c.proposed = true;
    c.head = true;
    c.score = std::nextafter(head, std::numeric_limits<float>::infinity()) + 1e-3f * b.score;
  }
}

std::vector<Detection> Detector::detections() const {
  std::vector<Detection> out;
  for (std::size_t k = 0; k < count_; ++k) {
    const Candidate& c = candidates_[k];
    if (!c.head) continue;
    Detection d;
    d.score = c.score;
    d.label = 1;
    d.centroid = c.segment.centroid;
    d.box = c.segment.box;
    d.indices = c.segment.indices;
    out.push_back(std::move(d));
  }
  std::stable_sort(out.begin(), out.end(), [](const Detection& a, const Detection& b) { return a.score > b.score; });
  return out;
}

}  // namespace cropsight::pipeline::broccoli
