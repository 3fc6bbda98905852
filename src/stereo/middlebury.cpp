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

BadPixelStats bad_pixels(const DisparityImage& est, const DisparityImage& truth, const std::string& where) {
  if (est.width != truth.width || est.height != truth.height)
    throw Error(where, "estimate and ground truth differ in size");
  long n = 0, b1 = 0, b2 = 0, inv = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const float t = truth.data[i];
    if (std::isnan(t)) continue;
    ++n;
    const float e = est.data[i];
    if (std::isnan(e)) {
      ++inv, ++b1, ++b2;
      continue;
    }
    const float err = std::fabs(e - t);
    b1 += err > 1.0f;
    b2 += err > 2.0f;
  }
  if (n == 0) throw Error(where, "ground truth has no valid pixel; nothing to score");
  BadPixelStats s;
  s.pixels = n;
  if (n > 0) {
    s.bad1 = 100.0 * double(b1) / double(n);
    s.bad2 = 100.0 * double(b2) / double(n);
    s.invalid = 100.0 * double(inv) / double(n);
  }
  return s;
}

MiddleburyEvaluation evaluate_middlebury(const std::vector<MiddleburyPair>& pairs, const MiddleburyMatcher& match) {
  MiddleburyEvaluation e;
  double s1 = 0, s2 = 0;
  for (const auto& p : pairs) {
    const int nd = ((p.max_disparity + 1 + 15) / 16) * 16;
    StageTimer t;
    DisparityImage d;
    {
      auto scope = t.scope("match");
      d = match(p, nd);
    }
    const BadPixelStats st = bad_pixels(d, p.truth, p.name);
    e.pairs.push_back({p.name, st, t.total_ms(), nd});
    s1 += st.bad1;
    s2 += st.bad2;
  }
  e.mean_bad1 = s1 / double(pairs.size());
  e.mean_bad2 = s2 / double(pairs.size());
  return e;
}

}  // namespace cropsight::stereo
