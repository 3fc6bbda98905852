// The classical potato detector (see the header for the method and its defaults).
#include "cropsight/pipeline/potato/blob_detector.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "concavity_split.hpp"
#include "cropsight/core/error.hpp"
#include "depth_completion.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::potato {

void BlobConfig::validate(const std::string& where) const {
  check_config(*this, where);
  if (cov_aa * cov_bb - cov_ab * cov_ab <= 0)
    throw Error(where, "the colour covariance (cov_aa, cov_ab, cov_bb) must be positive definite");
  if (min_lightness > max_lightness) throw Error(where, "'min_lightness' must not exceed 'max_lightness'");
  if (depth_min_m >= depth_max_m) throw Error(where, "'depth_min_m' must be less than 'depth_max_m'");
}

struct BlobDetector::Impl {
  BlobConfig cfg;
  // Colour likelihood per (a*, b*), 0 outside the threshold: one lookup per pixel instead of a
  // quadratic form and an exp.
  std::vector<std::uint8_t> lut = std::vector<std::uint8_t>(256 * 256);
  std::array<std::uint8_t, 256> l_ok{};
  // Saturation test in whole 8-bit units: chroma per (a*, b*) against min_saturation x L per lightness.
  std::vector<std::uint8_t> chroma = std::vector<std::uint8_t>(256 * 256);
  std::array<std::uint8_t, 256> min_chroma{};
  cv::Mat lab, like, mask, labels, stats, centroids;
  GrayImage last_mask;
};

BlobDetector::BlobDetector(const BlobConfig& cfg) : impl_(std::make_unique<Impl>()) {
  cfg.validate("potato detector");
  impl_->cfg = cfg;
  const double det = cfg.cov_aa * cfg.cov_bb - cfg.cov_ab * cfg.cov_ab;
  const double iaa = cfg.cov_bb / det, iab = -cfg.cov_ab / det, ibb = cfg.cov_aa / det;
  const double t2 = cfg.max_colour_distance * cfg.max_colour_distance;
  for (int a = 0; a < 256; ++a)
    for (int b = 0; b < 256; ++b) {
      const double da = a - cfg.mean_a, db = b - cfg.mean_b;
      const double d2 = da * da * iaa + 2 * da * db * iab + db * db * ibb;
      // At least 1 inside the threshold so that "foreground" is simply lut > 0.
      impl_->lut[std::size_t(a) * 256 + std::size_t(b)] =
          d2 < t2 ? std::uint8_t(std::max(1.0, std::round(255.0 * std::exp(-0.5 * d2)))) : 0;
    }
  for (int l = 0; l < 256; ++l) {
    impl_->l_ok[std::size_t(l)] = l >= cfg.min_lightness && l <= cfg.max_lightness;
    impl_->min_chroma[std::size_t(l)] = std::uint8_t(std::min(255.0, std::round(cfg.min_saturation * l)));
  }
  for (int a = 0; a < 256; ++a)
    for (int b = 0; b < 256; ++b)
      impl_->chroma[std::size_t(a) * 256 + std::size_t(b)] =
          std::uint8_t(std::min(255.0, std::round(std::hypot(a - 128.0, b - 128.0))));
}

BlobDetector::~BlobDetector() = default;

const GrayImage& BlobDetector::last_mask() const { return impl_->last_mask; }

namespace {
cv::Mat disc(double fraction, int short_side) {
  const int k = int(std::lround(fraction * short_side));
  return k >= 2 ? cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)) : cv::Mat();
}

double aspect(const std::vector<cv::Point>& pts) {
  const cv::RotatedRect rr = cv::minAreaRect(pts);
  const double lo = std::max(1.0f, std::min(rr.size.width, rr.size.height)),
               hi = std::max(rr.size.width, rr.size.height);
  return hi / lo;
}

std::vector<cv::Point> outline_points(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  std::vector<cv::Point> pts;
  for (const auto& c : contours) pts.insert(pts.end(), c.begin(), c.end());
  return pts;
}

