// nn::CenterNet's encoding and decoding (center_codec.hpp, center_decode.hpp): OpenCV only for the
// letterbox resize.
#include "nn/center_codec.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "cropsight/core/error.hpp"
#include "cropsight/nn/center_decode.hpp"
#include "nn/mask_upsampling.hpp"

namespace cropsight::nn {

std::vector<float> center_blob(const ColorImage& image, int input_w, int input_h, Letterbox* lb_out) {
  const Letterbox lb = Letterbox::fit(image.width, image.height, input_w, input_h, OnnxResize::letterbox);
  if (lb_out) *lb_out = lb;
  const cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<Rgb8*>(image.data.data()));
  cv::Mat canvas(input_h, input_w, CV_8UC3, cv::Scalar::all(kCenterPad));
  cv::Mat roi = canvas(cv::Rect(lb.pad_x, lb.pad_y, lb.resized_w, lb.resized_h));
  if (lb.resized_w == image.width && lb.resized_h == image.height)
    rgb.copyTo(roi);
  else
    cv::resize(rgb, roi, roi.size(), 0, 0, cv::INTER_LINEAR);
  const std::size_t plane = std::size_t(input_w) * std::size_t(input_h);
  std::vector<float> blob(3 * plane);
  for (int y = 0; y < input_h; ++y) {
    const auto* row = canvas.ptr<std::uint8_t>(y);
    for (int x = 0; x < input_w; ++x)
      for (int c = 0; c < 3; ++c)
        blob[std::size_t(c) * plane + std::size_t(y) * std::size_t(input_w) + std::size_t(x)] =
            float(row[3 * x + c]) / 255.f;
  }
  return blob;
}

std::vector<float> mirrored_blob(const std::vector<float>& blob, int input_w, int input_h) {
  std::vector<float> out(blob.size());
  const std::size_t w = std::size_t(input_w), rows = blob.size() / w;
  if (rows * w != blob.size() || rows != 3 * std::size_t(input_h))
    throw Error("detector", "blob size differs from 3 x input size");
  for (std::size_t r = 0; r < rows; ++r)
    std::reverse_copy(blob.begin() + std::ptrdiff_t(r * w), blob.begin() + std::ptrdiff_t((r + 1) * w),
                      out.begin() + std::ptrdiff_t(r * w));
  return out;
}

namespace {
// a := (a + mirror(b)) / 2 for planes of `w` cells a row (b's rows reversed).
void average_mirrored(std::vector<float>& a, const std::vector<float>& b, int w) {
  const std::size_t n = std::size_t(w);
  for (std::size_t r = 0; r < a.size() / n; ++r) {
    float* ar = a.data() + r * n;
    const float* br = b.data() + r * n;
    for (std::size_t x = 0; x < n; ++x) ar[x] = 0.5f * (ar[x] + br[n - 1 - x]);
  }
}
}  // namespace

CenterNetHeads::MaskPass mask_pass(CenterNetHeads h, int input_w, int input_h) {
  CenterNetHeads::MaskPass p;
  p.input_w = input_w, p.input_h = input_h, p.out_w = h.out_w, p.out_h = h.out_h;
  p.mask = std::move(h.mask);
  return p;
}

void merge_mirrored_heads(CenterNetHeads& h, const CenterNetHeads& m) {
  if (h.classes != m.classes || h.out_w != m.out_w || h.out_h != m.out_h || h.heatmap.size() != m.heatmap.size() ||
      h.size.size() != m.size.size() || h.mask.size() != m.mask.size())
    throw Error("detector", "flip test: the mirrored heads differ in shape");
  average_mirrored(h.heatmap, m.heatmap, h.out_w);
  average_mirrored(h.size, m.size, h.out_w);  // (w, h) of a box does not change under a mirror
  average_mirrored(h.mask, m.mask, h.out_w);
}

float gaussian_radius(float h, float w, float mo) {
  const float b1 = h + w, c1 = w * h * (1 - mo) / (1 + mo);
  const float r1 = (b1 + std::sqrt(std::max(0.f, b1 * b1 - 4 * c1))) / 2;
  const float a2 = 4, b2 = 2 * (h + w), c2 = (1 - mo) * w * h;
  const float r2 = (b2 + std::sqrt(std::max(0.f, b2 * b2 - 4 * a2 * c2))) / 2;
  const float a3 = 4 * mo, b3 = -2 * mo * (h + w), c3 = (mo - 1) * w * h;
  const float r3 = (b3 + std::sqrt(std::max(0.f, b3 * b3 - 4 * a3 * c3))) / 2;
  return std::min({r1, r2, r3});
}

