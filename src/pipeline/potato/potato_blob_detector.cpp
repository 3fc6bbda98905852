// The classical potato detector (see the header for the method and its defaults).
#include "cropsight/pipeline/potato/potato_blob_detector.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "cropsight/core/error.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::potato {

void PotatoBlobConfig::validate(const std::string& where) const {
  check_config(*this, where);
  if (cov_aa * cov_bb - cov_ab * cov_ab <= 0)
    throw Error(where, "the colour covariance (cov_aa, cov_ab, cov_bb) must be positive definite");
  if (min_lightness > max_lightness) throw Error(where, "'min_lightness' must not exceed 'max_lightness'");
  if (depth_min_m >= depth_max_m) throw Error(where, "'depth_min_m' must be less than 'depth_max_m'");
}

struct PotatoBlobDetector::Impl {
  PotatoBlobConfig cfg;
  // Colour likelihood per (a*, b*), 0 outside the threshold: one lookup per pixel instead of a
  // quadratic form and an exp.
  std::vector<std::uint8_t> lut = std::vector<std::uint8_t>(256 * 256);
  std::array<std::uint8_t, 256> l_ok{};
  cv::Mat lab, like, mask, labels, stats, centroids;
  GrayImage last_mask;
};

PotatoBlobDetector::PotatoBlobDetector(const PotatoBlobConfig& cfg) : impl_(std::make_unique<Impl>()) {
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
  for (int l = 0; l < 256; ++l) impl_->l_ok[std::size_t(l)] = l >= cfg.min_lightness && l <= cfg.max_lightness;
}

PotatoBlobDetector::~PotatoBlobDetector() = default;

const GrayImage& PotatoBlobDetector::last_mask() const { return impl_->last_mask; }

namespace {
cv::Mat disc(double fraction, int short_side) {
  const int k = int(std::lround(fraction * short_side));
  return k >= 2 ? cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)) : cv::Mat();
}

// Potatoes that touch or overlap in the image form one blob with a neck between two convex
// parts. The cores of the blob (pixels farther from its boundary than `core_fraction` of the
// deepest one) fall apart at such a neck; each core then takes the blob pixels nearest to it.
// One core = one potato: `parts` is left untouched and 1 is returned. Scale-free: only the ratio
// of distances counts.
int split_touching(const cv::Mat& blob, double core_fraction, cv::Mat& parts) {
  if (core_fraction <= 0) return 1;
  cv::Mat padded, dist, cores, core_labels;
  cv::copyMakeBorder(blob, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
  cv::distanceTransform(padded, dist, cv::DIST_L2, cv::DIST_MASK_5);
  double max_d = 0;
  cv::minMaxLoc(dist, nullptr, &max_d);
  if (max_d <= 1) return 1;
  cv::compare(dist, core_fraction * max_d, cores, cv::CMP_GE);
  const int n = cv::connectedComponents(cores, core_labels, 8, CV_32S) - 1;
  if (n < 2) return 1;
  // Each pixel of the blob goes to its nearest core (distance transform with labels of the
  // nearest zero pixel; the cores are the only zeros).
  cv::Mat not_cores = ~cores, nearest_dist, nearest;
  cv::distanceTransform(not_cores, nearest_dist, nearest, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_CCOMP);
  parts = nearest(cv::Rect(1, 1, blob.cols, blob.rows)).clone();
  parts.setTo(0, blob == 0);
  double num = 0;  // labels are numbered by the transform's own pass over the cores
  cv::minMaxLoc(nearest, nullptr, &num);
  return int(num);
}

// The box and score of one part (mask in its ROI at `tl`), or nothing when it fails the shape rules.
std::optional<Detection2D> blob_detection(const cv::Mat& part, cv::Point tl, int area, double colour,
                                          const PotatoBlobConfig& cfg) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(part, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  if (contours.empty()) return std::nullopt;
  std::vector<cv::Point> pts;
  for (const auto& c : contours) pts.insert(pts.end(), c.begin(), c.end());
  std::vector<cv::Point> hull;
  cv::convexHull(pts, hull);
  const double solidity = std::min(1.0, area / std::max(1.0, cv::contourArea(hull)));
  const cv::RotatedRect rr = cv::minAreaRect(pts);
  const double lo = std::max(1.0f, std::min(rr.size.width, rr.size.height)),
               hi = std::max(rr.size.width, rr.size.height);
  if (solidity < cfg.min_solidity || hi / lo > cfg.max_aspect) return std::nullopt;
  const cv::Rect b = cv::boundingRect(pts);
  Detection2D d;
  d.x1 = float(tl.x + b.x);
  d.y1 = float(tl.y + b.y);
  d.x2 = float(tl.x + b.x + b.width);
  d.y2 = float(tl.y + b.y + b.height);
  d.class_id = 0;
  d.score = float(colour * solidity);
  if (d.score < cfg.min_score) return std::nullopt;
  return d;
}
}  // namespace

std::vector<Detection2D> PotatoBlobDetector::detect(const DetectorInput& in) {
  if (!in.image || in.image->empty()) throw Error("potato detector", "empty image");
  Impl& m = *impl_;
  const PotatoBlobConfig& cfg = m.cfg;
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
      std::uint8_t value = m.l_ok[p[u][0]] ? m.lut[std::size_t(p[u][1]) * 256 + p[u][2]] : 0;
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
  if (const cv::Mat k = disc(cfg.opening_fraction, short_side); !k.empty())
    cv::morphologyEx(m.mask, m.mask, cv::MORPH_OPEN, k);
  if (const cv::Mat k = disc(cfg.closing_fraction, short_side); !k.empty())
    cv::morphologyEx(m.mask, m.mask, cv::MORPH_CLOSE, k);

  const int n = cv::connectedComponentsWithStats(m.mask, m.labels, m.stats, m.centroids, 8, CV_32S);
  const double min_area = cfg.min_area_fraction * double(w) * double(h);
  std::vector<Detection2D> out;
  cv::Mat blob, parts, part;
  for (int i = 1; i < n; ++i) {
    const int* s = m.stats.ptr<int>(i);
    if (s[cv::CC_STAT_AREA] < min_area) continue;
    const cv::Rect r(s[cv::CC_STAT_LEFT], s[cv::CC_STAT_TOP], s[cv::CC_STAT_WIDTH], s[cv::CC_STAT_HEIGHT]);
    cv::compare(m.labels(r), i, blob, cv::CMP_EQ);
    const int num_parts = split_touching(blob, cfg.split_core_fraction, parts);
    for (int k = 1; k <= num_parts; ++k) {
      if (num_parts == 1)
        part = blob;
      else
        cv::compare(parts, k, part, cv::CMP_EQ);
      const int area = cv::countNonZero(part);
      if (area < min_area) continue;
      const double colour = cv::sum(m.like(r) & part)[0] / (255.0 * area);  // like is 0 outside the colour test
      if (auto d = blob_detection(part, r.tl(), area, colour, cfg)) out.push_back(*d);
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Detection2D& a, const Detection2D& b) { return a.score > b.score; });
  m.last_mask.width = w;
  m.last_mask.height = h;
  m.last_mask.data.assign(m.mask.datastart, m.mask.dataend);
  return out;
}

}  // namespace cropsight::pipeline::potato
