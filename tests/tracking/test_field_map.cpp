// Field-map CSV round trip, bad files, and the HeadMapper glue on an organised cloud.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "cropsight/core/camera.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/tracking/field_map_io.hpp"
#include "cropsight/tracking/head_mapper.hpp"
#include "testing/testing.hpp"

using namespace cropsight;
using namespace cropsight::tracking;

TEST(FieldMap, RoundTrip) {
  cropsight::testing::TempDir dir;
  TrackedHead a;
  a.id = 3;
  a.position = {1.25, -0.3, 0.52};
  a.diameter_mm = 131.2;
  a.bbox_mm = 128.0;
  a.hull_mm = 101.5;
  a.frames_seen = 9;
  a.first_frame = 4;
  a.last_frame = 12;
  a.score = 9;
  a.harvestable = true;
  TrackedHead b = a;
  b.id = 4;
  b.harvestable = false;
  write_field_map(dir / "m.csv", {a, b});
  const auto r = read_field_map(dir / "m.csv");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].id, 3);
  EXPECT_NEAR((r[0].position - a.position).norm(), 0, 1e-9);
  EXPECT_DOUBLE_EQ(r[0].diameter_mm, 131.2);
  EXPECT_DOUBLE_EQ(r[0].hull_mm, 101.5);
  EXPECT_EQ(r[0].frames_seen, 9);
  EXPECT_TRUE(r[0].harvestable);
  EXPECT_FALSE(r[1].harvestable);
}

