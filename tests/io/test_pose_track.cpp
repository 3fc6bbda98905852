// Pose files (CSV, TUM) and their join to frame times (pose_track.hpp).
#include <gtest/gtest.h>

#include "cropsight/core/error.hpp"
#include "cropsight/io/pose_track.hpp"
#include "testing/testing.hpp"

namespace cropsight::io {
namespace {

using cropsight::testing::error_message;
using cropsight::testing::TempDir;
using cropsight::testing::write_text;

TEST(PoseTrack, CsvColumnsByName) {
  TempDir t;
  // Any column order, extra columns ignored, comments and blank lines skipped.
  write_text(t / "odom.csv", "# wheel odometry\nspeed,z,y,x,timestamp\n\n0.5,1.2,0,0.0,100.0\n0.5,1.2,0,0.1,100.2\n");
  const PoseTrack p = read_pose_track(t / "odom.csv");
  EXPECT_EQ(p.format, "csv");
  ASSERT_EQ(p.poses.size(), 2u);
  EXPECT_DOUBLE_EQ(p.poses[1].time, 100.2);
  EXPECT_DOUBLE_EQ(p.poses[1].position.x(), 0.1);
  EXPECT_DOUBLE_EQ(p.poses[1].position.z(), 1.2);
  EXPECT_FALSE(p.poses[0].orientation.has_value());
}

TEST(PoseTrack, TumWithOrientation) {
  TempDir t;
  write_text(t / "traj.txt",
             "# timestamp tx ty tz qx qy qz qw\n1.0 0 0 1 0 0 0 1\n1.5 0.2 0 1 0 0 0.7071068 0.7071068\n");
  const PoseTrack p = read_pose_track(t / "traj.txt");
  EXPECT_EQ(p.format, "tum");
  ASSERT_EQ(p.poses.size(), 2u);
  ASSERT_TRUE(p.poses[1].orientation.has_value());
  EXPECT_NEAR(p.poses[1].orientation->z(), 0.7071068, 1e-12);
  EXPECT_DOUBLE_EQ(p.poses[1].position.x(), 0.2);
}

// GNSS fixes as a pose file: local metres (origin at the first fix, x along the travel) and the
// geo origin that ties them to WGS84; back to the same latitude and longitude through it.
TEST(PoseTrack, GnssFixesBecomeLocalPositionsWithTheirOrigin) {
  TempDir t;
  // Due north, 0.0001° of latitude apart (about 11.1 m).
  write_text(t / "fixes.csv", "timestamp,lat,lon,alt\n10.0,52.2,0.12,20\n11.0,52.2001,0.12,20\n");
  const PoseTrack p = read_pose_track(t / "fixes.csv");
  EXPECT_EQ(p.format, "gnss");
  ASSERT_TRUE(p.geo_origin.has_value());
  EXPECT_DOUBLE_EQ(p.geo_origin->latitude_deg, 52.2);
  EXPECT_NEAR(p.geo_origin->field_x_azimuth_deg, 0.0, 1e-3);  // x along the travel: north
  ASSERT_EQ(p.poses.size(), 2u);
  EXPECT_DOUBLE_EQ(p.poses[0].time, 10.0);
  EXPECT_NEAR(p.poses[0].position.norm(), 0.0, 1e-9);
  EXPECT_NEAR(p.poses[1].position.x(), 11.13, 0.02);  // WGS84 metres per 0.0001° of latitude at 52.2°
  EXPECT_NEAR(p.poses[1].position.y(), 0.0, 1e-6);
  const Wgs84 back = GeoReference(*p.geo_origin).to_wgs84(p.poses[1].position);
  EXPECT_NEAR(back.latitude_deg, 52.2001, 1e-9);
  EXPECT_NEAR(back.longitude_deg, 0.12, 1e-9);
}

// One line naming the file, the line and the problem.
TEST(PoseTrack, BadFiles) {
  TempDir t;
  auto error_of = [&](const std::string& name, const std::string& text) {
    write_text(t / name, text);
    return error_message([&] { read_pose_track(t / name); });
  };
  const std::string nan_time = error_of("a.csv", "timestamp,x,y,z\n0,0,0,0\nnan,1,0,0\n");
  EXPECT_NE(nan_time.find("a.csv"), std::string::npos);
  EXPECT_NE(nan_time.find("line 3: timestamp must be a finite number, got 'nan'"), std::string::npos) << nan_time;
  const std::string back = error_of("b.txt", "2.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n");
  EXPECT_NE(back.find("line 2: time 1 s does not increase (previous 2 s)"), std::string::npos) << back;
  const std::string same = error_of("c.csv", "t,x,y,z\n1,0,0,0\n1,0,0,0\n");
  EXPECT_NE(same.find("does not increase"), std::string::npos) << same;
  const std::string tum_nan = error_of("d.tum", "nan 0 0 0 0 0 0 1\n");
  EXPECT_NE(tum_nan.find("line 1: t must be a finite number"), std::string::npos) << tum_nan;
  const std::string quat = error_of("e.txt", "1.0 0 0 0 0 0 0 2\n");
  EXPECT_NE(quat.find("not of unit length"), std::string::npos) << quat;
  const std::string unknown = error_of("f.csv", "speed,heading\n1.1,5.2\n");
  EXPECT_NE(unknown.find("not a pose file in a known format (csv: "), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("tum: "), std::string::npos);
  EXPECT_NE(unknown.find("gnss: "), std::string::npos);
  // Latitude and longitude without time: the GNSS reader names the header it needs.
  const std::string untimed = error_of("f2.csv", "lat,lon\n52.1,5.2\n");
  EXPECT_NE(untimed.find("expected the header timestamp,lat,lon"), std::string::npos) << untimed;
  const std::string no_z = error_of("g.csv", "timestamp,x,y\n1,2,3\n");
  EXPECT_NE(no_z.find("not a pose file"), std::string::npos) << no_z;  // needs 4 columns to be a pose CSV
  const std::string header_only = error_of("h.csv", "timestamp,x,y,z\n");
  EXPECT_NE(header_only.find("no poses after the header"), std::string::npos) << header_only;
  const std::string ragged = error_of("i.csv", "timestamp,x,y,z\n1,2,3\n");
  EXPECT_NE(ragged.find("line 2: expected 4 values as in the header, got 3"), std::string::npos) << ragged;
}

TEST(PoseTrack, JoinInterpolatesWithinTolerance) {
  PoseTrack p;
  p.poses = {{10.0, {0, 0, 1}, {}}, {10.1, {1, 0, 1}, {}}, {10.2, {2, 2, 1}, {}}};
  const auto at = join_poses(p, {10.0, 10.05, 10.175, 10.23}, 0.08, "poses.csv");
  ASSERT_EQ(at.size(), 4u);
  EXPECT_NEAR(at[0].x(), 0.0, 1e-12);
  EXPECT_NEAR(at[1].x(), 0.5, 1e-9);
  EXPECT_NEAR(at[2].x(), 1.75, 1e-9);
  EXPECT_NEAR(at[2].y(), 1.5, 1e-9);
  EXPECT_NEAR(at[3].x(), 2.0, 1e-12);  // past the end, within tolerance: the last pose
  const std::string far = error_message([&] { join_poses(p, {10.0, 10.3}, 0.08, "poses.csv"); });
  EXPECT_NE(far.find("poses.csv"), std::string::npos);
  EXPECT_NE(far.find("no pose within 0.08 s of frame 1 at t = 10.3 s"), std::string::npos) << far;
}

}  // namespace
}  // namespace cropsight::io
