// The evaluation protocols of grape/eval.hpp on confusion matrices computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/grape/eval.hpp"

namespace {
using namespace cropsight;
using namespace cropsight::pipeline;
using namespace cropsight::pipeline::grape;

// Cloud A: (truth, pred) = (0,0) x4, (1,1) x3, (1,2) x1, (2,2) x2.
//   IoU 0 = 4/4 = 1, IoU 1 = 3/(4+3-3) = 0.75, IoU 2 = 2/(2+3-2) = 2/3.
// Cloud B: (0,0) x2, (0,1) x2, (1,1) x2; class 2 in neither truth nor prediction.
//   IoU 0 = 2/(4+2-2) = 0.5, IoU 1 = 2/(2+4-2) = 0.5, IoU 2 undefined.
eval::ConfusionMatrix cloud_a() {
  eval::ConfusionMatrix m(3);
  m.add(0, 0, 4), m.add(1, 1, 3), m.add(1, 2, 1), m.add(2, 2, 2);
  return m;
}
eval::ConfusionMatrix cloud_b() {
  eval::ConfusionMatrix m(3);
  m.add(0, 0, 2), m.add(0, 1, 2), m.add(1, 1, 2);
  return m;
}

TEST(GrapeEvalProtocols, PooledOverChosenClasses) {
  eval::ConfusionMatrix pooled = cloud_a();
  pooled.merge(cloud_b());
  // Pooled: (0,0) 6, (0,1) 2, (1,1) 5, (1,2) 1, (2,2) 2.
  //   IoU 0 = 6/(8+6-6) = 0.75, IoU 1 = 5/(6+7-5) = 0.625, IoU 2 = 2/(2+3-2) = 2/3.
  EXPECT_NEAR(pooled_miou(pooled, {1, 2}), (0.625 + 2.0 / 3) / 2, 1e-12);
  EXPECT_NEAR(pooled_miou(pooled, {0, 1, 2}), (0.75 + 0.625 + 2.0 / 3) / 3, 1e-12);
  EXPECT_NEAR(pooled_miou(pooled, {0, 1, 2}), pooled.mean_iou(), 1e-12);
  // An undefined class is skipped in the pooled mean (as mean_iou()), not counted as 1.
  EXPECT_NEAR(pooled_miou(cloud_b(), {1, 2}), 0.5, 1e-12);
  EXPECT_TRUE(std::isnan(pooled_miou(cloud_b(), {2})));
  EXPECT_THROW(pooled_miou(pooled, {3}), Error);
}

TEST(GrapeEvalProtocols, PerCloudCountsAnAbsentClassAsOne) {
  // {1, 2}: A (0.75 + 2/3) / 2, B (0.5 + 1) / 2 (class 2 absent from both: 1).
  const double a = (0.75 + 2.0 / 3) / 2, b = (0.5 + 1.0) / 2;
  EXPECT_NEAR(per_cloud_miou({cloud_a(), cloud_b()}, {1, 2}), (a + b) / 2, 1e-12);
  // All labels: A (1 + 0.75 + 2/3) / 3, B (0.5 + 0.5 + 1) / 3.
  EXPECT_NEAR(per_cloud_miou({cloud_a(), cloud_b()}, {0, 1, 2}), ((1 + 0.75 + 2.0 / 3) / 3 + (0.5 + 0.5 + 1.0) / 3) / 2,
              1e-12);
  // Not the pooled figure: per cloud weighs clouds equally, pooling weighs points.
  eval::ConfusionMatrix pooled = cloud_a();
  pooled.merge(cloud_b());
  EXPECT_GT(std::abs(per_cloud_miou({cloud_a(), cloud_b()}, {1, 2}) - pooled_miou(pooled, {1, 2})), 0.05);
  EXPECT_TRUE(std::isnan(per_cloud_miou({}, {1, 2})));
  EXPECT_THROW(per_cloud_miou({cloud_a()}, {-1}), Error);
}

TEST(GrapeEvalProtocols, MergedEvaluationsGiveEveryProtocol) {
  pipeline::grape::Figures a, b;
  a.confusion = cloud_a(), a.per_cloud = {cloud_a()}, a.clouds = 1, a.points = 10;
  b.confusion = cloud_b(), b.per_cloud = {cloud_b()}, b.clouds = 1, b.points = 6;
  a.merge(b);
  ASSERT_EQ(a.per_cloud.size(), 2u);
  EXPECT_EQ(a.named_classes(), (std::vector<int>{1, 2}));  // the named classes below 3 labels
  EXPECT_NEAR(a.confusion.mean_iou(), (0.75 + 0.625 + 2.0 / 3) / 3, 1e-12);
  const auto p = pipeline::grape::grape_protocols(a);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[0].name, "pooled_all_labels");
  EXPECT_NEAR(p[0].miou, a.confusion.mean_iou(), 1e-12);
  EXPECT_EQ(p[1].name, "pooled_named_classes");
  EXPECT_EQ(p[1].classes, (std::vector<int>{1, 2}));
  EXPECT_NEAR(p[1].miou, (0.625 + 2.0 / 3) / 2, 1e-12);
  EXPECT_EQ(p[2].name, "per_cloud_named_classes");
  EXPECT_NEAR(p[2].miou, ((0.75 + 2.0 / 3) / 2 + 0.75) / 2, 1e-12);
  EXPECT_EQ(p[3].name, "per_cloud_all_labels");
  EXPECT_NEAR(p[3].miou, ((1 + 0.75 + 2.0 / 3) / 3 + 2.0 / 3) / 2, 1e-12);
  EXPECT_NE(a.text().find("per cloud, named classes (1 2): "), std::string::npos) << a.text();
}

