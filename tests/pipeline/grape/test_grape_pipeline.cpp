#include "cropsight/pipeline/grape/pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/io/config_yaml.hpp"
#include "pipeline/grape/grape_test_frame.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;
// Declarations, not `using namespace cropsight::pipeline` (unity batches: see
// test_grape_segmenter.cpp).
using pipeline::grape::Config;
using pipeline::grape::CutPointConfig;
using pipeline::grape::FrameResult;
using pipeline::grape::grape_cut_point;
using pipeline::grape::grape_detections;
using pipeline::grape::Pipeline;
using pipeline::grape::Segmenter;
using pipeline::grape::SegmenterConfig;

// A labelled bunch cloud (m): berries (label 1) in a 4 cm cube, and a peduncle (label 2) of `n` points
// along `axis` around `centre`, with a few millimetres of jitter; plus, when `stray`, five
// peduncle-labelled points 10 cm away that the cut point must ignore.
Cloud peduncle_cloud(const Eigen::Vector3f& centre, const Eigen::Vector3f& axis, int n, bool stray) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  Cloud c;
  for (int i = 0; i < 300; ++i) {
    c.points.push_back(centre + Eigen::Vector3f(0, 0.06f, 0) + 0.02f * Eigen::Vector3f(u(rng), u(rng), u(rng)));
    c.labels.push_back(1);
  }
  for (int i = 0; i < n; ++i) {
    // Evenly spaced along a 4 cm rod, so that the centroid is `centre` up to the jitter.
    const float t = 0.04f * (float(i) / float(n - 1) - 0.5f);
    c.points.push_back(centre + t * axis + 0.001f * Eigen::Vector3f(u(rng), u(rng), u(rng)));
    c.labels.push_back(2);
  }
  if (stray)
    for (int i = 0; i < 5; ++i) {
      c.points.push_back(centre + Eigen::Vector3f(0.1f, 0, 0) + 0.002f * Eigen::Vector3f(u(rng), u(rng), u(rng)));
      c.labels.push_back(2);
    }
  return c;
}

TEST(GrapeCutPoint, CentroidAndUpwardDirectionOfTheLargestPeduncleCluster) {
  const Eigen::Vector3f centre(0.05f, -0.1f, 0.8f);
  // Given pointing down-left in the image (+y): the result must point up (-y), the same line.
  const Eigen::Vector3f down = Eigen::Vector3f(-0.3f, 1.f, 0.2f).normalized();
  const Cloud c = peduncle_cloud(centre, down, 80, true);
  const auto cut = pipeline::grape::grape_cut_point(c);
  ASSERT_TRUE(cut.has_value());
  EXPECT_EQ(cut->confidence, 80);  // the stray five are another cluster
  EXPECT_LT((cut->position - centre).norm(), 0.001f) << cut->position.transpose();
  EXPECT_NEAR(cut->direction.norm(), 1.f, 1e-5f);
  EXPECT_LT(cut->direction.y(), 0.f);
  EXPECT_GT(cut->direction.dot(-down), 0.999f) << cut->direction.transpose();
  // The same rod given pointing up gives the same answer.
  const auto up = pipeline::grape::grape_cut_point(peduncle_cloud(centre, -down, 80, true));
  ASSERT_TRUE(up.has_value());
  EXPECT_GT(up->direction.dot(cut->direction), 0.999f);
  // Another label id: the berries' ball is then "the peduncle".
  pipeline::grape::CutPointConfig cfg;
  cfg.peduncle_label = 1;
  const auto berries = pipeline::grape::grape_cut_point(c, cfg);
  ASSERT_TRUE(berries.has_value());
  EXPECT_EQ(berries->confidence, 300);
}

TEST(GrapeCutPoint, NoneWithoutEnoughPedunclePoints) {
  const Eigen::Vector3f centre(0, 0, 1), axis(0, 1, 0);
  Cloud c = peduncle_cloud(centre, axis, 20, false);
  for (auto& l : c.labels)
    if (l == 2) l = 3;  // no peduncle point at all
  EXPECT_FALSE(pipeline::grape::grape_cut_point(c).has_value());
  // Nine peduncle points (min_points 10) in one cluster, plus the five strays: none.
  EXPECT_FALSE(pipeline::grape::grape_cut_point(peduncle_cloud(centre, axis, 9, true)).has_value());
  pipeline::grape::CutPointConfig cfg;
  cfg.min_points = 9;
  EXPECT_TRUE(pipeline::grape::grape_cut_point(peduncle_cloud(centre, axis, 9, true), cfg).has_value());
  // A tolerance below the rod's spacing (4 cm / 8 steps = 5 mm) splits it: no cluster of 9.
  cfg.cluster_tolerance = 0.002;
  EXPECT_FALSE(pipeline::grape::grape_cut_point(peduncle_cloud(centre, axis, 9, true), cfg).has_value());
  c.labels.clear();
  EXPECT_THROW(pipeline::grape::grape_cut_point(c), Error);
}

TEST(GrapeDetections, DetectorClassesBecomeCocoCategories) {
  Detection2D grape{10.5f, 20.2f, 30.1f, 40.9f, 0, 0.8f}, peduncle{1, 2, 3, 4, 1, 0.6f};
  const auto d = pipeline::grape::grape_detections({grape, peduncle});
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].box, (Box2D{10, 20, 21, 21}));  // covers [10.5, 30.1) x [20.2, 40.9)
  EXPECT_EQ(d[0].category, 1);
  EXPECT_FLOAT_EQ(d[0].score, 0.8f);
  EXPECT_EQ(d[1].category, 2);
  EXPECT_EQ(d[1].annotation, 1);
}