void draw_gaussian(float* hm, int ow, int oh, int cx, int cy, int radius) {
  const float sigma = float(2 * radius + 1) / 6.f;
  const float k = 1.f / (2 * sigma * sigma);
  for (int y = std::max(0, cy - radius); y <= std::min(oh - 1, cy + radius); ++y)
    for (int x = std::max(0, cx - radius); x <= std::min(ow - 1, cx + radius); ++x) {
      const float dx = float(x - cx), dy = float(y - cy);
      float& v = hm[std::size_t(y) * std::size_t(ow) + std::size_t(x)];
      v = std::max(v, std::exp(-(dx * dx + dy * dy) * k));
    }
}

CenterTargets encode_targets(const std::vector<Detection2D>& boxes, const std::vector<GrayImage>& masks, int classes,
                             int ow, int oh, int max_objects) {
  CenterTargets t;
  const std::size_t plane = std::size_t(ow) * std::size_t(oh);
  t.heatmap.assign(std::size_t(classes) * plane, 0.f);
  t.index.assign(std::size_t(max_objects), 0);
  t.size.assign(2 * std::size_t(max_objects), 0.f);
  t.offset.assign(2 * std::size_t(max_objects), 0.f);
  t.reg_mask.assign(std::size_t(max_objects), 0.f);
  int k = 0;
  for (const auto& b : boxes) {
    if (k >= max_objects) break;
    if (b.class_id < 0 || b.class_id >= classes) continue;
    const float s = float(kCenterStride);
    const float w = b.width() / s, h = b.height() / s;
    const float cx = b.centre_x() / s, cy = b.centre_y() / s;
    if (b.width() < 1 || b.height() < 1 || cx < 0 || cy < 0 || cx >= float(ow) || cy >= float(oh)) continue;
    const int ix = int(cx), iy = int(cy);
    const int radius = std::max(0, int(gaussian_radius(std::ceil(h), std::ceil(w))));
    draw_gaussian(t.heatmap.data() + std::size_t(b.class_id) * plane, ow, oh, ix, iy, radius);
    t.index[std::size_t(k)] = std::int64_t(iy) * ow + ix;
    t.size[2 * std::size_t(k)] = w, t.size[2 * std::size_t(k) + 1] = h;
    t.offset[2 * std::size_t(k)] = cx - float(ix), t.offset[2 * std::size_t(k) + 1] = cy - float(iy);
    t.reg_mask[std::size_t(k)] = 1.f;
    ++k;
  }
  if (!masks.empty()) {
    t.mask.assign(std::size_t(classes) * plane, 0.f);
    for (int c = 0; c < classes && c < int(masks.size()); ++c)
      for (std::size_t i = 0; i < plane && i < masks[std::size_t(c)].data.size(); ++i)
        t.mask[std::size_t(c) * plane + i] = masks[std::size_t(c)].data[i] ? 1.f : 0.f;
  }
  return t;
}

std::vector<Detection2D> decode_heads(const CenterNetHeads& h, const Letterbox& lb, float threshold, int top_k) {
  struct Peak {
    float score;
    int c, y, x;
  };
  std::vector<Peak> peaks;
  const int W = h.out_w, H = h.out_h;
  const std::size_t plane = std::size_t(W) * std::size_t(H);
  for (int c = 0; c < h.classes; ++c) {
    const float* hm = h.heatmap.data() + std::size_t(c) * plane;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const float v = hm[std::size_t(y) * std::size_t(W) + std::size_t(x)];
        if (v < threshold) continue;
        bool peak = true;
        for (int yy = std::max(0, y - 1); yy <= std::min(H - 1, y + 1) && peak; ++yy)
          for (int xx = std::max(0, x - 1); xx <= std::min(W - 1, x + 1); ++xx)
            if (hm[std::size_t(yy) * std::size_t(W) + std::size_t(xx)] > v) {
              peak = false;
              break;
            }
        if (peak) peaks.push_back({v, c, y, x});
      }
  }
  std::stable_sort(peaks.begin(), peaks.end(), [](const Peak& a, const Peak& b) { return a.score > b.score; });
  if (int(peaks.size()) > top_k) peaks.resize(std::size_t(top_k));
  std::vector<Detection2D> out;
  const float s = float(kCenterStride);
  for (const auto& p : peaks) {
    const std::size_t i = std::size_t(p.y) * std::size_t(W) + std::size_t(p.x);
    const float cx = float(p.x) + h.offset[i], cy = float(p.y) + h.offset[plane + i];
    const float hw = 0.5f * h.size[i], hh = 0.5f * h.size[plane + i];
    Detection2D d = lb.to_image((cx - hw) * s, (cy - hh) * s, (cx + hw) * s, (cy + hh) * s);
    if (d.area() <= 0) continue;
    d.class_id = p.c, d.score = p.score;
    out.push_back(d);
  }
  return out;
}