TEST(GrapeEvalProtocols, SixLabelsNameTheFiveClassesOfThePaper) {
  pipeline::grape::Figures e;  // the default: the dataset's six labels
  EXPECT_EQ(e.named_classes(), (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(e.all_labels(), (std::vector<int>{0, 1, 2, 3, 4, 5}));
}
}  // namespace

namespace {
// Cloud A as points: the labels of its (truth, pred) pairs, in that order.
std::pair<cropsight::Cloud, std::vector<int>> points_of_cloud_a() {
  const std::vector<std::pair<int, int>> pairs = {{0, 0}, {0, 0}, {0, 0}, {0, 0}, {1, 1},
                                                  {1, 1}, {1, 1}, {1, 2}, {2, 2}, {2, 2}};
  cropsight::Cloud c;
  std::vector<int> pred;
  for (const auto& [t, p] : pairs) {
    c.points.emplace_back(0.f, 0.f, 0.f);
    c.labels.push_back(t);
    pred.push_back(p);
  }
  return {c, pred};
}
}  // namespace

TEST(GrapeEvaluator, AddingACloudGivesItsConfusionPooledAndPerCloud) {
  const auto [cloud, pred] = points_of_cloud_a();
  cropsight::pipeline::grape::Evaluator ev(3);
  ev.add(pred, cloud, 0.25);
  ev.add(pred, cloud, 0.25);
  const cropsight::pipeline::grape::Figures& f = ev.figures();
  EXPECT_EQ(f.clouds, 2u);
  EXPECT_EQ(f.points, 20u);
  EXPECT_DOUBLE_EQ(f.ms_per_cloud(), 250.0);
  ASSERT_EQ(f.per_cloud.size(), 2u);
  for (int t = 0; t < 3; ++t)
    for (int p = 0; p < 3; ++p) {
      EXPECT_EQ(f.per_cloud[0].at(t, p), cloud_a().at(t, p));
      EXPECT_EQ(f.confusion.at(t, p), 2 * cloud_a().at(t, p));
    }
  cropsight::Cloud unlabelled = cloud;
  unlabelled.labels.clear();
  EXPECT_THROW(ev.add(pred, unlabelled), cropsight::Error);
  EXPECT_THROW(ev.add({0}, cloud), cropsight::Error);
}
