#include "cropsight/stereo/calibration.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <iterator>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cv_convert.hpp"
#include "io/decode_image.hpp"
#include "io/yaml_key.hpp"

namespace cropsight::stereo {

namespace fs = std::filesystem;

std::vector<Eigen::Vector3f> Checkerboard::object_points() const {
  std::vector<Eigen::Vector3f> p;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) p.emplace_back(float(c * square_size), float(r * square_size), 0.0f);
  return p;
}

void Checkerboard::validate(const std::string& where) const {
  if (cols < kMinBoardCorners || rows < kMinBoardCorners || cols > kMaxBoardCorners || rows > kMaxBoardCorners)
    throw Error(where, "checkerboard needs " + std::to_string(kMinBoardCorners) + ".." +
                           std::to_string(kMaxBoardCorners) + " inner corners each way, got " + std::to_string(cols) +
                           "x" + std::to_string(rows));
  if (!(square_size > 0 && square_size <= kMaxSquareSize))
    throw Error(where, "checkerboard square size must be finite, > 0 and at most " +
                           std::to_string(int(kMaxSquareSize * 1000)) + " mm");
}

namespace {

Eigen::Matrix3d to_eigen(const cv::Mat& m) {
  Eigen::Matrix3d e;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) e(r, c) = m.at<double>(r, c);
  return e;
}

std::vector<double> to_vec(const cv::Mat& m) {
  std::vector<double> v;
  for (int i = 0; i < int(m.total()); ++i) v.push_back(m.at<double>(i));
  return v;
}

}  // namespace

StereoCalibration calibrate_stereo(const std::vector<std::vector<Eigen::Vector2f>>& left_corners,
                                   const std::vector<std::vector<Eigen::Vector2f>>& right_corners,
                                   const Checkerboard& board, int width, int height, const CalibrationConfig& cfg,
                                   const std::string& where) {
  if (left_corners.size() != right_corners.size())
    throw Error(where, "left and right view counts differ (" + std::to_string(left_corners.size()) + " vs " +
                           std::to_string(right_corners.size()) + ")");
  if (int(left_corners.size()) < cfg.min_views)
    throw Error(where, "too few checkerboard views: " + std::to_string(left_corners.size()) + " (need at least " +
                           std::to_string(cfg.min_views) + ")");
  board.validate(where);
  if (cfg.min_views < 1) throw Error(where, "'min_views' must be >= 1");
  if (width <= 0 || height <= 0) throw Error(where, "invalid image size");
  const std::size_t nc = std::size_t(board.cols) * board.rows;
  std::vector<cv::Point3f> obj;
  for (const auto& p : board.object_points()) obj.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<cv::Point3f>> objects;
  std::vector<std::vector<cv::Point2f>> l, r;
  for (std::size_t v = 0; v < left_corners.size(); ++v) {
    if (left_corners[v].size() != nc || right_corners[v].size() != nc)
      throw Error(where, "view " + std::to_string(v) + " has the wrong number of corners");
    objects.push_back(obj);
    l.emplace_back();
    r.emplace_back();
    for (std::size_t i = 0; i < nc; ++i) {
      l.back().emplace_back(left_corners[v][i].x(), left_corners[v][i].y());
      r.back().emplace_back(right_corners[v][i].x(), right_corners[v][i].y());
    }
  }
  const cv::Size size(width, height);
  int flags = cfg.fix_k3 ? cv::CALIB_FIX_K3 : 0;
  cv::Mat k1, d1, k2, d2, rvecs, tvecs;
  cv::calibrateCamera(objects, l, size, k1, d1, rvecs, tvecs, flags);
  cv::calibrateCamera(objects, r, size, k2, d2, rvecs, tvecs, flags);
  cv::Mat R, T, E, F;
  const double rms =
      cv::stereoCalibrate(objects, l, r, k1, d1, k2, d2, size, R, T, E, F, flags | cv::CALIB_USE_INTRINSIC_GUESS,
                          cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-7));
  StereoCalibration c;
  c.width = width;
  c.height = height;
  c.K1 = to_eigen(k1);
  c.K2 = to_eigen(k2);
  c.D1 = to_vec(d1);
  c.D2 = to_vec(d2);
  c.R = to_eigen(R);
  c.T = Eigen::Vector3d(T.at<double>(0), T.at<double>(1), T.at<double>(2));
  c.E = to_eigen(E);
  c.F = to_eigen(F);
  c.rms = rms;
  c.views = int(objects.size());
  return c;
}

