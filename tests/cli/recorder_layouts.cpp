#include "cli/recorder_layouts.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>

#include "cropsight/io/files.hpp"
#include "testing/testing.hpp"

namespace cropsight::testing {

namespace fs = std::filesystem;

namespace recorder_layout_impl {

struct ColorRig {
  CameraIntrinsics camera;
  Eigen::Matrix3d rotation;  // depth -> colour
  Eigen::Vector3d translation;
};

ColorRig rig_of(Recorder r) {
  ColorRig rig;
  CameraIntrinsics& c = rig.camera;
  const bool rs = r == Recorder::RealSense;
  c.width = rs ? 640 : 960;
  c.height = rs ? 480 : 540;
  c.fx = rs ? 380.0 : 470.0;
  c.fy = rs ? 381.0 : 471.0;
  c.cx = rs ? 321.3 : 481.7;
  c.cy = rs ? 238.9 : 268.2;
  c.distortion =
      rs ? std::vector<double>{0.0, 0.0, 0.0, 0.0, 0.0} : std::vector<double>{0.02, -0.03, 0.0005, 0.0, 0.01};
  rig.rotation = Eigen::AngleAxisd(rs ? 0.004 : 0.012, Eigen::Vector3d(0.2, 1.0, -0.1).normalized()).toRotationMatrix();
  rig.translation = rs ? Eigen::Vector3d(0.0149, 0.0002, 0.0003) : Eigen::Vector3d(-0.0521, 0.0004, 0.0012);
  return rig;
}

std::string list(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    char b[64];
    std::snprintf(b, sizeof b, "%s%.17g", i ? ", " : "", v[i]);
    s += b;
  }
  return s + "]";
}

std::string echo_yaml(const CameraIntrinsics& c) {  // rostopic echo of a sensor_msgs/CameraInfo
  return "header:\n  seq: 0\n  stamp:\n    secs: 0\n    nsecs: 0\n  frame_id: \"camera\"\nheight: " +
         std::to_string(c.height) + "\nwidth: " + std::to_string(c.width) + "\ndistortion_model: \"plumb_bob\"\nD: " +
         list(c.distortion.empty() ? std::vector<double>(5, 0.0) : c.distortion) +
         "\nK: " + list({c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}) + "\nR: " + list({1, 0, 0, 0, 1, 0, 0, 0, 1}) +
         "\nP: " + list({c.fx, 0, c.cx, 0, 0, c.fy, c.cy, 0, 0, 0, 1, 0}) + "\nbinning_x: 0\nbinning_y: 0\n---\n";
}

std::string calibration_yaml(const CameraIntrinsics& c) {  // camera_calibration's ost.yaml
  const std::vector<double> d = c.distortion.empty() ? std::vector<double>(5, 0.0) : c.distortion;
  return "image_width: " + std::to_string(c.width) + "\nimage_height: " + std::to_string(c.height) +
         "\ncamera_name: cam\ncamera_matrix:\n  rows: 3\n  cols: 3\n  data: " +
         list({c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}) +
         "\ndistortion_model: plumb_bob\ndistortion_coefficients:\n  rows: 1\n  cols: 5\n  data: " + list(d) + "\n";
}

std::string extrinsics_yaml(const ColorRig& rig, bool inverse) {
  Eigen::Matrix3d r = rig.rotation;
  Eigen::Vector3d t = rig.translation;
  if (inverse) {
    r.transposeInPlace();
    t = -(r * t);
  }
  std::vector<double> rv;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rv.push_back(r(i, j));
  return std::string(inverse ? "color_to_depth" : "depth_to_color") + ":\n  rotation: " + list(rv) +
         "\n  translation: " + list({t.x(), t.y(), t.z()}) + "\n";
}

// The colour camera's view of one frame: every depth pixel splatted, nearest surface first, over
// the colour pixels its footprint covers; grey where no surface lands.
cv::Mat render_color(const RgbdFrame& f, const ColorRig& rig) {
  const CameraIntrinsics& dc = f.camera;
  const CameraIntrinsics& cc = rig.camera;
  std::vector<cv::Point3d> points;
  std::vector<Rgb8> colours;
  for (int v = 0; v < dc.height; ++v)
    for (int u = 0; u < dc.width; ++u) {
      if (f.depth.at(u, v) == 0) continue;
      const double z = f.depth.at(u, v) * dc.depth_scale;
      points.emplace_back((u - dc.cx) / dc.fx * z, (v - dc.cy) / dc.fy * z, z);
      colours.push_back(f.color.at(u, v));
    }
  cv::Mat r, rvec, tvec, k = (cv::Mat_<double>(3, 3) << cc.fx, 0, cc.cx, 0, cc.fy, cc.cy, 0, 0, 1);
  cv::eigen2cv(rig.rotation, r);
  cv::Rodrigues(r, rvec);
  cv::eigen2cv(rig.translation, tvec);
  std::vector<cv::Point2d> px;
  cv::projectPoints(points, rvec, tvec, k, cv::Mat(cc.distortion), px);
  cv::Mat out(cc.height, cc.width, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::Mat zbuf(cc.height, cc.width, CV_64F, cv::Scalar(std::numeric_limits<double>::infinity()));
  const int reach = int(std::ceil(0.5 * cc.fx / dc.fx));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d q = rig.rotation * Eigen::Vector3d(points[i].x, points[i].y, points[i].z) + rig.translation;
    const int cu = int(std::lround(px[i].x)), cv_ = int(std::lround(px[i].y));
    for (int y = cv_ - reach; y <= cv_ + reach; ++y)
      for (int x = cu - reach; x <= cu + reach; ++x) {
        if (x < 0 || y < 0 || x >= cc.width || y >= cc.height) continue;
        // The pixel a point projects to is its own; the footprint around it yields to nearer
        // surfaces and to other points' own pixels.
        const double key = q.z() + ((x == cu && y == cv_) ? 0.0 : 0.005);
        if (key >= zbuf.at<double>(y, x)) continue;
        zbuf.at<double>(y, x) = key;
        out.at<cv::Vec3b>(y, x) = cv::Vec3b(colours[i].b, colours[i].g, colours[i].r);
      }
  }
  return out;
}

std::string stamp_name(double ms) {
  char b[64];
  std::snprintf(b, sizeof b, "%.3f", ms);
  return b;
}

}  // namespace recorder_layout_impl