// Logistic weight of how much the part stands out from the background (not foreground) pixels in a
// ring of `ring` px around it, darker or lighter: 0.5 when level with it, towards 1 with contrast;
// 1 when the ring holds no background. Either sign, so that the same preset serves a potato in
// front of a white sheet and one in a dark root chamber.
double contrast_factor(const cv::Mat& part, cv::Rect r, const cv::Mat& lab, const cv::Mat& foreground, int ring,
                       double scale) {
  if (scale <= 0 || ring < 1) return 1.0;
  const cv::Rect wide =
      cv::Rect(r.x - ring, r.y - ring, r.width + 2 * ring, r.height + 2 * ring) & cv::Rect(0, 0, lab.cols, lab.rows);
  cv::Mat grown = cv::Mat::zeros(wide.size(), CV_8UC1);
  part.copyTo(grown(r - wide.tl()));
  // A square ring: separable, so its cost does not grow with the ring width.
  cv::dilate(grown, grown, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * ring + 1, 2 * ring + 1)));
  grown.setTo(0, foreground(wide));
  if (cv::countNonZero(grown) == 0) return 1.0;
  const double l_ring = cv::mean(lab(wide), grown)[0], l_part = cv::mean(lab(r), part)[0];
  return 1.0 / (1.0 + std::exp(-std::abs(l_ring - l_part) / scale));
}

// The box of one part (mask in its ROI at `tl`), or nothing when it fails the convexity rule.
std::optional<Detection2D> part_detection(const cv::Mat& part, cv::Point tl, int area, double score_without_shape,
                                          const BlobConfig& cfg) {
  const std::vector<cv::Point> pts = outline_points(part);
  if (pts.empty()) return std::nullopt;
  std::vector<cv::Point> hull;
  cv::convexHull(pts, hull);
  const double solidity = std::min(1.0, area / std::max(1.0, cv::contourArea(hull)));
  if (solidity < cfg.min_solidity) return std::nullopt;
  const cv::Rect b = cv::boundingRect(pts);
  Detection2D d;
  d.x1 = float(tl.x + b.x);
  d.y1 = float(tl.y + b.y);
  d.x2 = float(tl.x + b.x + b.width);
  d.y2 = float(tl.y + b.y + b.height);
  d.class_id = 0;
  d.score = float(score_without_shape * solidity);
  if (d.score < cfg.min_score) return std::nullopt;
  return d;
}
}  // namespace