TEST(FieldMap, BadFilesNameTheLine) {
  cropsight::testing::TempDir dir;
  const std::string header = field_map_csv({});
  {
    std::ofstream(dir / "a.csv") << "x,y\n1,2\n";
    EXPECT_THROW(read_field_map(dir / "a.csv"), Error);
  }
  std::ofstream(dir / "b.csv") << header << "1,0.1,0.2,0.3,100,100,80,3,0,2,3,1\n1,0.1,zz,0.3,100,100,80,3,0,2,3,1\n";
  try {
    read_field_map(dir / "b.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "c.csv") << header << "1,0.1,0.2\n";
  EXPECT_THROW(read_field_map(dir / "c.csv"), Error);
  std::ofstream(dir / "d.csv") << header << "1,0.1,0.2,0.3,100,100,80,3,0,2,3,7\n";
  EXPECT_THROW(read_field_map(dir / "d.csv"), Error);
  EXPECT_THROW(read_field_map(dir / "missing.csv"), Error);
}

TEST(HeadMapper, SizesTracksAndRescores) {
  // A 40×40 cloud with a flat 100 mm square patch of points 0.7 m below the camera, seen in 5
  // frames while the camera is still; plus a one-frame false detection.
  OrganizedCloud c(40, 40);
  std::vector<int> head, fp;
  for (int v = 0; v < 40; ++v)
    for (int u = 0; u < 40; ++u) {
      const int i = c.index(u, v);
      c.x[std::size_t(i)] = 0.005f * float(u - 20);
      c.y[std::size_t(i)] = 0.005f * float(v - 20);
      c.z[std::size_t(i)] = 0.7f;
      if (u >= 10 && u <= 30 && v >= 10 && v <= 30) head.push_back(i);
      if (u >= 32 && u < 38 && v >= 32 && v < 38) fp.push_back(i);
    }
  HeadMapperConfig cfg;
  ConfigMap m{{"sizing.estimator", "bbox"},
              {"sizing.compute_hull", "false"},
              {"tracking.min_track_score", "3"},
              {"detector.other", "1"}};
  cfg.apply(m, "test");
  EXPECT_FALSE(cfg.sizing.compute_hull);
  // Without recording (the ROS node's setting) the sizes, ids and map are the same and nothing
  // is kept per detection.
  HeadMapper quiet(cfg);
  quiet.set_record_detections(false);
  HeadMapper mapper(cfg);
  for (int f = 0; f < 5; ++f) {
    std::vector<Detection> d(1);
    d[0].indices = head;
    d[0].centroid = {0.0f, 0.0f, 0.7f};
    d[0].score = 0.5f;
    d[0].box = {10, 10, 21, 21};
    if (f == 2) {
      Detection x;
      x.indices = fp;
      x.centroid = {0.07f, 0.07f, 0.7f};
      x.score = 0.9f;
      x.box = {32, 32, 6, 6};
      d.push_back(x);
    }
    std::vector<Detection> q = d;
    mapper.add_frame(f, c, d, Eigen::Vector3d(0, 0, 0.8));
    quiet.add_frame(f, c, q, Eigen::Vector3d(0, 0, 0.8));
    EXPECT_NEAR(d[0].size_m, 0.100, 1e-5);
    EXPECT_EQ(d[0].track_id, 1);
    for (std::size_t k = 0; k < d.size(); ++k) {
      EXPECT_EQ(q[k].size_m, d[k].size_m);
      EXPECT_EQ(q[k].track_id, d[k].track_id);
    }
  }
  EXPECT_TRUE(quiet.detections().empty());
  ASSERT_EQ(quiet.finish().size(), 1u);
  const auto& map = mapper.finish();
  EXPECT_EQ(quiet.map()[0].position, map[0].position);
  EXPECT_EQ(quiet.map()[0].frames_seen, map[0].frames_seen);
  ASSERT_EQ(map.size(), 1u);
  EXPECT_EQ(map[0].frames_seen, 5);
  EXPECT_NEAR(map[0].position.z(), 0.1, 1e-6);
  ASSERT_EQ(mapper.detections().size(), 6u);
  float best_fp = 0, worst_tp = 1e9;
  for (const auto& d : mapper.detections())
    (d.track_id == 1 ? worst_tp : best_fp) =
        d.track_id == 1 ? std::min(worst_tp, mapper.filtered_score(d)) : std::max(best_fp, mapper.filtered_score(d));
  EXPECT_GT(worst_tp, best_fp);  // the confirmed head now outranks the brighter false detection
  EXPECT_THROW(mapper.finish(), Error);
}

TEST(HeadMapper, DetectionsAtTheBorderArePartial) {
  OrganizedCloud c(40, 40);
  std::vector<int> edge;
  for (int v = 0; v < 40; ++v)
    for (int u = 0; u < 40; ++u) {
      const int i = c.index(u, v);
      c.x[std::size_t(i)] = 0.005f * float(u - 20);
      c.y[std::size_t(i)] = 0.005f * float(v - 20);
      c.z[std::size_t(i)] = 0.7f;
      if (u < 8 && v >= 10 && v < 30) edge.push_back(i);
    }
  HeadMapper mapper;
  std::vector<Detection> d(1);
  d[0].indices = edge;
  d[0].centroid = {-0.08f, 0.0f, 0.7f};
  d[0].box = {0, 10, 8, 20};  // touches the left border
  d[0].score = 0.5f;          // below tracking.edge_single_detection_score (1.0)
  mapper.add_frame(0, c, d);
  EXPECT_EQ(d[0].size_m, 0.0f);  // not measured
  EXPECT_EQ(d[0].track_id, 1);   // it started a head (partial_tracks)...
  ASSERT_EQ(mapper.detections().size(), 1u);
  EXPECT_TRUE(mapper.detections()[0].partial);
  EXPECT_TRUE(mapper.finish().empty());  // ...seen once: below the map's score threshold
  ASSERT_EQ(mapper.filter().all_heads().size(), 1u);
  EXPECT_EQ(mapper.filter().all_heads()[0].partial_frames, 1);
  EXPECT_EQ(mapper.filter().all_heads()[0].size_samples, 0);
}

// tracking.position_cap_m: a head's position is the centroid of its top, not of everything
// visible. A dome seen off-axis shows more of one flank; the flank pulls the all-points centroid
// sideways but not the top's.
TEST(HeadMapper, PositionIsTheTopOfTheHead) {
  OrganizedCloud c(60, 60);
  std::vector<int> head;
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 60; ++u) {
      const int i = c.index(u, v);
      const float x = 0.003f * float(u - 30), y = 0.003f * float(v - 30);
      c.x[std::size_t(i)] = x;
      c.y[std::size_t(i)] = y;
      const float r2 = x * x + y * y;
      c.z[std::size_t(i)] = 0.7f + r2 / (2 * 0.08f);  // dome, apex at (0, 0), radius of curvature 8 cm
      // Visible: the top (r < 5 cm) and, on the +x side only, the flank down to r = 8 cm.
      if (r2 < 0.05f * 0.05f || (x > 0 && r2 < 0.08f * 0.08f)) head.push_back(i);
    }
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();  // what the detector reports as the centroid
  for (int i : head) mean += c.point(std::size_t(i));
  mean /= float(head.size());
  auto position = [&](const std::string& cap) {
    HeadMapperConfig cfg;
    cfg.apply({{"sizing.estimator", "bbox"}, {"sizing.compute_hull", "false"}, {"tracking.position_cap_m", cap}},
              "test");
    HeadMapper mapper(cfg);
    std::vector<Detection> d(1);
    d[0].indices = head;
    d[0].centroid = mean;
    d[0].score = 1.0f;
    d[0].box = {5, 5, 50, 50};
    mapper.add_frame(0, c, d, Eigen::Vector3d::Zero());
    return mapper.detections().at(0).centroid;
  };
  const Eigen::Vector3f all = position("0"), top = position("0.01");
  EXPECT_EQ(all, mean);  // 0: the detector's centroid, as in the paper
  EXPECT_GT(all.x(), 0.01f) << "the flank pulls the all-points centroid";
  EXPECT_NEAR(top.x(), 0.0f, 0.002f);
  EXPECT_NEAR(top.y(), 0.0f, 0.002f);
  EXPECT_LT(top.z(), 0.7f + 0.01f);
}

namespace {
// A 120×100 pinhole view from `camera` (field frame, poses) of a 6 cm sphere whose field centre is
// (0.02, 0, -0.76) (apex 0.70 m below the camera) over ground 0.85 m below; `head` gets the
// sphere's pixels.
OrganizedCloud render_head(const CameraIntrinsics& cam, const Eigen::Vector3d& camera, std::vector<int>& head) {
  const FieldTransform t = FieldTransform::parse("y,x,-z");
  const Eigen::Vector3d centre = t.to_camera(camera, Eigen::Vector3d(0.02, 0.0, -0.76));
  const double radius = 0.06;
  OrganizedCloud c(cam.width, cam.height);
  head.clear();
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const Eigen::Vector3d d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      const double b = d.dot(centre), disc = b * b - d.squaredNorm() * (centre.squaredNorm() - radius * radius);
      double s = 0.85;  // depth of the ground
      const bool on_head = disc >= 0.0;
      if (on_head) s = (b - std::sqrt(disc)) / d.squaredNorm();
      const Eigen::Vector3d p = s * d;
      const int i = c.index(u, v);
      c.x[std::size_t(i)] = float(p.x()), c.y[std::size_t(i)] = float(p.y()), c.z[std::size_t(i)] = float(p.z());
      if (on_head) head.push_back(i);
    }
  return c;
}
}  // namespace

