#include <gtest/gtest.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/pcl_conversions.hpp"
#include "cropsight/core/rgbd_frame.hpp"
#include "cropsight/core/segment.hpp"

using namespace cropsight;

namespace {
RgbdFrame make_frame() {
  RgbdFrame f;
  f.camera = CameraIntrinsics::from_fov(8, 6, 1.2, 1.0);
  f.camera.depth_scale = 0.001;
  f.depth = DepthImage(8, 6, 1000);
  f.depth.at(2, 3) = 0;     // no return
  f.depth.at(5, 1) = 3000;  // beyond max depth in one test
  return f;
}
}  // namespace

TEST(OrganizedCloud, DeprojectionKeepsLayoutAndMarksHoles) {
  const RgbdFrame f = make_frame();
  const OrganizedCloud c = to_organized_cloud(f);
  ASSERT_EQ(c.width, 8);
  ASSERT_EQ(c.height, 6);
  EXPECT_FALSE(c.valid(c.index(2, 3)));
  EXPECT_TRUE(c.valid(c.index(5, 1)));
  EXPECT_EQ(c.count_valid(), 47u);
  const Eigen::Vector3f expect = f.camera.deproject(4, 2, 1.0f);
  EXPECT_NEAR(c.x[c.index(4, 2)], expect.x(), 1e-6);
  EXPECT_NEAR(c.y[c.index(4, 2)], expect.y(), 1e-6);
}

TEST(OrganizedCloud, DepthRangeFilter) {
  const OrganizedCloud c = to_organized_cloud(make_frame(), 0.5f, 2.0f);
  EXPECT_FALSE(c.valid(c.index(5, 1)));
  EXPECT_EQ(c.count_valid(), 46u);
}

TEST(OrganizedCloud, PclRoundTripKeepsOrganisation) {
  const OrganizedCloud c = to_organized_cloud(make_frame());
  pcl::PointCloud<pcl::PointXYZ> p;
  to_pcl(c, p);
  EXPECT_EQ(p.width, 8u);
  EXPECT_EQ(p.height, 6u);
  EXPECT_FALSE(p.is_dense);
  EXPECT_TRUE(p.isOrganized());
  const OrganizedCloud back = organized_from_pcl(p);
  ASSERT_EQ(back.size(), c.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(back.valid(i), c.valid(i));
    if (c.valid(i)) {
      EXPECT_EQ(back.z[i], c.z[i]);
    }
  }
}

TEST(OrganizedCloud, UnorganisedPclIsRejected) {
  pcl::PointCloud<pcl::PointXYZ> p;
  p.push_back({1, 2, 3});
  EXPECT_THROW(organized_from_pcl(p), Error);
}

TEST(Cloud, ColourSurvivesPcl) {
  Cloud c;
  c.points = {{1, 2, 3}, {4, 5, 6}};
  c.colors = {{1, 0, 0}, {0, 0.5f, 1}};
  pcl::PointCloud<pcl::PointXYZRGB> p;
  to_pcl(c, p);
  EXPECT_EQ(p[1].g, 128);
  const Cloud back = cloud_from_pcl(p);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_NEAR(back.colors[1].y(), 0.5f, 0.01f);
  EXPECT_NO_THROW(back.validate("x"));
}

TEST(Segment, SummaryComputesBoxAndCentroid) {
  const OrganizedCloud c = to_organized_cloud(make_frame());
  Segment s;
  s.indices = {c.index(1, 1), c.index(3, 4)};
  summarize(s, c);
  EXPECT_EQ(s.box, (Box2D{1, 1, 3, 4}));
  EXPECT_NEAR(s.centroid.z(), 1.0f, 1e-6);
}