std::vector<Detection2D> boxes_from_heads(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w,
                                          int image_h) {
  const Letterbox lb = Letterbox::fit(image_w, image_h, cfg.input_width, cfg.input_height, OnnxResize::letterbox);
  return decode_heads(heads, lb, float(cfg.score_threshold), cfg.top_k);
}

// A named namespace: src/nn compiles as unity batches, where anonymous helpers could collide.
namespace mask_region {

// The threshold of each class: `threshold` for all, or (negative) the model's per-class ones.
std::vector<float> class_thresholds(const CenterNetHeads& heads, const CenterNetConfig& cfg, float threshold) {
  std::vector<float> t = threshold < 0 ? cfg.mask_threshold_values()
                                       : std::vector<float>(std::size_t(std::max(heads.classes, 0)), threshold);
  t.resize(std::size_t(std::max(heads.classes, 0)), 0.5f);
  return t;
}

// The pixels a box touches, as half-open integer bounds clipped to the image.
struct PixelRect {
  int u0, v0, u1, v1;
};

std::vector<PixelRect> class_rects(const std::vector<Detection2D>& boxes, int c, int image_w, int image_h) {
  std::vector<PixelRect> out;
  for (const auto& b : boxes) {
    if (b.class_id != c) continue;
    const PixelRect r{std::clamp(int(std::floor(b.x1)), 0, image_w), std::clamp(int(std::floor(b.y1)), 0, image_h),
                      std::clamp(int(std::ceil(b.x2)), 0, image_w), std::clamp(int(std::ceil(b.y2)), 0, image_h)};
    if (r.u0 < r.u1 && r.v0 < r.v1) out.push_back(r);
  }
  return out;
}

// The column spans of row v covered by `rects`, overlapping and touching ones merged, left to right.
void row_spans(const std::vector<PixelRect>& rects, int v, std::vector<std::pair<int, int>>& spans) {
  spans.clear();
  for (const auto& r : rects)
    if (r.v0 <= v && v < r.v1) spans.emplace_back(r.u0, r.u1);
  std::sort(spans.begin(), spans.end());
  std::size_t n = 0;
  for (const auto& s : spans) {
    if (n > 0 && s.first <= spans[n - 1].second)
      spans[n - 1].second = std::max(spans[n - 1].second, s.second);
    else
      spans[n++] = s;
  }
  spans.resize(n);
}

}  // namespace mask_region

using mask_region::class_rects;
using mask_region::class_thresholds;
using mask_region::PixelRect;
using mask_region::row_spans;

std::vector<GrayImage> masks_from_heads(const CenterNetHeads& heads, const CenterNetConfig& cfg, int image_w,
                                        int image_h, float threshold) {
  MaskScores scores(heads, cfg, image_w, image_h);
  const std::vector<float> per_class = class_thresholds(heads, cfg, threshold);
  std::vector<GrayImage> out;
  for (int c = 0; c < heads.classes; ++c) {
    const float t = per_class[std::size_t(c)];
    GrayImage m(image_w, image_h, 0);
    for (int v = 0; v < image_h; ++v) {
      auto* row = m.row(v);
      const float* score = scores.row(c, v);
      for (int u = 0; u < image_w; ++u) row[u] = score[u] >= t ? 255 : 0;
    }
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<GrayImage> masks_in_boxes(const CenterNetHeads& heads, const CenterNetConfig& cfg,
                                      const std::vector<Detection2D>& boxes, int image_w, int image_h,
                                      float threshold) {
  MaskScores scores(heads, cfg, image_w, image_h);
  const std::vector<float> per_class = class_thresholds(heads, cfg, threshold);
  std::vector<GrayImage> out;
  std::vector<std::pair<int, int>> spans;
  for (int c = 0; c < heads.classes; ++c) {
    const float t = per_class[std::size_t(c)];
    const std::vector<PixelRect> rects = class_rects(boxes, c, image_w, image_h);
    GrayImage m(image_w, image_h, 0);
    for (int v = 0; v < image_h; ++v) {
      row_spans(rects, v, spans);
      auto* row = m.row(v);
      for (const auto& [u0, u1] : spans) {
        const float* score = scores.span(c, v, u0, u1);
        for (int u = u0; u < u1; ++u) row[u] = score[u] >= t ? 255 : 0;
      }
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace cropsight::nn
