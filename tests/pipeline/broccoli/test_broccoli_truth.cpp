#include <gtest/gtest.h>

#include <cmath>

#include "cropsight/pipeline/broccoli/truth.hpp"

using namespace cropsight;
using namespace cropsight::pipeline;
using namespace cropsight::pipeline::broccoli;

TEST(BroccoliTruth, MajorityOfOneHeadMakesAHeadCluster) {
  // 10 pixels: labels 0 0 3 3 3 3 3 5 5 0
  const std::vector<std::uint16_t> labels{0, 0, 3, 3, 3, 3, 3, 5, 5, 0};
  const std::vector<int> all{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  ClusterTruth t = cluster_truth(all, labels);
  EXPECT_EQ(t.head_id, 3);  // exactly half (5 of 10) on head 3 counts
  EXPECT_FLOAT_EQ(t.fraction, 0.5f);
  const std::vector<int> leafy{0, 1, 2, 3, 7, 8, 9};  // 2 on head 3, 2 on head 5, 3 on nothing
  t = cluster_truth(leafy, labels);
  EXPECT_EQ(t.head_id, 0);  // 2/7 < 0.5 on any one head
  EXPECT_NEAR(t.fraction, 2.0 / 7.0, 1e-6);
  // Two heads 40 % each: not a head (the rule asks for one head).
  const std::vector<std::uint16_t> two{1, 1, 2, 2, 0};
  EXPECT_EQ(cluster_truth(std::vector<int>{0, 1, 2, 3, 4}, two).head_id, 0);
  EXPECT_EQ(cluster_truth(std::vector<int>{0, 1, 2, 3, 4}, two, 0.4f).head_id, 1);
  EXPECT_EQ(cluster_truth(all, {}).head_id, 0);  // no labels: not a head
}

TEST(BroccoliTruth, InstancesAreTheVisiblePointsOfEachHead) {
  OrganizedCloud c(4, 2);
  c.labels = {7, 7, 0, 2, 7, 2, 2, 0};
  for (int i = 0; i < 8; ++i) c.x[i] = c.y[i] = 0.0f, c.z[i] = 1.0f;
  c.z[1] = NAN;  // a labelled pixel without a return is not part of the visible head
  std::vector<TruthInstance> inst;
  truth_instances(c, 0, inst);
  ASSERT_EQ(inst.size(), 2u);
  EXPECT_EQ(inst[0].id, 2);
  EXPECT_EQ(inst[0].indices, (std::vector<int>{3, 5, 6}));
  EXPECT_EQ(inst[1].id, 7);
  EXPECT_EQ(inst[1].indices, (std::vector<int>{0, 4}));
  EXPECT_TRUE(inst[1].cut_by_border);  // a 4x2 image: every pixel is on the border
  truth_instances(c, 3, inst);         // heads with fewer than 3 visible points are left out
  ASSERT_EQ(inst.size(), 1u);
  EXPECT_EQ(inst[0].id, 2);
}

TEST(BroccoliTruth, HeadsTouchingTheImageBorderAreMarked) {
  OrganizedCloud c(5, 5);
  c.labels.assign(25, 0);
  for (int i = 0; i < 25; ++i) c.x[i] = c.y[i] = 0.0f, c.z[i] = 1.0f;
  c.labels[12] = 4;               // centre pixel: inside the view
  c.labels[5] = c.labels[6] = 9;  // (0,1) is on the left border
  c.z[5] = NAN;                   // even when the border pixel has no return
  std::vector<TruthInstance> inst;
  truth_instances(c, 0, inst);
  ASSERT_EQ(inst.size(), 2u);
  EXPECT_EQ(inst[0].id, 4);
  EXPECT_FALSE(inst[0].cut_by_border);
  EXPECT_EQ(inst[1].id, 9);
  EXPECT_TRUE(inst[1].cut_by_border);
  EXPECT_EQ(inst[1].indices, std::vector<int>{6});
}

// The any-depth truth keeps every labelled pixel with a sensor return, also those the depth
// window dropped (NaN in the cloud): the same sets as truth_instances when nothing was dropped.
TEST(BroccoliTruth, AnyDepthInstancesKeepHeadsTheWindowDropped) {
  OrganizedCloud c(4, 2);
  c.labels = {7, 7, 0, 2, 7, 2, 2, 0};
  const std::vector<std::uint16_t> depth{1200, 0, 900, 1100, 1200, 1100, 1100, 900};  // mm; pixel 1: no return
  for (int i = 0; i < 8; ++i)
    c.x[i] = c.y[i] = 0.0f, c.z[i] = depth[std::size_t(i)] ? 0.001f * depth[std::size_t(i)] : NAN;
  std::vector<TruthInstance> window, any;
  truth_instances(c, 0, window);
  truth_instances_any_depth(c.labels, depth, 4, 2, 0, any);
  ASSERT_EQ(any.size(), window.size());
  for (std::size_t k = 0; k < any.size(); ++k) EXPECT_EQ(any[k].indices, window[k].indices);
  for (int i = 0; i < 8; ++i)
    if (c.z[std::size_t(i)] > 1.0f) c.z[std::size_t(i)] = NAN;  // a 1.0 m window drops head 7 and head 2
  truth_instances(c, 0, window);
  EXPECT_TRUE(window.empty());
  truth_instances_any_depth(c.labels, depth, 4, 2, 0, any);
  ASSERT_EQ(any.size(), 2u);
  EXPECT_EQ(any[0].indices, (std::vector<int>{3, 5, 6}));
  EXPECT_EQ(any[1].indices, (std::vector<int>{0, 4}));
  EXPECT_THROW(truth_instances_any_depth(c.labels, std::vector<std::uint16_t>(7, 1000), 4, 2, 0, any),
               std::invalid_argument);
  truth_instances_any_depth({}, depth, 4, 2, 0, any);  // no label image: no truth
  EXPECT_TRUE(any.empty());
}
