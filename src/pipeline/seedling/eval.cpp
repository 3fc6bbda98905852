#include "cropsight/pipeline/seedling/eval.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "cropsight/core/timer.hpp"
#include "cropsight/segmentation/gmm.hpp"
#include "cropsight/stereo/reconstruct.hpp"

namespace cropsight::pipeline::seedling {

namespace {

// The true top view: the seedling as the left camera sees it (true disparity inside the true mask).
std::vector<Eigen::Vector3d> true_points(const Truth& truth, const stereo::RectifiedGeometry& geo) {
  stereo::DisparityImage masked = truth.disparity;
  for (std::size_t i = 0; i < masked.size(); ++i)
    if (!truth.mask.data[i]) masked.data[i] = std::nanf("");
  const stereo::StereoPoints sp = stereo::reconstruct(masked, geo);
  std::vector<Eigen::Vector3d> tp;
  for (const auto& p : sp.points) tp.push_back(p.cast<double>());
  return tp;
}

double stage_ms(const StageTimer& t, const std::string& name) {
  double ms = 0;
  for (const auto& s : t.stages())
    if (s.name == name) ms += s.total_ms;
  return ms;
}

}  // namespace

Score score(const FrameResult& det, const Truth& truth, const stereo::RectifiedGeometry& geo, double cell) {
  Score s;
  const std::vector<Eigen::Vector3d> tp = true_points(truth, geo);
  const std::vector<Eigen::Vector3d> dp = [&] {
    std::vector<Eigen::Vector3d> v;
    for (const auto& p : det.points) v.push_back(p.cast<double>());
    return v;
  }();
  if (truth.envelope.volume() > 0) s.volume_ratio = det.envelope.volume() / truth.envelope.volume();
  if (tp.empty()) return s;
  const Eigen::Vector3d& n = truth.plane_normal;
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto* set : {&tp, &dp})
    for (const auto& p : *set) {
      const Eigen::Vector2d q(e1.dot(p), e2.dot(p));
      lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    }
  const Eigen::Vector2d origin = lo - Eigen::Vector2d::Constant(2 * cell);
  const int w = int((hi.x() - lo.x()) / cell) + 5, h = int((hi.y() - lo.y()) / cell) + 5;
  if (double(w) * h > 4e7) return s;  // detection far from the truth: no overlap worth rasterising
  const TopViewMask a = rasterize_top_view(tp, n, cell, origin, w, h);
  const TopViewMask b = rasterize_top_view(dp, n, cell, origin, w, h);
  long inter = 0, uni = 0, area = 0;
  for (std::size_t i = 0; i < a.mask.size(); ++i) {
    const bool x = a.mask.data[i], y = b.mask.data[i];
    inter += x && y;
    uni += x || y;
    area += x;
  }
  s.iou = uni ? double(inter) / double(uni) : 0;
  s.sensitivity = area ? double(inter) / double(area) : 0;
  s.recognised = s.iou >= 0.5;
  return s;
}

Evaluator::Evaluator(const segmentation::GmmConfig& gmm, Options options) : gmm_(gmm), opt_(options) {}

const PairResult& Evaluator::add(const std::string& pair, const FrameResult& det, const Truth& truth,
                                 const stereo::RectifiedGeometry& geo) {
  const Score s = score(det, truth, geo, opt_.cell);
  Figures& e = sums_;
  ++e.pairs;
  e.recognition_rate += s.recognised;
  e.sensitivity += s.sensitivity;
  e.volume_ratio += s.volume_ratio;
  e.ms_total += det.timer.total_ms();
  e.ms_sgm += stage_ms(det.timer, "disparity");
  e.ms_gmm += stage_ms(det.timer, "gmm");
  if (opt_.compare_opencv_em && int(det.sampled.size()) >= gmm_.components) {
    StageTimer t;
    segmentation::GmmResult ref;
    {
      auto scope = t.scope("em");
      ref = segmentation::fit_gmm_opencv(det.sampled, gmm_, nullptr, pair);
    }
    e.ms_gmm_opencv += t.total_ms();
    e.gmm_opencv_mean_log_likelihood += ref.log_likelihood;
    e.gmm_mean_log_likelihood += det.gmm.log_likelihood;
    ++e.opencv_runs;
  }
  e.per_pair.push_back({pair, s, det.timer.total_ms(), det.gmm.iterations});
  return e.per_pair.back();
}

Figures Evaluator::figures() const {
  Figures e = sums_;
  if (e.pairs > 0) {
    const double n = double(e.pairs);
    for (double* v : {&e.recognition_rate, &e.sensitivity, &e.volume_ratio, &e.ms_total, &e.ms_sgm, &e.ms_gmm}) *v /= n;
  }
  if (e.opencv_runs > 0) {
    const double n = double(e.opencv_runs);
    for (double* v : {&e.ms_gmm_opencv, &e.gmm_mean_log_likelihood, &e.gmm_opencv_mean_log_likelihood}) *v /= n;
  }
  return e;
}

Figures evaluate_seedling_dataset(const Dataset& data, const Pipeline& pipeline, const Evaluator::Options& options,
                                  const std::function<void(int)>& progress) {
  Evaluator ev(pipeline.config().gmm, options);
  for (std::size_t k = 0; k < data.pairs.size(); ++k) {
    const auto& p = data.pairs[k];
    // Images are read before the pipeline runs: its timings exclude I/O.
    const auto [left, right] = read_pair(p);
    const Truth truth = read_truth(p);
    ev.add(p.filename().string(), pipeline.process(left, right, data.geometry, p.string()), truth, data.geometry);
    if (progress) progress(int(k + 1));
  }
  return ev.figures();
}

}  // namespace cropsight::pipeline::seedling
