// The paper's seven detectors on the 11 shared images, scored by the library's metric and by an
// independent reference written here from the definition (a different algorithm: for each
// detection, recall and precision by counting; AP as the sum over distinct recall levels of the
// best precision reached at that recall or beyond).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "cropsight/pipeline/potato/detection_eval.hpp"
#include "testing/testing.hpp"

namespace {
namespace fs = std::filesystem;
using namespace cropsight;
using cropsight::pipeline::potato::AnnotatedImage;

fs::path detection_dir() { return cropsight::testing::shared_data_dir() / "potato" / "detection"; }

struct Ref {
  double x1, y1, x2, y2, score;
  int image;
};

double reference_ap(const std::vector<AnnotatedImage>& set, const fs::path& dets_dir, double t) {
  std::vector<Ref> truth, dets;
  for (int i = 0; i < int(set.size()); ++i) {
    for (const auto& o : set[std::size_t(i)].truth.objects) truth.push_back({o.xmin, o.ymin, o.xmax, o.ymax, 1, i});
    for (const auto& l : io::read_detection_text(dets_dir / (set[std::size_t(i)].stem + ".txt")))
      dets.push_back({l.x1, l.y1, l.x2, l.y2, l.score, i});
  }
  // Rank: score descending, then image, then file order (index).
  std::vector<int> order(dets.size());
  for (int k = 0; k < int(order.size()); ++k) order[std::size_t(k)] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    if (dets[std::size_t(a)].score != dets[std::size_t(b)].score)
      return dets[std::size_t(a)].score > dets[std::size_t(b)].score;
    return a < b;
  });
  auto pixels = [](const Ref& r) { return (r.x2 - r.x1 + 1) * (r.y2 - r.y1 + 1); };
  std::set<int> taken;
  std::vector<int> tp;
  for (int k : order) {
    const Ref& d = dets[std::size_t(k)];
    int best = -1;
    double best_iou = 0;
    for (int j = 0; j < int(truth.size()); ++j) {
      const Ref& g = truth[std::size_t(j)];
      if (g.image != d.image) continue;
      const double iw = std::min(d.x2, g.x2) - std::max(d.x1, g.x1) + 1,
                   ih = std::min(d.y2, g.y2) - std::max(d.y1, g.y1) + 1;
      if (iw <= 0 || ih <= 0) continue;
      const double iou = iw * ih / (pixels(d) + pixels(g) - iw * ih);
      if (iou > best_iou) best_iou = iou, best = j;
    }
    const bool hit = best >= 0 && best_iou >= t && !taken.count(best);
    if (hit) taken.insert(best);
    tp.push_back(hit);
  }
  std::map<double, double> best_precision_at_recall;  // recall -> best precision at that rank
  int cum = 0;
  for (std::size_t k = 0; k < tp.size(); ++k) {
    cum += tp[k];
    const double r = double(cum) / double(truth.size()), p = double(cum) / double(k + 1);
    best_precision_at_recall[r] = std::max(best_precision_at_recall[r], p);
  }
  double ap = 0, prev = 0;
  for (auto it = best_precision_at_recall.begin(); it != best_precision_at_recall.end(); ++it) {
    double pmax = 0;
    for (auto jt = it; jt != best_precision_at_recall.end(); ++jt) pmax = std::max(pmax, jt->second);
    ap += (it->first - prev) * pmax;
    prev = it->first;
  }
  return ap;
}

TEST(PotatoPaperAp, SevenDetectorsMatchTheReference) {
  CROPSIGHT_REQUIRE_DATA(detection_dir());
  const auto set =
      pipeline::potato::load_annotated_images(detection_dir() / "images", detection_dir() / "annotations_voc");
  ASSERT_EQ(set.size(), 11u);
  int boxes = 0;
  for (const auto& a : set) boxes += int(a.truth.objects.size());
  EXPECT_EQ(boxes, 32);
  for (const char* model : {"f_rcn", "f_rcnn_inception", "f_rcnn_resnet", "ssd300_inception", "ssd300_mobilenet",
                            "ssd512_inception", "ssd512_mobilenet"}) {
    const fs::path dir = detection_dir() / "paper_detections" / model;
    const auto r = pipeline::potato::evaluate_saved_detections(set, dir);
    std::printf("[ paper ] %-18s 11 images: AP50 %.4f  AP75 %.4f  mAP50:95 %.4f  (%lld detections)\n", model, r.ap.ap50,
                r.ap.ap75, r.ap.map50_95, (long long)r.ap.detections);
    EXPECT_NEAR(r.ap.ap50, reference_ap(set, dir, 0.5), 1e-12) << model;
    EXPECT_NEAR(r.ap.ap75, reference_ap(set, dir, 0.75), 1e-12) << model;
    EXPECT_GT(r.ap.ap50, 0.8) << model;  // the paper's detectors all find most potatoes
  }
}

}  // namespace
