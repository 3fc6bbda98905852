// Detector training augmentation and the training preset's sections
// (include/cropsight/nn/detection_augment.hpp), on OpenCV.
#include "cropsight/nn/detection_augment.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "cropsight/core/error.hpp"

namespace cropsight::nn {

namespace {

cv::Mat as_mat(const ColorImage& im) {
  return cv::Mat(im.height, im.width, CV_8UC3, const_cast<Rgb8*>(im.data.data()));
}
cv::Mat as_mat(const GrayImage& im) {
  return cv::Mat(im.height, im.width, CV_8UC1, const_cast<std::uint8_t*>(im.data.data()));
}
ColorImage to_color(const cv::Mat& m) {
  ColorImage out(m.cols, m.rows);
  m.copyTo(as_mat(out));
  return out;
}
GrayImage to_gray(const cv::Mat& m) {
  GrayImage out(m.cols, m.rows);
  m.copyTo(as_mat(out));
  return out;
}

// Applies the affine map x' = a x + b (per axis) to the image, masks and boxes; output w x h.
DetectionSample warp(const DetectionSample& s, double ax, double bx, double ay, double by, int w, int h,
                     double min_visible) {
  // Boxes are continuous (pixel i spans [i, i + 1)); OpenCV maps pixel centres, i + 0.5.
  const cv::Mat M = (cv::Mat_<double>(2, 3) << ax, 0, bx + 0.5 * (ax - 1), 0, ay, by + 0.5 * (ay - 1));
  DetectionSample out;
  out.name = s.name;
  cv::Mat img;
  cv::warpAffine(as_mat(s.image), img, M, cv::Size(w, h), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(114));
  out.image = to_color(img);
  for (const auto& m : s.masks) {
    cv::Mat o;
    cv::warpAffine(as_mat(m), o, M, cv::Size(w, h), cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar(0));
    out.masks.push_back(to_gray(o));
  }
  for (const auto& b : s.boxes) {
    Detection2D d = b;
    d.x1 = float(ax * b.x1 + bx), d.x2 = float(ax * b.x2 + bx);
    d.y1 = float(ay * b.y1 + by), d.y2 = float(ay * b.y2 + by);
    if (d.x1 > d.x2) std::swap(d.x1, d.x2);
    const float full = d.area();
    d.x1 = std::clamp(d.x1, 0.f, float(w)), d.x2 = std::clamp(d.x2, 0.f, float(w));
    d.y1 = std::clamp(d.y1, 0.f, float(h)), d.y2 = std::clamp(d.y2, 0.f, float(h));
    if (d.width() >= 2 && d.height() >= 2 && d.area() >= float(min_visible) * full) out.boxes.push_back(d);
  }
  return out;
}

// The 2 x 2 mosaic of four samples, each stretched to a quarter of s's frame.
DetectionSample mosaic(const DetectionSample& s, const std::vector<const DetectionSample*>& four, double min_visible) {
  const int W = s.image.width, H = s.image.height, hw = W / 2, hh = H / 2;
  DetectionSample out;
  out.name = s.name;
  out.image = ColorImage(W, H, Rgb8{114, 114, 114});
  const bool masks = std::all_of(four.begin(), four.end(), [&](const DetectionSample* p) {
    return !p->masks.empty() && p->masks.size() == s.masks.size();
  });
  if (masks) out.masks.assign(s.masks.size(), GrayImage(W, H));
  for (int q = 0; q < 4; ++q) {
    const DetectionSample& p = *four[std::size_t(q)];
    const int ox = (q % 2) * hw, oy = (q / 2) * hh;
    const double ax = double(hw) / p.image.width, ay = double(hh) / p.image.height;
    const DetectionSample t = warp(p, ax, ox, ay, oy, W, H, min_visible);
    const cv::Rect r(ox, oy, hw, hh);
    as_mat(t.image)(r).copyTo(as_mat(out.image)(r));
    if (masks)
      for (std::size_t c = 0; c < out.masks.size(); ++c) as_mat(t.masks[c])(r).copyTo(as_mat(out.masks[c])(r));
    out.boxes.insert(out.boxes.end(), t.boxes.begin(), t.boxes.end());
  }
  return out;
}

// Pastes up to n instances of `src` into `dst` at random places (same scale).
void copy_paste(DetectionSample& dst, const DetectionSample& src, int n, std::mt19937_64& rng) {
  if (src.boxes.empty()) return;
  const bool masks = !src.masks.empty() && src.masks.size() == dst.masks.size();
  std::uniform_int_distribution<std::size_t> pick(0, src.boxes.size() - 1);
  for (int k = 0; k < n; ++k) {
    const Detection2D& b = src.boxes[pick(rng)];
    const cv::Rect from(int(std::floor(b.x1)), int(std::floor(b.y1)), int(std::ceil(b.x2) - std::floor(b.x1)),
                        int(std::ceil(b.y2) - std::floor(b.y1)));
    const cv::Rect in_src = from & cv::Rect(0, 0, src.image.width, src.image.height);
    if (in_src.width < 2 || in_src.height < 2 || in_src.width >= dst.image.width || in_src.height >= dst.image.height)
      continue;
    const int x = std::uniform_int_distribution<int>(0, dst.image.width - in_src.width)(rng);
    const int y = std::uniform_int_distribution<int>(0, dst.image.height - in_src.height)(rng);
    const cv::Rect to(x, y, in_src.width, in_src.height);
    cv::Mat alpha = masks ? as_mat(src.masks[std::size_t(b.class_id)])(in_src) > 0
                          : cv::Mat(in_src.size(), CV_8UC1, cv::Scalar(255));
    as_mat(src.image)(in_src).copyTo(as_mat(dst.image)(to), alpha);
    if (masks)
      for (std::size_t c = 0; c < dst.masks.size(); ++c)
        as_mat(dst.masks[c])(to).setTo(cv::Scalar(int(c) == b.class_id ? 255 : 0), alpha);
    else
      dst.masks.clear();  // the pasted pixels would be unlabelled
    dst.boxes.push_back({float(x), float(y), float(x + in_src.width), float(y + in_src.height), b.class_id, 1.f});
  }
}

void colour_jitter(ColorImage& im, const DetectionAugmentConfig& cfg, std::mt19937_64& rng) {
  auto factor = [&](double a) { return std::uniform_real_distribution<double>(1 - a, 1 + a)(rng); };
  const double br = factor(cfg.brightness), co = factor(cfg.contrast), sa = factor(cfg.saturation);
  double mean = 0;
  for (const auto& p : im.data) mean += (p.r + p.g + p.b) / 3.0;
  mean /= double(std::max<std::size_t>(1, im.size()));
  for (auto& p : im.data) {
    const double grey = 0.299 * p.r + 0.587 * p.g + 0.114 * p.b;
    auto f = [&](std::uint8_t v) {
      double x = grey + (v - grey) * sa;  // saturation
      x = mean + (x - mean) * co;         // contrast
      return std::uint8_t(std::clamp(std::lround(x * br), 0L, 255L));
    };
    p = Rgb8{f(p.r), f(p.g), f(p.b)};
  }
}

}  // namespace

DetectionSample augment_detection(const DetectionSample& s, const std::vector<DetectionSample>& pool,
                                  const DetectionAugmentConfig& cfg, std::uint64_t draw) {
  std::mt19937_64 rng(draw);
  std::uniform_real_distribution<double> u(0, 1);
  const int W = s.image.width, H = s.image.height;
  DetectionSample out;
  if (!pool.empty() && u(rng) < cfg.mosaic) {
    std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
    out = mosaic(s, {&s, &pool[pick(rng)], &pool[pick(rng)], &pool[pick(rng)]}, cfg.min_visible);
  } else {
    out = s;
  }
  if (!pool.empty() && u(rng) < cfg.copy_paste) {
    const DetectionSample& src = pool[std::uniform_int_distribution<std::size_t>(0, pool.size() - 1)(rng)];
    copy_paste(out, src, std::uniform_int_distribution<int>(1, std::max(1, cfg.paste_max))(rng), rng);
  }
  // Zoom about a shifted centre: x' = z (x - cx) + W / 2.
  const double z =
      std::exp(std::uniform_real_distribution<double>(std::log(cfg.scale_min), std::log(cfg.scale_max))(rng));
  const double cx = W * (0.5 + cfg.shift * (2 * u(rng) - 1)), cy = H * (0.5 + cfg.shift * (2 * u(rng) - 1));
  const bool flip = u(rng) < cfg.flip;
  const double ax = flip ? -z : z;
  out = warp(out, ax, W / 2.0 - ax * cx, z, H / 2.0 - z * cy, W, H, cfg.min_visible);
  colour_jitter(out.image, cfg, rng);
  return out;
}

DetectorTrainingConfig detector_training_config(const ConfigMap& values, const std::string& where) {
  for (const auto& [key, value] : values)
    if (key.rfind("detector.", 0) != 0 && key.rfind("augment.", 0) != 0)
      throw Error(where, "unknown key '" + key + "' (keys are detector.* or augment.*)");
  DetectorTrainingConfig cfg;
  apply_config(cfg.detector, values, where, "detector.");
  apply_config(cfg.augment, values, where, "augment.");
  return cfg;
}

}  // namespace cropsight::nn