TEST(GrapePipelineConfig, PresetHoldsTheDefaultsAndRangesNameTheirSection) {
  pipeline::grape::Config preset;
  const auto path = cropsight::testing::source_dir() / "configs" / "grape-camera.yaml";
  apply_config(preset, io::load_config_map(path), path.string());
  EXPECT_EQ(dump_config(preset), dump_config(pipeline::grape::Config{}));
  pipeline::grape::Config c;
  c.cut_point.min_points = 2;
  try {
    c.validate("cfg");
    ADD_FAILURE() << "min_points 2 accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.problem().rfind("'cut_point.min_points'", 0), 0u) << e.what();
  }
  c = {};
  c.roi.z_min = 5;  // the rule between two roi fields
  EXPECT_THROW(c.validate("cfg"), Error);
}

pipeline::grape::Segmenter shipped_gbdt() {
  pipeline::grape::SegmenterConfig s;
  s.model = (cropsight::testing::source_dir() / "models" / "grape-gbdt-fast.json").string();
  s.threads = 1;
  return pipeline::grape::Segmenter(s, "test");
}

// The whole pipeline on the synthetic frame with the shipped fast GBDT segmenter.
TEST(GrapePipeline, SyntheticFrameEndToEnd) {
  const auto t = cropsight::testing::grape_test_frame();
  pipeline::grape::Pipeline pipe(pipeline::grape::Config{}, shipped_gbdt());
  const pipeline::grape::FrameResult r = pipe.process(t.frame, t.boxes);
  EXPECT_EQ(r.detections.size(), 4u);
  EXPECT_TRUE(r.outside.empty());
  ASSERT_EQ(r.bunches.size(), 2u);
  EXPECT_EQ(r.bunches[0].roi, (Box2D{60, 33, 41, 63}));   // A with its peduncle (Eq. 1)
  EXPECT_EQ(r.bunches[1].roi, (Box2D{120, 70, 34, 29}));  // B and C merged
  const CameraIntrinsics& cam = t.frame.camera;
  for (const auto& b : r.bunches) {
    const Cloud& c = b.cloud;
    EXPECT_EQ(c.size(), std::size_t(b.roi.area()));  // every pixel has a depth in (0.001, 3) m
    ASSERT_EQ(c.labels.size(), c.size());
    ASSERT_EQ(c.colors.size(), c.size());
    ASSERT_EQ(c.normals.size(), c.size());
    for (std::size_t i = 0; i < c.size(); ++i) {
      // Metres, camera frame: each point projects into its ROI at the depth of that pixel.
      const Eigen::Vector2f px = cam.project(c.points[i]);
      const int u = int(std::lround(px.x())), v = int(std::lround(px.y()));
      ASSERT_TRUE(u >= b.roi.x && u < b.roi.x + b.roi.width && v >= b.roi.y && v < b.roi.y + b.roi.height) << i;
      EXPECT_NEAR(c.points[i].z(), t.frame.depth.at(u, v) * 0.001f, 2e-5f) << i;
      EXPECT_GE(c.labels[i], 0);
      EXPECT_LT(c.labels[i], 6);
    }
    // Whatever the model labels peduncle, the cut point is that of the labelled cloud.
    const auto again = pipeline::grape::grape_cut_point(c);
    ASSERT_EQ(b.cut_point.has_value(), again.has_value());
    if (again) {
      EXPECT_EQ(b.cut_point->confidence, again->confidence);
      EXPECT_EQ(b.cut_point->position, again->position);
      EXPECT_LE(b.cut_point->direction.y(), 0.f);
    }
  }
  // Without a detector, only the boxes' overload runs.
  EXPECT_THROW(pipe.process(t.frame), Error);
  RgbdFrame grey = t.frame;
  grey.color = {};
  EXPECT_THROW(pipe.process(grey, t.boxes), Error);  // the segmenter needs colour
}

// The segmenter's peduncle labels replaced by the truth (the rod's pixels): the cut point is then
// exact on the real frame's geometry, from the cloud the pipeline produced.
TEST(GrapePipeline, CutPointOnTheFramesPeduncle) {
  const auto t = cropsight::testing::grape_test_frame();
  const pipeline::grape::Pipeline pipe(pipeline::grape::Config{}, shipped_gbdt());
  pipeline::grape::FrameResult r = pipe.process(t.frame, t.boxes);
  ASSERT_FALSE(r.bunches.empty());
  Cloud c = r.bunches[0].cloud;
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  int n = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const bool rod = std::abs(c.points[i].z() - 0.78f) < 1e-4f;  // only the rod is at 780 mm
    c.labels[i] = rod ? 2 : 1;
    if (rod) sum += c.points[i], ++n;
  }
  ASSERT_EQ(n, 4 * 20);
  const auto cut = pipeline::grape::grape_cut_point(c);
  ASSERT_TRUE(cut.has_value());
  EXPECT_EQ(cut->confidence, n);
  EXPECT_LT((cut->position - sum / float(n)).norm(), 1e-5f);
  EXPECT_GT(-cut->direction.y(), 0.99f);  // a vertical rod: straight up the image
  EXPECT_LT(cut->position.y(), 0.f);      // above the optical axis (rows 35-54 < cy = 60)
}

}  // namespace
