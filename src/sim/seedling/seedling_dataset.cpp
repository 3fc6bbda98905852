// Checkerboard pairs for calibration tests and the on-disk seedling data set.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/sim/seedling/seedling_sim.hpp"

namespace cropsight::sim {

namespace fs = std::filesystem;

namespace {

// Board reflectance at board-frame (x, y): checker squares inside a white margin, grey outside.
float board_value(double x, double y, int cols, int rows, double sq) {
  if (x < -2 * sq || y < -2 * sq || x > (cols + 1) * sq || y > (rows + 1) * sq) return 90.0f;
  if (x < -sq || y < -sq || x > cols * sq || y > rows * sq) return 235.0f;
  const long i = long(std::floor(x / sq)), j = long(std::floor(y / sq));
  return ((i + j) & 1) ? 235.0f : 20.0f;
}

GrayImage render_board_view(const StereoRigModel& rig, const Eigen::Matrix3d& R_cam_to_left,
                            const Eigen::Vector3d& centre_in_left, int cols, int rows, double sq,
                            const Eigen::Matrix3d& Rb, const Eigen::Vector3d& tb, int ss) {
  GrayImage img(rig.width, rig.height);
  const Eigen::Matrix3d Rb_t = Rb.transpose();
  for (int v = 0; v < rig.height; ++v)
    for (int u = 0; u < rig.width; ++u) {
      float acc = 0;
      for (int j = 0; j < ss; ++j)
        for (int i = 0; i < ss; ++i) {
          const double x = u + (i + 0.5) / ss - 0.5, y = v + (j + 0.5) / ss - 0.5;
          const Eigen::Vector3d d = R_cam_to_left * Eigen::Vector3d((x - rig.cx) / rig.f, (y - rig.cy) / rig.f, 1);
          // Board frame: p_b = Rb^T (p - tb); intersect with z_b = 0.
          const Eigen::Vector3d o_b = Rb_t * (centre_in_left - tb), d_b = Rb_t * d;
          if (std::fabs(d_b.z()) < 1e-12) {
            acc += 90.0f;
            continue;
          }
          const double t = -o_b.z() / d_b.z();
          acc += t > 0 ? board_value(o_b.x() + t * d_b.x(), o_b.y() + t * d_b.y(), cols, rows, sq) : 90.0f;
        }
      img.at(u, v) = std::uint8_t(std::clamp(acc / float(ss * ss), 0.0f, 255.0f));
    }
  return img;
}

void write_png(const fs::path& path, const cv::Mat& m) {
  io::write_atomic_with(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), m)) throw Error(path.string(), "cannot write image");
  });
}

cv::Mat bgr(const ColorImage& im) {
  cv::Mat rgb(im.height, im.width, CV_8UC3, const_cast<Rgb8*>(im.data.data())), out;
  cv::cvtColor(rgb, out, cv::COLOR_RGB2BGR);
  return out;
}

}  // namespace

stereo::StereoCalibration ideal_calibration(const StereoRigModel& rig) {
  stereo::StereoCalibration c;
  c.width = rig.width;
  c.height = rig.height;
  c.K1 << rig.f, 0, rig.cx, 0, rig.f, rig.cy, 0, 0, 1;
  c.K2 = c.K1;
  c.D1 = c.D2 = std::vector<double>(5, 0.0);
  c.R = rig.R;
  c.T = rig.T;
  Eigen::Matrix3d tx;  // [T]x: E = [T]x R
  tx << 0, -c.T.z(), c.T.y(), c.T.z(), 0, -c.T.x(), -c.T.y(), c.T.x(), 0;
  c.E = tx * c.R;
  c.F = c.K2.inverse().transpose() * c.E * c.K1.inverse();
  return c;
}

stereo::RectifiedGeometry rectified_geometry(const StereoRigModel& rig) {
  return {rig.width, rig.height, rig.f, rig.cx, rig.cy, rig.cx, rig.baseline()};
}

CheckerboardPair render_checkerboard_pair(const StereoRigModel& rig, int cols, int rows, double square,
                                          const Eigen::Matrix3d& R_board, const Eigen::Vector3d& t_board,
                                          int supersample) {
  CheckerboardPair p;
  p.left = render_board_view(rig, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), cols, rows, square, R_board,
                             t_board, supersample);
  // Right camera: x_r = R x_l + T, so its centre is -R^T T and its axes are R^T in the left frame.
  p.right = render_board_view(rig, rig.R.transpose(), -rig.R.transpose() * rig.T, cols, rows, square, R_board, t_board,
                              supersample);
  return p;
}