bool find_corners(const GrayImage& image, const Checkerboard& board, std::vector<Eigen::Vector2f>& corners) {
  board.validate("checkerboard");
  std::vector<cv::Point2f> pts;
  cv::Mat m = detail::view(image);
  const bool ok = cv::findChessboardCorners(m, cv::Size(board.cols, board.rows), pts,
                                            cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
  corners.clear();
  if (!ok) return false;
  cv::cornerSubPix(m, pts, cv::Size(5, 5), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-3));
  for (const auto& p : pts) corners.emplace_back(p.x, p.y);
  return true;
}

StereoCalibration calibrate_stereo_folder(const fs::path& dir, const Checkerboard& board,
                                          const CalibrationConfig& cfg) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "calibration image folder not found");
  board.validate(dir.string());  // before OpenCV's corner finder asserts on it
  std::vector<fs::path> lefts;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("left", 0) == 0) lefts.push_back(e.path());
  }
  std::sort(lefts.begin(), lefts.end());
  if (lefts.empty()) throw Error(dir.string(), "no left_*.png / right_*.png checkerboard pairs");
  std::vector<std::vector<Eigen::Vector2f>> lc, rc;
  int w = 0, h = 0;
  for (const auto& lp : lefts) {
    fs::path rp = lp.parent_path() / ("right" + lp.filename().string().substr(4));
    if (!fs::exists(rp)) throw Error(lp.string(), "no matching right image " + rp.filename().string());
    cv::Mat l = io::decode_image_file(lp, cv::IMREAD_GRAYSCALE), r = io::decode_image_file(rp, cv::IMREAD_GRAYSCALE);
    if (l.empty()) throw Error(lp.string(), "cannot decode image");
    if (r.empty()) throw Error(rp.string(), "cannot decode image");
    if (l.size() != r.size()) throw Error(rp.string(), "size differs from the left image");
    if (w == 0) w = l.cols, h = l.rows;
    if (l.cols != w || l.rows != h) throw Error(lp.string(), "size differs from the other calibration images");
    std::vector<Eigen::Vector2f> a, b;
    if (find_corners(detail::to_gray(l), board, a) && find_corners(detail::to_gray(r), board, b)) {
      lc.push_back(std::move(a));
      rc.push_back(std::move(b));
    }
  }
  if (int(lc.size()) < cfg.min_views)
    throw Error(dir.string(), "too few checkerboard views: board found in both images of " + std::to_string(lc.size()) +
                                  " of " + std::to_string(lefts.size()) + " pairs (need at least " +
                                  std::to_string(cfg.min_views) + ")");
  return calibrate_stereo(lc, rc, board, w, h, cfg, dir.string());
}

namespace {

void emit_matrix(YAML::Emitter& out, const char* key, const double* v, int n) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < n; ++i) out << v[i];
  out << YAML::EndSeq;
}

void emit_matrix(YAML::Emitter& out, const char* key, const Eigen::Matrix3d& m) {
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> r = m;
  emit_matrix(out, key, r.data(), 9);
}

std::vector<double> read_list(const YAML::Node& root, const std::string& key, std::size_t n, const std::string& where,
                              bool any_length = false) {
  const YAML::Node node = root[key];
  if (!node) throw Error(where, "missing key '" + key + "'");
  if (!node.IsSequence() || (!any_length && node.size() != n))
    throw Error(where, "key '" + key + "' must be a list of " + std::to_string(n) + " numbers");
  std::vector<double> v;
  try {
    for (const auto& x : node) v.push_back(x.as<double>());
  } catch (const YAML::Exception&) {
    throw Error(where, "key '" + key + "' holds a non-number");
  }
  return v;
}

