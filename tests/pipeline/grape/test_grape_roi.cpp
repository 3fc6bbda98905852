#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "cropsight/core/error.hpp"
#include "cropsight/pipeline/grape/roi.hpp"
#include "testing/testing.hpp"

namespace {
using namespace cropsight;
using namespace cropsight::pipeline;
using namespace cropsight::pipeline::grape;

TEST(GrapeRoi, Equation1) {
  // bunch g = (X 100, Y 200, W 80, H 120); peduncle p = (X 130, Y 150, W 10, H 40)
  const Box2D r = roi_from_boxes({100, 200, 80, 120}, {130, 150, 10, 40});
  EXPECT_EQ(r.x, 100);                   // X = X_g
  EXPECT_EQ(r.y, 150);                   // Y = Y_p
  EXPECT_EQ(r.width, 80);                // W = W_g
  EXPECT_EQ(r.height, 200 + 120 - 150);  // H = Y_g + H_g - Y_p
}

TEST(GrapeRoi, PairsPedunclesAndMergesOverlaps) {
  std::vector<pipeline::grape::Detection> d = {
      {{100, 200, 80, 120}, 1, 0.9f},  // bunch A
      {{130, 150, 10, 40}, 2, 0.9f},   // its peduncle (centre x 135 inside A, above it)
      {{400, 100, 50, 60}, 1, 0.9f},   // bunch B, no peduncle
      {{170, 250, 50, 50}, 1, 0.9f},   // bunch C overlapping A -> merged with A's ROI
      {{600, 50, 10, 10}, 2, 0.9f},    // stray peduncle
      {{700, 300, 20, 20}, 1, 0.1f},   // low score: ignored
  };
  auto rois = pipeline::grape::grape_rois(d, 640, 480);
  ASSERT_EQ(rois.size(), 2u);
  EXPECT_EQ(rois[0], (Box2D{100, 150, 120, 170}));  // union of A's Eq.1 ROI and C
  EXPECT_EQ(rois[1], (Box2D{400, 100, 50, 60}));
  // Clipping to the image.
  rois = pipeline::grape::grape_rois({{{600, 400, 100, 100}, 1, 1.f}}, 640, 480);
  ASSERT_EQ(rois.size(), 1u);
  EXPECT_EQ(rois[0], (Box2D{600, 400, 40, 80}));
}

TEST(GrapeRoi, DeprojectionHandComputed) {
  CameraIntrinsics cam;
  cam.width = 4, cam.height = 3;
  cam.fx = 100, cam.fy = 200, cam.cx = 1.5, cam.cy = 1.0;
  cam.depth_scale = 0.001;
  DepthImage depth(4, 3, 0);
  ColorImage color(4, 3, Rgb8{0, 0, 0});
  depth.at(3, 2) = 2000;  // 2 m at u=3, v=2 -> x = (3-1.5)/100*2 = 0.03, y = (2-1)/200*2 = 0.01
  color.at(3, 2) = {255, 51, 0};
  depth.at(0, 0) = 3000;  // 3.0 m: not kept (z < 3.0 strictly)
  depth.at(1, 0) = 1;     // 0.001 m: not kept (z > 0.001 strictly)
  depth.at(2, 0) = 2;     // 0.002 m: kept
  depth.at(0, 2) = 500;   // outside the ROI below
  const Cloud c = roi_cloud(depth, color, cam, {1, 0, 3, 3});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c.points[0].z(), 0.002f, 1e-7f);
  EXPECT_NEAR(c.points[0].x(), (2 - 1.5f) / 100 * 0.002f, 1e-9f);
  EXPECT_NEAR(c.points[1].x(), 0.03f, 1e-6f);
  EXPECT_NEAR(c.points[1].y(), 0.01f, 1e-6f);
  EXPECT_NEAR(c.points[1].z(), 2.0f, 1e-6f);
  EXPECT_FLOAT_EQ(c.colors[1].x(), 1.f);
  EXPECT_FLOAT_EQ(c.colors[1].y(), 0.2f);
  EXPECT_FLOAT_EQ(c.colors[1].z(), 0.f);
  cam.width = 5;
  EXPECT_THROW(roi_cloud(depth, color, cam, {0, 0, 1, 1}), Error);
}