// Long on purpose: the detector's steps in order: the colour mask and its opening, the blobs, their shape rules, one
// box each.
std::vector<Detection2D> BlobDetector::detect(const DetectorInput& in) {
  if (!in.image || in.image->empty()) throw Error("potato detector", "empty image");
  Impl& m = *impl_;
  const BlobConfig& cfg = m.cfg;
  const ColorImage& img = *in.image;
  const int w = img.width, h = img.height;
  const Image<float>* depth = in.depth_m && !in.depth_m->empty() ? in.depth_m : nullptr;
  if (depth && (depth->width != w || depth->height != h))
    throw Error("potato detector", "depth is " + std::to_string(depth->width) + "x" + std::to_string(depth->height) +
                                       ", the image " + std::to_string(w) + "x" + std::to_string(h));

  cv::cvtColor(stereo::detail::view(img), m.lab, cv::COLOR_RGB2Lab);
  m.like.create(h, w, CV_8UC1);
  m.mask.create(h, w, CV_8UC1);
  for (int v = 0; v < h; ++v) {
    const cv::Vec3b* p = m.lab.ptr<cv::Vec3b>(v);
    std::uint8_t* lk = m.like.ptr<std::uint8_t>(v);
    std::uint8_t* mk = m.mask.ptr<std::uint8_t>(v);
    const float* z = depth ? depth->row(v) : nullptr;
    for (int u = 0; u < w; ++u) {
      const std::size_t ab = std::size_t(p[u][1]) * 256 + p[u][2];
      std::uint8_t value = m.l_ok[p[u][0]] && m.chroma[ab] >= m.min_chroma[p[u][0]] ? m.lut[ab] : 0;
      if (z && value) {
        const float d = z[u];
        const bool in_range = d >= cfg.depth_min_m && d <= cfg.depth_max_m;
        if (!(in_range || (d <= 0 && cfg.keep_depth_holes))) value = 0;
      }
      lk[u] = value;
      mk[u] = value ? 255 : 0;
    }
  }
  // Opening first: strings and roots are a few pixels wide and vanish; potatoes keep their shape.
  const int short_side = std::min(w, h);
  const cv::Mat opening = disc(cfg.opening_fraction, short_side);
  if (!opening.empty()) cv::morphologyEx(m.mask, m.mask, cv::MORPH_OPEN, opening);
  if (const cv::Mat k = disc(cfg.closing_fraction, short_side); !k.empty())
    cv::morphologyEx(m.mask, m.mask, cv::MORPH_CLOSE, k);

  const int n = cv::connectedComponentsWithStats(m.mask, m.labels, m.stats, m.centroids, 8, CV_32S);
  const double min_area = cfg.min_area_fraction * double(w) * double(h);
  const int ring = int(std::lround(cfg.contrast_ring_fraction * short_side));
  const detail::SplitRule split_rule{cfg.split_concavity_depth, cfg.split_min_part_fraction,
                                     cfg.split_min_part_solidity, cfg.split_max_depth};
  detail::DepthCompletionRule completion;
  completion.grow = cfg.depth_completion;
  completion.band_m = cfg.depth_completion_band_m;
  completion.step_m = cfg.depth_completion_step_m;
  std::vector<Detection2D> out;
  cv::Mat blob;
  std::vector<cv::Mat> parts;
  for (int i = 1; i < n; ++i) {
    const int* s = m.stats.ptr<int>(i);
    if (s[cv::CC_STAT_AREA] < min_area) continue;
    const cv::Rect r(s[cv::CC_STAT_LEFT], s[cv::CC_STAT_TOP], s[cv::CC_STAT_WIDTH], s[cv::CC_STAT_HEIGHT]);
    cv::compare(m.labels(r), i, blob, cv::CMP_EQ);
    // The aspect rule is the whole blob's: a bundle of roots is long and thin as one piece, while
    // a part of a split may be a thin visible sliver of a potato behind another.
    if (aspect(outline_points(blob)) > cfg.max_aspect) continue;
    parts.clear();
    if (detail::split_at_concavities(blob, split_rule, parts) < 2) parts.assign(1, blob);
    for (const cv::Mat& part : parts) {
      const int area = cv::countNonZero(part);
      if (area < min_area) continue;
      const double colour = cv::sum(m.like(r) & part)[0] / (255.0 * area);  // like is 0 outside the colour test
      const double contrast = contrast_factor(part, r, m.lab, m.mask, ring, cfg.contrast_scale);
      if (auto d = part_detection(part, r.tl(), area, colour * contrast, cfg)) {
        if (depth) *d = detail::complete_by_depth(*d, part, r.x, r.y, *depth, m.labels, i, opening, completion);
        out.push_back(*d);
      }
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Detection2D& a, const Detection2D& b) { return a.score > b.score; });
  // Two parts of one potato (a root's shadow across it) complete to the same box: keep the better.
  if (depth && completion.grow > 0) {
    std::vector<Detection2D> kept;
    for (const Detection2D& d : out)
      if (std::none_of(kept.begin(), kept.end(),
                       [&](const Detection2D& k) { return iou(k, d) > cfg.depth_completion_same_iou; }))
        kept.push_back(d);
    out.swap(kept);
  }
  m.last_mask.width = w;
  m.last_mask.height = h;
  m.last_mask.data.assign(m.mask.datastart, m.mask.dataend);
  return out;
}

}  // namespace cropsight::pipeline::potato