// tracking.predict_missed: a tracked head that a frame does not detect gets the frame's points in
// a ball where the filter expects it — here all of the head and none of the ground.
TEST(HeadMapper, PredictsTheHeadsAFrameMissed) {
  const CameraIntrinsics cam = CameraIntrinsics::from_fov(120, 100, 70.0 * M_PI / 180, 60.0 * M_PI / 180);
  auto run = [&](const ConfigMap& keys, std::vector<PredictedHead>& missed, std::vector<int>& truth) {
    HeadMapperConfig cfg;
    cfg.apply(keys, "test");
    HeadMapper mapper(cfg);
    for (int f = 0; f < 5; ++f) {
      const Eigen::Vector3d camera(0.01 * f, 0.0, 0.0);  // 1 cm per frame along the row
      OrganizedCloud c = render_head(cam, camera, truth);
      std::vector<Detection> d;
      if (f < 4) {  // detected in frames 0-3, missed in frame 4
        Detection x;
        x.indices = truth;
        x.score = 1.0f;
        int u0 = 1000, v0 = 1000, u1 = -1, v1 = -1;
        for (int i : truth) {
          u0 = std::min(u0, i % c.width), u1 = std::max(u1, i % c.width);
          v0 = std::min(v0, i / c.width), v1 = std::max(v1, i / c.width);
          x.centroid += c.point(std::size_t(i)) / float(truth.size());
        }
        x.box = {u0, v0, u1 - u0 + 1, v1 - v0 + 1};
        d.push_back(x);
      }
      mapper.add_frame(f, c, d, camera);
      missed = mapper.predict_missed(c, cam);
      if (f < 4) {
        EXPECT_TRUE(missed.empty()) << "frame " << f << ": the head was detected";
      }
    }
    mapper.finish();
    if (!missed.empty()) {
      EXPECT_EQ(mapper.predicted_score(missed[0].track_id), HeadMapper::kConfirmedBonus - 1.0f);
    }
  };
  std::vector<PredictedHead> missed;
  std::vector<int> truth;
  run({{"sizing.estimator", "bbox"}, {"sizing.compute_hull", "false"}, {"tracking.use_poses", "true"}}, missed, truth);
  ASSERT_EQ(missed.size(), 1u);
  EXPECT_EQ(missed[0].track_id, 1);
  std::vector<int> common;
  std::set_intersection(missed[0].indices.begin(), missed[0].indices.end(), truth.begin(), truth.end(),
                        std::back_inserter(common));
  EXPECT_EQ(common.size(), truth.size()) << "every head point is predicted";
  EXPECT_EQ(missed[0].indices.size(), truth.size()) << "no ground point is";
  EXPECT_GT(truth.size(), 100u);

  run({{"sizing.estimator", "bbox"},
       {"sizing.compute_hull", "false"},
       {"tracking.use_poses", "true"},
       {"tracking.predict_missed", "false"}},
      missed, truth);
  EXPECT_TRUE(missed.empty());

  HeadMapper mapper;
  OrganizedCloud small(10, 10);
  EXPECT_THROW(mapper.predict_missed(small, cam), Error);  // intrinsics of another image size
  HeadMapperConfig bad;  // the range declared with the field: refused where it is read, and in code
  EXPECT_THROW(bad.apply({{"tracking.predict_radius_scale", "0"}}, "test"), Error);
  bad.tracking.predict_radius_scale = 0.0;
  EXPECT_THROW(HeadMapper{bad}, Error);
}
