#include "cropsight/eval/detection_ap.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace cropsight::eval {

double point_set_iou(std::span<const int> a, std::span<const int> b) {
  if (a.empty() && b.empty()) return 0.0;
  // Merge-count on sorted copies when needed (detections arrive in flood-fill order).
  std::vector<int> sa, sb;
  if (!std::is_sorted(a.begin(), a.end())) {
    sa.assign(a.begin(), a.end());
    std::sort(sa.begin(), sa.end());
    a = sa;
  }
  if (!std::is_sorted(b.begin(), b.end())) {
    sb.assign(b.begin(), b.end());
    std::sort(sb.begin(), sb.end());
    b = sb;
  }
  std::size_t i = 0, j = 0, inter = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i] < b[j])
      ++i;
    else if (b[j] < a[i])
      ++j;
    else
      ++inter, ++i, ++j;
  }
  return double(inter) / double(a.size() + b.size() - inter);
}

double average_precision(std::vector<RankedHit> ranked, std::int64_t num_truth) {
  if (num_truth <= 0) return NAN;
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const RankedHit& x, const RankedHit& y) { return x.score > y.score; });
  const std::size_t n = ranked.size();
  std::vector<double> precision(n), recall(n);
  std::int64_t tp = 0;
  for (std::size_t i = 0; i < n; ++i) {
    tp += ranked[i].correct;
    precision[i] = double(tp) / double(i + 1);
    recall[i] = double(tp) / double(num_truth);
  }
  // Precision envelope: the best precision at this recall or any higher one.
  for (std::size_t i = n; i-- > 1;) precision[i - 1] = std::max(precision[i - 1], precision[i]);
  double ap = 0.0, prev_recall = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    ap += (recall[i] - prev_recall) * precision[i];
    prev_recall = recall[i];
  }
  return ap;
}

void DetectionApAccumulator::add_frame(const std::vector<std::vector<int>>& truth,
                                       const std::vector<Scored>& detections, const std::vector<bool>& ignored) {
  const int frame = int(frame_truths_.size());
  frame_truths_.push_back(int(truth.size()));
  frame_first_det_.push_back(std::int64_t(dets_.size()));
  std::vector<char> ign(truth.size(), 0);
  for (std::size_t t = 0; t < truth.size() && t < ignored.size(); ++t) ign[t] = ignored[t] ? 1 : 0;
  for (char i : ign) num_truth_ += i ? 0 : 1;
  frame_ignored_.push_back(std::move(ign));
  for (const Scored& d : detections) {
    Det det{frame, d.score, std::int64_t(pairs_.size()), 0};
    for (std::size_t t = 0; t < truth.size(); ++t) {
      const double iou = point_set_iou(d.indices, truth[t]);
      if (iou > 0.0) pairs_.push_back({int(t), iou});
    }
    det.num_pairs = std::int64_t(pairs_.size()) - det.first_pair;
    std::sort(pairs_.begin() + det.first_pair, pairs_.end(),
              [](const Pair& a, const Pair& b) { return a.iou > b.iou || (a.iou == b.iou && a.truth < b.truth); });
    dets_.push_back(det);
  }
}

std::vector<char> DetectionApAccumulator::correct_at(double t) const {
  std::vector<char> correct(dets_.size(), 0);
  const std::size_t frames = frame_truths_.size();
  std::vector<std::int64_t> order;
  std::vector<char> matched;
  for (std::size_t f = 0; f < frames; ++f) {
    const std::int64_t b = frame_first_det_[f];
    const std::int64_t e = f + 1 < frames ? frame_first_det_[f + 1] : std::int64_t(dets_.size());
    order.resize(std::size_t(e - b));
    std::iota(order.begin(), order.end(), b);
    std::stable_sort(order.begin(), order.end(), [&](std::int64_t x, std::int64_t y) {
      return dets_[std::size_t(x)].score > dets_[std::size_t(y)].score;
    });
    matched.assign(std::size_t(frame_truths_[f]), 0);
    const std::vector<char>& ign = frame_ignored_[f];
    for (std::int64_t d : order) {
      const Det& det = dets_[std::size_t(d)];
      // Pairs are sorted by IoU: the first unmatched counted one is the best not-yet-matched
      // instance; failing that, an ignored instance reaching t makes the detection ignored.
      bool found = false;
      for (std::int64_t k = det.first_pair; k < det.first_pair + det.num_pairs; ++k) {
        const Pair& p = pairs_[std::size_t(k)];
        if (ign[std::size_t(p.truth)] || matched[std::size_t(p.truth)]) continue;
        if (p.iou >= t) {
          matched[std::size_t(p.truth)] = 1;
          correct[std::size_t(d)] = 1;
          found = true;
        }
        break;
      }
      if (found) continue;
      for (std::int64_t k = det.first_pair; k < det.first_pair + det.num_pairs; ++k) {
        const Pair& p = pairs_[std::size_t(k)];
        if (ign[std::size_t(p.truth)] && p.iou >= t) {
          correct[std::size_t(d)] = 2;
          break;
        }
      }
    }
  }
  return correct;
}

double DetectionApAccumulator::ap(double iou_threshold) const {
  const std::vector<char> correct = correct_at(iou_threshold);
  std::vector<RankedHit> ranked;
  ranked.reserve(dets_.size());
  for (std::size_t i = 0; i < dets_.size(); ++i)
    if (correct[i] != 2) ranked.push_back({dets_[i].score, correct[i] == 1});
  return average_precision(std::move(ranked), num_truth_);
}

double DetectionApAccumulator::map50_95() const {
  double s = 0.0;
  // (50 + 5i) / 100 is the correctly rounded threshold (0.5 + 0.05·i accumulates error at 0.8).
  for (int i = 0; i < 10; ++i) s += ap(double(50 + 5 * i) / 100.0);
  return s / 10.0;
}

std::int64_t DetectionApAccumulator::true_positives(double iou_threshold, float min_score) const {
  const std::vector<char> correct = correct_at(iou_threshold);
  std::int64_t n = 0;
  for (std::size_t i = 0; i < dets_.size(); ++i) n += correct[i] == 1 && dets_[i].score > min_score;
  return n;
}

}  // namespace cropsight::eval