TEST(GrapeRoi, FrameStagesGiveNormalisedCloudsWithNormals) {
  // A 40x30 frame: a tilted plane (depth rising to the right) under one bunch box with its
  // peduncle above it, one box wholly outside the image and one of another category.
  CameraIntrinsics cam;
  cam.width = 40, cam.height = 30;
  cam.fx = cam.fy = 50, cam.cx = 20, cam.cy = 15;
  DepthImage depth(40, 30, 0);
  ColorImage color(40, 30, Rgb8{20, 200, 40});
  for (int v = 0; v < 30; ++v)
    for (int u = 0; u < 40; ++u) depth.at(u, v) = std::uint16_t(1000 + 10 * u);
  const std::vector<pipeline::grape::Detection> dets = {{{10, 10, 10, 10}, 1, 0.9f, 0},
                                                        {{14, 5, 2, 5}, 2, 0.9f, 1},
                                                        {{100, 100, 5, 5}, 1, 0.9f, 2},
                                                        {{0, 0, 5, 5}, 7, 0.9f, 3}};
  const pipeline::grape::RoiFrame f = pipeline::grape::grape_roi_clouds(depth, color, cam, dets);
  ASSERT_EQ(f.rois.size(), 1u);
  ASSERT_EQ(f.outside.size(), 1u);
  EXPECT_EQ(f.outside[0].annotation, 2);
  const pipeline::grape::RoiCloud& r = f.rois[0];
  EXPECT_EQ(r.box, (Box2D{10, 5, 10, 15}));  // Eq. 1
  ASSERT_EQ(r.cloud.size(), 150u);           // every pixel of the ROI has a kept depth
  ASSERT_EQ(r.cloud.normals.size(), r.cloud.size());
  ASSERT_EQ(r.cloud.labels, std::vector<int>(r.cloud.size(), 0));
  float radius = 0;
  for (std::size_t i = 0; i < r.cloud.size(); ++i) {
    radius = std::max(radius, r.cloud.points[i].norm());
    EXPECT_NEAR(r.cloud.normals[i].norm(), 1.f, 1e-4f);
    // Towards the camera: the camera sits at -centroid/scale in the normalised frame.
    const Eigen::Vector3f to_camera = -r.centroid / r.scale - r.cloud.points[i];
    EXPECT_GT(r.cloud.normals[i].dot(to_camera), 0.f) << i;
  }
  EXPECT_NEAR(radius, 1.f, 1e-5f);
  // Mapping back: p * scale + centroid is the deprojected pixel (u = 10, v = 5 is the first).
  const Eigen::Vector3f first = r.cloud.points[0] * r.scale + r.centroid;
  EXPECT_NEAR((first - cam.deproject(10, 5, 1.1f)).norm(), 0.f, 1e-5f);
  cam.width = 41;
  EXPECT_THROW(pipeline::grape::grape_roi_clouds(depth, color, cam, dets), Error);
}

TEST(GrapeRoi, ReadsCocoDetections) {
  cropsight::testing::TempDir t;
  std::ofstream(t / "det.json") << R"({"images": [], "annotations": [
      {"image_id": 1, "bbox": [10.5, 20, 30, 40], "category_id": 1},
      {"image_id": 2, "bbox": [1, 2, 3, 4], "category_id": 2, "score": 0.7}]})";
  auto d = read_coco_detections(t / "det.json");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].box, (Box2D{10, 20, 30, 40}));
  EXPECT_FLOAT_EQ(d[1].score, 0.7f);
  EXPECT_EQ(read_coco_detections(t / "det.json", 2).size(), 1u);
  std::ofstream(t / "bad.json") << R"([{"bbox": [1, 2, 3], "category_id": 1}])";
  try {
    read_coco_detections(t / "bad.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json: annotation 0"), std::string::npos) << e.what();
  }
}

TEST(GrapeRoi, SharedCocoAnnotationsGiveRois) {
  const auto ann = cropsight::testing::shared_data_dir() / "grape" / "coco_train" / "annotations.json";
  CROPSIGHT_REQUIRE_DATA(ann);
  const auto all = read_coco_detections(ann, 1);  // one image's annotations
  ASSERT_FALSE(all.empty());
  std::vector<pipeline::grape::Detection> one = all;
  const auto rois = pipeline::grape::grape_rois(one, 1280, 720);
  EXPECT_FALSE(rois.empty());
  for (const auto& r : rois) {
    EXPECT_GE(r.x, 0);
    EXPECT_LE(r.x + r.width, 1280);
    EXPECT_LE(r.y + r.height, 720);
  }
}
TEST(GrapeRoi, ConfigValidated) {
  auto named = [](void (*set)(pipeline::grape::RoiConfig&), const std::string& key) {
    pipeline::grape::RoiConfig c;
    set(c);
    try {
      c.validate("cfg");
      ADD_FAILURE() << key << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.problem().rfind("'" + key + "'", 0), 0u) << e.what();
    }
    EXPECT_THROW(pipeline::grape::grape_rois({}, 10, 10, c), Error) << key;
  };
  named([](pipeline::grape::RoiConfig& c) { c.normal_k = 100000000; }, "normal_k");
  named([](pipeline::grape::RoiConfig& c) { c.z_min = 5, c.z_max = 1; }, "z_max");
  named([](pipeline::grape::RoiConfig& c) { c.bunch_category = -1; }, "bunch_category");
  named([](pipeline::grape::RoiConfig& c) { c.min_score = 5; }, "min_score");
  EXPECT_NO_THROW(pipeline::grape::RoiConfig{}.validate("cfg"));
}
}  // namespace
