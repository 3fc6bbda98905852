#include "cropsight/stereo/middlebury.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "cropsight/core/error.hpp"
#include "cropsight/core/timer.hpp"
#include "cropsight/stereo/stereo_io.hpp"

namespace cropsight::stereo {

namespace fs = std::filesystem;

std::vector<MiddleburyPair> load_middlebury(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "Middlebury directory not found");
  struct Spec {
    const char* name;
    const char* gt;
    double scale;
    int max_disp;
  };
  // GT scales and ranges from ../shared/data/README.md.
  const Spec specs[] = {{"tsukuba", "disp_left.pgm", 16, 15},
                        {"venus", "disp_left.pgm", 8, 19},
                        {"teddy", "disp_left.png", 4, 59},
                        {"cones", "disp_left.png", 4, 59}};
  std::vector<MiddleburyPair> out;
  for (const Spec& s : specs) {
    MiddleburyPair p;
    p.name = s.name;
    std::tie(p.left, p.right) = read_color_pair(dir / s.name / "left.png", dir / s.name / "right.png");
    const fs::path gt = dir / s.name / s.gt;
    // The published ground truths are 8-bit (disparity x scale); a 16-bit file read with these
    // scales would be off by 256x and score every pixel bad.
    p.truth = read_disparity(gt, s.scale, 8);
    p.max_disparity = s.max_disp;
    if (p.left.width != p.truth.width || p.left.height != p.truth.height)
      throw Error(gt.string(), "ground truth size differs from the images");
    // All zero (= unknown) leaves nothing to score: bad_pixels() would report 0 % bad.
    if (std::none_of(p.truth.data.begin(), p.truth.data.end(), [](float v) { return std::isfinite(v); }))
      throw Error(gt.string(), "ground truth has no valid pixel (all zero); nothing to score");
    out.push_back(std::move(p));
  }
  return out;
}

BadPixelStats bad_pixels(const DisparityImage& est, const DisparityImage& truth, const std::string& where,
                         const GrayImage& mask) {
  if (est.width != truth.width || est.height != truth.height)
    throw Error(where, "estimate and ground truth differ in size");
  if (!mask.empty() && (mask.width != truth.width || mask.height != truth.height))
    throw Error(where, "mask and ground truth differ in size");
  long n = 0, b1 = 0, b2 = 0, inv = 0;
  double err_sum = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const float t = truth.data[i];
    if (std::isnan(t) || (!mask.empty() && mask.data[i] == 0)) continue;
    ++n;
    const float e = est.data[i];
    if (std::isnan(e)) {
      ++inv, ++b1, ++b2;
      continue;
    }
    const float err = std::fabs(e - t);
    err_sum += err;
    b1 += err > 1.0f;
    b2 += err > 2.0f;
  }
  if (n == 0) throw Error(where, "ground truth has no valid pixel; nothing to score");
  BadPixelStats s;
  s.pixels = n;
  s.bad1 = 100.0 * double(b1) / double(n);
  s.bad2 = 100.0 * double(b2) / double(n);
  s.invalid = 100.0 * double(inv) / double(n);
  s.avg_error = n > inv ? err_sum / double(n - inv) : 0.0;
  return s;
}

GrayImage nonoccluded_mask(const DisparityImage& lt, const DisparityImage& rt, double tolerance,
                           const std::string& where) {
  if (lt.width != rt.width || lt.height != rt.height) throw Error(where, "left and right ground truths differ in size");
  GrayImage m(lt.width, lt.height, 0);
  for (int y = 0; y < lt.height; ++y)
    for (int x = 0; x < lt.width; ++x) {
      const float d = lt.at(x, y);
      if (std::isnan(d)) continue;
      const int xr = int(std::lround(double(x) - d));
      if (xr < 0 || xr >= rt.width) continue;  // the partner lies outside the right image
      const float dr = rt.at(xr, y);
      if (!std::isnan(dr) && std::fabs(double(dr) - d) <= tolerance) m.at(x, y) = 255;
    }
  return m;
}

MiddleburyEvaluation evaluate_middlebury(const std::vector<MiddleburyPair>& pairs, const MiddleburyMatcher& match) {
  MiddleburyEvaluation e;
  BadPixelStats sum, sum_nonocc;
  for (const auto& p : pairs) {
    const int nd = p.num_disparities > 0 ? p.num_disparities : ((p.max_disparity + 1 + 15) / 16) * 16;
    StageTimer t;
    DisparityImage d;
    {
      auto scope = t.scope("match");
      d = match(p, nd);
    }
    MiddleburyPairResult r{p.name, bad_pixels(d, p.truth, p.name), false, {}, t.total_ms(), nd};
    if (!p.nonoccluded.empty()) {
      r.has_nonoccluded = true;
      r.nonoccluded = bad_pixels(d, p.truth, p.name + " (non-occluded)", p.nonoccluded);
      sum_nonocc.bad1 += r.nonoccluded.bad1, sum_nonocc.bad2 += r.nonoccluded.bad2;
      sum_nonocc.invalid += r.nonoccluded.invalid, sum_nonocc.avg_error += r.nonoccluded.avg_error;
      sum_nonocc.pixels += r.nonoccluded.pixels;
      ++e.nonoccluded_pairs;
    }
    sum.bad1 += r.stats.bad1, sum.bad2 += r.stats.bad2, sum.invalid += r.stats.invalid;
    sum.avg_error += r.stats.avg_error;
    e.pairs.push_back(std::move(r));
  }
  const double n = pairs.empty() ? 1.0 : double(pairs.size());
  e.mean_bad1 = sum.bad1 / n, e.mean_bad2 = sum.bad2 / n;
  e.mean_invalid = sum.invalid / n, e.mean_avg_error = sum.avg_error / n;
  if (e.nonoccluded_pairs > 0) {
    const double k = double(e.nonoccluded_pairs);
    e.mean_nonoccluded = {sum_nonocc.bad1 / k, sum_nonocc.bad2 / k, sum_nonocc.invalid / k, sum_nonocc.avg_error / k,
                          sum_nonocc.pixels};
  }
  return e;
}

}  // namespace cropsight::stereo