using namespace recorder_layout_impl;

RecorderLayout write_recorder_layout(const io::SequenceReader& seq, const fs::path& dir, Recorder recorder) {
  const bool rs = recorder == Recorder::RealSense;
  const ColorRig rig = rig_of(recorder);
  RecorderLayout l{dir / "depth",
                   dir / "color",
                   dir / "depth_info.yaml",
                   dir / "color_info.yaml",
                   dir / "extrinsics.yaml",
                   dir / (rs ? "poses.csv" : "trajectory.txt"),
                   rs ? "" : "--timestamps " + shell_quoted(dir / "timestamps.csv")};
  fs::create_directories(l.depth_dir);
  fs::create_directories(l.color_dir);
  write_text(l.depth_info, rs ? echo_yaml(seq.info().camera) : calibration_yaml(seq.info().camera));
  write_text(l.color_info, rs ? calibration_yaml(rig.camera) : echo_yaml(rig.camera));
  write_text(l.extrinsics, extrinsics_yaml(rig, !rs));
  write_text(l.depth_dir / "README.txt", "depth in millimetres\n");
  std::string poses = rs ? "timestamp,x,y,z,qx,qy,qz,qw\n" : "# timestamp tx ty tz qx qy qz qw\n";
  const double t0 = 1596203844.0;  // RealSense names carry Unix milliseconds; the Kinect's CSV seconds
  std::string times = "frame,timestamp\n";
  for (int i = 0; i < seq.size(); ++i) {
    const RgbdFrame f = seq.read(i);
    const double t = t0 + f.timestamp;
    const std::string key = rs ? stamp_name(t * 1000.0) : std::to_string(1000 + i).substr(1);
    char time_row[64];
    std::snprintf(time_row, sizeof time_row, "%d,%.6f\n", i, t);
    times += time_row;
    fs::copy_file(seq.depth_path(i), l.depth_dir / (rs ? "_Depth_" + key + ".png" : key + "_depth.png"));
    const std::string color_name = rs ? "_Color_" + stamp_name(t * 1000.0 + 3.217) + ".jpg" : key + "_color.jpg";
    cv::imwrite((l.color_dir / color_name).string(), render_color(f, rig), {cv::IMWRITE_JPEG_QUALITY, 95});
    const Eigen::Vector3d& p = *f.camera_position;
    char row[256];
    std::snprintf(row, sizeof row, rs ? "%.6f,%.17g,%.17g,%.17g,0,0,0,1\n" : "%.17g %.17g %.17g %.17g 0 0 0 1\n", t,
                  p.x(), p.y(), p.z());
    poses += row;
    if (i + 1 < seq.size()) {  // a pose between two frames too, as an odometry log has
      const RgbdFrame g = seq.read(i + 1);
      const Eigen::Vector3d m = 0.5 * (p + *g.camera_position);
      const double tm = 0.5 * (t + t0 + g.timestamp);
      std::snprintf(row, sizeof row, rs ? "%.6f,%.17g,%.17g,%.17g,0,0,0,1\n" : "%.17g %.17g %.17g %.17g 0 0 0 1\n", tm,
                    m.x(), m.y(), m.z());
      poses += row;
    }
  }
  write_text(l.poses, poses);
  if (!rs) write_text(dir / "timestamps.csv", times);
  return l;
}

}  // namespace cropsight::testing