std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> random_board_poses(const StereoRigModel& rig, int cols,
                                                                            int rows, double square, int n,
                                                                            std::uint64_t seed) {
  std::mt19937_64 g(seed);
  auto uni = [&](double a, double b) { return a + (b - a) * double(g() >> 11) * (1.0 / 9007199254740992.0); };
  std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> poses;
  const double deg = M_PI / 180;
  for (int tries = 0; int(poses.size()) < n && tries < 100000; ++tries) {
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(uni(-35, 35) * deg, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(uni(-35, 35) * deg, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(uni(-20, 20) * deg, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    const Eigen::Vector3d centre(uni(-0.15, 0.15), uni(-0.1, 0.1), uni(0.35, 0.8));
    const Eigen::Vector3d t = centre - R * Eigen::Vector3d((cols - 1) * square / 2, (rows - 1) * square / 2, 0);
    bool ok = true;
    for (int r = -1; r <= rows && ok; ++r)  // the whole board including one square of margin
      for (int c = -1; c <= cols && ok; ++c) {
        const Eigen::Vector3d p = R * Eigen::Vector3d(c * square, r * square, 0) + t;
        for (int cam = 0; cam < 2 && ok; ++cam) {
          const Eigen::Vector3d q = cam == 0 ? p : Eigen::Vector3d(rig.R * p + rig.T);
          if (q.z() < 0.2) {
            ok = false;
            break;
          }
          const double u = rig.f * q.x() / q.z() + rig.cx, v = rig.f * q.y() / q.z() + rig.cy;
          ok = u > 8 && v > 8 && u < rig.width - 9 && v < rig.height - 9;
        }
      }
    if (ok) poses.emplace_back(R, t);
  }
  return poses;
}

void write_seedling_dataset(const fs::path& dir, const SeedlingSimConfig& cfg, int pairs, std::uint64_t seed,
                            int calib_pairs, void (*progress)(int, void*), void* ctx) {
  if (pairs < 0 || pairs > kMaxSeedlingPairs)
    throw Error(dir.string(),
                "pair count must be in 0.." + std::to_string(kMaxSeedlingPairs) + ", got " + std::to_string(pairs));
  if (calib_pairs < 0 || calib_pairs > kMaxCalibrationPairs)
    throw Error(dir.string(), "checkerboard pair count must be in 0.." + std::to_string(kMaxCalibrationPairs) +
                                  ", got " + std::to_string(calib_pairs));
  for (int k = 0; k < pairs; ++k) {
    const SeedlingPair p = simulate_seedling_pair(cfg, seed, k);
    char name[32];
    std::snprintf(name, sizeof name, "pair_%03d", k);
    const fs::path pd = dir / name;
    write_png(pd / "left.png", bgr(p.left));
    write_png(pd / "right.png", bgr(p.right));
    cv::Mat disp(p.disparity.height, p.disparity.width, CV_16U);
    for (int i = 0; i < int(p.disparity.size()); ++i) {
      const float d = p.disparity.data[i];
      disp.at<std::uint16_t>(i / p.disparity.width, i % p.disparity.width) =
          std::isfinite(d) ? std::uint16_t(std::clamp(std::lround(d * 256.0), 0L, 65535L)) : 0;
    }
    write_png(pd / "disparity.png", disp);
    write_png(pd / "mask.png",
              cv::Mat(p.mask.height, p.mask.width, CV_8U, const_cast<std::uint8_t*>(p.mask.data.data())));
    const StereoRigModel rig = cfg.rig();
    nlohmann::json j = {
        {"seed", seed},
        {"index", k},
        {"distance_m", p.distance},
        {"tilt_deg", p.tilt_deg},
        {"exposure", p.exposure},
        {"leaves", p.leaves},
        {"weeds", p.weeds},
        {"envelope",
         {{"length_m", p.envelope.length},
          {"width_m", p.envelope.width},
          {"height_m", p.envelope.height},
          {"volume_m3", p.envelope.volume()}}},
        {"plane", {{"normal", {p.plane_normal.x(), p.plane_normal.y(), p.plane_normal.z()}}, {"d", p.plane_d}}},
        {"seedling_base_m", {p.seedling_base.x(), p.seedling_base.y(), p.seedling_base.z()}},
        {"rig", {{"f_px", rig.f}, {"cx", rig.cx}, {"cy", rig.cy}, {"baseline_m", rig.baseline()}}},
        {"disparity_scale", 256}};
    io::write_file_atomic(pd / "truth.json", j.dump(2) + "\n");
    if (progress) progress(k + 1, ctx);
  }
  if (calib_pairs > 0) {
    const StereoRigModel rig = cfg.rig();
    const auto poses = random_board_poses(rig, 9, 6, 0.03, calib_pairs, seed + 99);
    for (std::size_t k = 0; k < poses.size(); ++k) {
      const CheckerboardPair b = render_checkerboard_pair(rig, 9, 6, 0.03, poses[k].first, poses[k].second);
      char name[32];
      std::snprintf(name, sizeof name, "%03zu.png", k);
      write_png(dir / "calib" / ("left_" + std::string(name)),
                cv::Mat(b.left.height, b.left.width, CV_8U, const_cast<std::uint8_t*>(b.left.data.data())));
      write_png(dir / "calib" / ("right_" + std::string(name)),
                cv::Mat(b.right.height, b.right.width, CV_8U, const_cast<std::uint8_t*>(b.right.data.data())));
    }
  }
}

}  // namespace cropsight::sim
