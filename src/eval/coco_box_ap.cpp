#include "cropsight/eval/coco_box_ap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace cropsight::eval {

namespace {
struct RankedDet {
  float score;
  bool tp;
};

// COCOeval.evaluateImg for one image at threshold t: per detection (by decreasing score) TP or FP.
void match_image(const CocoApImage& im, double t, int max_det, std::vector<RankedDet>& out) {
  std::vector<std::size_t> order(im.detections.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return im.detections[a].score > im.detections[b].score; });
  if (order.size() > std::size_t(max_det)) order.resize(std::size_t(max_det));
  std::vector<char> matched(im.truth.size(), 0);
  const double thr = std::min(t, 1 - 1e-10);
  for (auto d : order) {
    double best = thr;
    int m = -1;
    for (std::size_t g = 0; g < im.truth.size(); ++g) {
      if (matched[g]) continue;
      const double v = iou(im.detections[d], im.truth[g]);
      if (v < best) continue;
      best = v;
      m = int(g);
    }
    if (m >= 0) matched[std::size_t(m)] = 1;
    out.push_back({im.detections[d].score, m >= 0});
  }
}
}  // namespace

double coco_box_ap(const std::vector<CocoApImage>& images, double iou_threshold, int max_detections) {
  std::int64_t truths = 0;
  std::vector<RankedDet> ranked;
  for (const auto& im : images) {
    truths += std::int64_t(im.truth.size());
    match_image(im, iou_threshold, max_detections, ranked);
  }
  if (truths == 0) return std::numeric_limits<double>::quiet_NaN();
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const RankedDet& a, const RankedDet& b) { return a.score > b.score; });
  std::vector<double> rc(ranked.size()), pr(ranked.size());
  std::int64_t tp = 0;
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    tp += ranked[i].tp ? 1 : 0;
    rc[i] = double(tp) / double(truths);
    pr[i] = double(tp) / double(i + 1);
  }
  for (std::size_t i = pr.size(); i-- > 1;) pr[i - 1] = std::max(pr[i - 1], pr[i]);
  double sum = 0;
  for (int k = 0; k <= 100; ++k) {
    // np.linspace(0, 1, 101) then searchsorted(rc, r, side='left')
    const double r = k == 100 ? 1.0 : double(k) * 0.01;
    const auto it = std::lower_bound(rc.begin(), rc.end(), r);
    if (it != rc.end()) sum += pr[std::size_t(it - rc.begin())];
  }
  return sum / 101.0;
}

CocoApSummary coco_box_ap_summary(const std::vector<CocoApImage>& images, int max_detections) {
  CocoApSummary s;
  s.images = std::int64_t(images.size());
  for (const auto& im : images) {
    s.truths += std::int64_t(im.truth.size());
    s.detections += std::int64_t(std::min(im.detections.size(), std::size_t(max_detections)));
  }
  s.ap50 = coco_box_ap(images, 0.5, max_detections);
  s.ap75 = coco_box_ap(images, 0.75, max_detections);
  double sum = 0;
  for (int k = 0; k < 10; ++k) sum += coco_box_ap(images, 0.5 + 0.05 * k, max_detections);
  s.ap50_95 = sum / 10.0;
  return s;
}

}  // namespace cropsight::eval