Eigen::Matrix3d read_matrix(const YAML::Node& root, const std::string& key, const std::string& where) {
  const auto v = read_list(root, key, 9, where);
  Eigen::Matrix3d m;
  for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = v[i];
  return m;
}

}  // namespace

void save_calibration(const fs::path& path, const StereoCalibration& c) {
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::BeginMap;
  out << YAML::Key << "image_width" << YAML::Value << c.width;
  out << YAML::Key << "image_height" << YAML::Value << c.height;
  emit_matrix(out, "K1", c.K1);
  emit_matrix(out, "D1", c.D1.data(), int(c.D1.size()));
  emit_matrix(out, "K2", c.K2);
  emit_matrix(out, "D2", c.D2.data(), int(c.D2.size()));
  emit_matrix(out, "R", c.R);
  emit_matrix(out, "T", c.T.data(), 3);
  emit_matrix(out, "E", c.E);
  emit_matrix(out, "F", c.F);
  out << YAML::Key << "rms" << YAML::Value << c.rms;
  out << YAML::Key << "views" << YAML::Value << c.views;
  out << YAML::EndMap;
  io::write_file_atomic(
      path, std::string("# cropsight stereo calibration: T in metres, x_right = R x_left + T\n") + out.c_str() + "\n");
}

StereoCalibration load_calibration(const fs::path& path) {
  const std::string where = path.string();
  YAML::Node root;
  try {
    root = YAML::Load(io::read_file(path));
  } catch (const YAML::Exception& e) {
    throw Error(where, "malformed YAML at line " + std::to_string(e.mark.line + 1));
  }
  if (!root.IsMap()) throw Error(where, "expected a YAML map of calibration keys");
  static const char* const kKeys[] = {"image_width", "image_height", "K1",   "D1", "K2", "D2", "R", "T", "E",
                                      "F",           "rms",          "views"};
  for (const auto& kv : root) {
    const std::string key = io::detail::yaml_key(kv.first, where);
    if (std::find_if(std::begin(kKeys), std::end(kKeys), [&](const char* k) { return key == k; }) == std::end(kKeys))
      throw Error(where, "unknown key '" + key + "'");
  }
  StereoCalibration c;
  for (const char* key : {"image_width", "image_height"}) {
    if (!root[key]) throw Error(where, std::string("missing key '") + key + "'");
    try {
      (std::string(key) == "image_width" ? c.width : c.height) = root[key].as<int>();
    } catch (const YAML::Exception&) {
      throw Error(where, std::string("key '") + key + "' must be an integer");
    }
  }
  if (c.width <= 0 || c.height <= 0) throw Error(where, "image size must be positive");
  c.K1 = read_matrix(root, "K1", where);
  c.K2 = read_matrix(root, "K2", where);
  c.D1 = read_list(root, "D1", 0, where, true);
  c.D2 = read_list(root, "D2", 0, where, true);
  c.R = read_matrix(root, "R", where);
  const auto t = read_list(root, "T", 3, where);
  c.T = Eigen::Vector3d(t[0], t[1], t[2]);
  c.E = read_matrix(root, "E", where);
  c.F = read_matrix(root, "F", where);
  try {
    if (root["rms"]) c.rms = root["rms"].as<double>();
    if (root["views"]) c.views = root["views"].as<int>();
  } catch (const YAML::Exception&) {
    throw Error(where, "keys 'rms' and 'views' must be numbers");
  }
  if (!(c.K1(0, 0) > 0) || !(c.K2(0, 0) > 0)) throw Error(where, "focal lengths in K1/K2 must be positive");
  if (!(c.baseline() > 0)) throw Error(where, "T is zero: no baseline");
  return c;
}

}  // namespace cropsight::stereo
