// pascalvoc.py's matching (see the header), then the shared all-point AP of detection_ap.
#include "cropsight/eval/voc_ap.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cropsight/eval/detection_ap.hpp"

namespace cropsight::eval {

double voc_iou(const VocBox& a, const VocBox& b) {
  if (a.x1 > b.x2 || b.x1 > a.x2 || a.y2 < b.y1 || a.y1 > b.y2) return 0.0;
  const double inter =
      (std::min(a.x2, b.x2) - std::max(a.x1, b.x1) + 1) * (std::min(a.y2, b.y2) - std::max(a.y1, b.y1) + 1);
  const double area_a = (a.x2 - a.x1 + 1) * (a.y2 - a.y1 + 1), area_b = (b.x2 - b.x1 + 1) * (b.y2 - b.y1 + 1);
  return inter / (area_a + area_b - inter);
}

double voc_ap(const std::vector<VocImage>& images, double iou_threshold) {
  struct Ref {
    std::size_t image, det;
    double score;
  };
  std::vector<Ref> order;
  std::int64_t num_truth = 0;
  for (std::size_t i = 0; i < images.size(); ++i) {
    num_truth += std::int64_t(images[i].truth.size());
    for (std::size_t d = 0; d < images[i].detections.size(); ++d)
      order.push_back({i, d, images[i].detections[d].score});
  }
  // Ranked on the double scores here: RankedHit keeps a float, which could merge two scores that
  // differ in the 8th digit; the float order of an already sorted list is still non-increasing,
  // so average_precision's stable sort keeps this order.
  std::stable_sort(order.begin(), order.end(), [](const Ref& a, const Ref& b) { return a.score > b.score; });
  std::vector<std::vector<char>> matched(images.size());
  for (std::size_t i = 0; i < images.size(); ++i) matched[i].assign(images[i].truth.size(), 0);

  std::vector<RankedHit> ranked;
  ranked.reserve(order.size());
  for (const Ref& r : order) {
    const VocImage& img = images[r.image];
    const VocBox& det = img.detections[r.det];
    double best = 0.0;
    std::size_t best_j = 0;
    bool any = false;
    for (std::size_t j = 0; j < img.truth.size(); ++j) {
      const double v = voc_iou(det, img.truth[j]);
      if (v > best) best = v, best_j = j, any = true;  // strict: the first truth wins ties
    }
    bool tp = false;
    if (any && best >= iou_threshold && !matched[r.image][best_j]) tp = true, matched[r.image][best_j] = 1;
    ranked.push_back({float(r.score), tp});
  }
  return average_precision(std::move(ranked), num_truth);
}

VocApSummary voc_ap_summary(const std::vector<VocImage>& images) {
  VocApSummary s;
  s.images = std::int64_t(images.size());
  for (const VocImage& img : images) {
    s.truths += std::int64_t(img.truth.size());
    s.detections += std::int64_t(img.detections.size());
  }
  s.ap50 = voc_ap(images, 0.5);
  s.ap75 = voc_ap(images, 0.75);
  double sum = 0.0;
  // (50 + 5i) / 100 is the correctly rounded threshold (0.5 + 0.05·i accumulates error).
  for (int i = 0; i < 10; ++i) sum += voc_ap(images, double(50 + 5 * i) / 100.0);
  s.map50_95 = sum / 10.0;
  return s;
}

}  // namespace cropsight::eval
