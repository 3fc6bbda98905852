#include "cropsight/stereo/seedling_detector.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <random>

#include "cropsight/core/config.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/stereo/reconstruct.hpp"
#include "cv_convert.hpp"

namespace cropsight::stereo {
namespace {

struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double d = 0;
};

// Least-squares plane of `pts` (normal = smallest principal axis).
Plane fit_plane(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : pts) c += p;
  c /= double(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - c) * (p - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  Plane pl;
  pl.n = es.eigenvectors().col(0).normalized();
  pl.d = -pl.n.dot(c);
  return pl;
}

// RANSAC soil plane on a random subset; the normal is oriented towards the camera (origin on the
// positive side), so heights above the soil are positive.
Plane soil_plane(const std::vector<Eigen::Vector3f>& pts, const SeedlingConfig& cfg, const std::string& where) {
  if (pts.size() < 3) throw Error(where, "too few reconstructed points to fit the soil plane");
  std::mt19937 rng(12345);
  std::vector<Eigen::Vector3d> sub;
  const int m = std::min<int>(cfg.ransac_sample, int(pts.size()));
  for (int i = 0; i < m; ++i)
    sub.push_back(pts[std::uniform_int_distribution<std::size_t>(0, pts.size() - 1)(rng)].cast<double>());
  Plane best;
  int best_in = -1;
  for (int it = 0; it < cfg.ransac_iterations; ++it) {
    std::uniform_int_distribution<int> pick(0, m - 1);
    const Eigen::Vector3d a = sub[pick(rng)], b = sub[pick(rng)], c = sub[pick(rng)];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-9) continue;
    n.normalize();
    const double d = -n.dot(a);
    int in = 0;
    for (const auto& p : sub) in += std::fabs(n.dot(p) + d) < cfg.ransac_threshold;
    if (in > best_in) best_in = in, best = {n, d};
  }
  std::vector<Eigen::Vector3d> inl;
  for (const auto& p : sub)
    if (std::fabs(best.n.dot(p) + best.d) < cfg.ransac_threshold) inl.push_back(p);
  Plane pl = inl.size() >= 3 ? fit_plane(inl) : best;
  if (pl.d < 0) pl.n = -pl.n, pl.d = -pl.d;
  return pl;
}

}  // namespace

void validate_seedling_config(const SeedlingConfig& c, const std::string& where) {
  auto fail = [&](const std::string& key, const std::string& problem) {
    throw Error(where, "'" + key + "' " + problem);
  };
  auto num = [](double v) { return cropsight::detail::format_value(v); };
  // Real numbers: finite and inside [lo, hi] (NaN fails every comparison).
  auto real = [&](const char* key, double v, double lo, double hi) {
    if (!(v >= lo && v <= hi)) fail(key, "must be in [" + num(lo) + ", " + num(hi) + "], got " + num(v));
  };
  auto integer = [&](const char* key, long v, long lo, long hi) {
    if (v < lo || v > hi)
      fail(key, "must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + std::to_string(v));
  };
  validate_disparity_config(c.disparity, where, "disparity.");
  real("min_depth", c.min_depth, 1e-3, 1e3);
  real("max_depth", c.max_depth, 1e-3, 1e3);
  if (!(c.max_depth > c.min_depth))
    fail("max_depth", "(" + num(c.max_depth) + ") must be greater than min_depth (" + num(c.min_depth) + ")");
  integer("ransac_iterations", c.ransac_iterations, 1, 1000000);
  real("ransac_threshold", c.ransac_threshold, 1e-6, 10);
  integer("ransac_sample", c.ransac_sample, 3, 10000000);
  real("min_height", c.min_height, 0, 10);
  real("max_height", c.max_height, 0, 10);
  if (!(c.max_height > c.min_height))
    fail("max_height", "(" + num(c.max_height) + ") must be greater than min_height (" + num(c.min_height) + ")");
  integer("candidate_open", c.candidate_open, 0, 50);
  real("candidate_min_exg", c.candidate_min_exg, -1, 2);  // (2G-R-B)/(R+G+B) lies in [-1, 2]
  integer("sampling.target_points", c.sampling.target_points, 1, kMaxSampledPoints);
  integer("sampling.max_points_per_box", c.sampling.max_points_per_box, 0, 1 << 30);
  real("sampling.min_box_size", c.sampling.min_box_size, 1e-9, 1e3);
  // K can never exceed the points the GMM is fitted on (the down-sampled candidates).
  integer("gmm.components", c.gmm.components, 1, std::min(kMaxGmmComponents, c.sampling.target_points));
  integer("gmm.max_iterations", c.gmm.max_iterations, 1, 100000);
  real("gmm.tolerance", c.gmm.tolerance, 0, 1);
  real("gmm.min_variance", c.gmm.min_variance, 0, 1);
  integer("min_component_points", c.min_component_points, 1, kMaxSampledPoints);
  real("height_ratio", c.height_ratio, 0, 1);
  real("join_distance", c.join_distance, 1e-6, 10);
  integer("outlier.mean_k", c.outlier.mean_k, 1, 10000);
  real("outlier.std_mul", c.outlier.std_mul, 0, 1e3);
  // The top-view raster spans the seedling's extent in cells: a tiny cell makes it huge.
  real("topview_cell", c.topview_cell, 1e-4, 1);
  integer("topview_dilate", c.topview_dilate, 0, 100);
}

double TopViewMask::area() const {
  long n = 0;
  for (auto v : mask.data) n += v > 0;
  return double(n) * cell * cell;
}

TopViewMask rasterize_top_view(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& n, double cell,
                               const Eigen::Vector2d& origin, int width, int height) {
  TopViewMask t;
  t.cell = cell;
  t.origin = origin;
  t.mask = GrayImage(width, height, 0);
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  for (const auto& p : points) {
    const int i = int(std::floor((e1.dot(p) - origin.x()) / cell));
    const int j = int(std::floor((e2.dot(p) - origin.y()) / cell));
    if (i >= 0 && j >= 0 && i < width && j < height) t.mask.at(i, j) = 255;
  }
  cv::Mat m = detail::view(t.mask);
  cv::morphologyEx(m, m, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  return t;
}

SeedlingDetection detect_seedling(const ColorImage& left, const ColorImage& right, const RectifiedGeometry& geo,
                                  const SeedlingConfig& cfg, const std::string& where) {
  SeedlingDetection r;
  if (left.width != geo.width || left.height != geo.height)
    throw Error(where, "image size " + std::to_string(left.width) + "x" + std::to_string(left.height) +
                           " differs from the calibration's " + std::to_string(geo.width) + "x" +
                           std::to_string(geo.height));
  validate_seedling_config(cfg, where);
  DisparityImage disp;
  {
    auto s = r.timer.scope("disparity");
    disp = compute_disparity(left, right, cfg.disparity, where);
  }
  StereoPoints sp;
  {
    auto s = r.timer.scope("reconstruct");
    sp = reconstruct(disp, geo, cfg.min_depth, cfg.max_depth);
  }
  r.points_total = int(sp.points.size());
  r.image_mask = GrayImage(left.width, left.height, 0);
  if (sp.points.size() < 100) return r;

  Plane pl;
  std::vector<int> cand;  // indices into sp of plant candidates
  std::vector<float> height(sp.points.size());
  {
    auto s = r.timer.scope("plane");
    pl = soil_plane(sp.points, cfg, where);
    for (std::size_t i = 0; i < sp.points.size(); ++i) {
      height[i] = float(pl.n.dot(sp.points[i].cast<double>()) + pl.d);
      if (height[i] > cfg.min_height && height[i] < cfg.max_height) cand.push_back(int(i));
    }
    if (cfg.candidate_min_exg > -1.0) {
      // Normalised excess green; +1 in the denominator keeps black pixels at 0 instead of NaN.
      std::erase_if(cand, [&](int i) {
        const Rgb8& c = left.data[std::size_t(sp.pixels[i])];
        const double exg = (2.0 * c.g - c.r - c.b) / (double(c.r) + c.g + c.b + 1.0);
        return exg < cfg.candidate_min_exg;
      });
    }
    if (cfg.candidate_open > 0 && !cand.empty()) {
      // Disparity errors on low-contrast soil raise single pixels or small clumps above the
      // height threshold; a plant is a solid region in the image. Opening the candidate mask
      // drops the clumps narrower than the kernel and keeps the plant (minus thin tips).
      cv::Mat m(left.height, left.width, CV_8U, cv::Scalar(0));
      for (int i : cand) m.data[sp.pixels[i]] = 255;
      const int k = 2 * cfg.candidate_open + 1;
      cv::morphologyEx(m, m, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
      std::erase_if(cand, [&](int i) { return m.data[sp.pixels[i]] == 0; });
    }
  }
  r.plane_normal = pl.n;
  r.plane_d = pl.d;
  r.points_candidates = int(cand.size());
  if (int(cand.size()) < std::max(cfg.gmm.components, cfg.min_component_points)) return r;

  std::vector<Eigen::Vector3f> cpts(cand.size());
  for (std::size_t i = 0; i < cand.size(); ++i) cpts[i] = sp.points[cand[i]];
  std::vector<int> sample_idx;  // indices into cpts
  {
    auto s = r.timer.scope("sample");
    sample_idx = geometry::sample_exact(cpts, cfg.sampling);
    r.sampled.reserve(sample_idx.size());
    for (int i : sample_idx) r.sampled.push_back(cpts[i]);
  }
  r.points_sampled = int(r.sampled.size());
  {
    auto s = r.timer.scope("gmm");
    r.gmm = segmentation::fit_gmm(r.sampled, cfg.gmm, where);
  }

  std::vector<Eigen::Vector3f> chosen;
  {
    auto s = r.timer.scope("recognise");
    const int k = r.gmm.model.size();
    std::vector<double> hsum(k, 0);
    std::vector<int> count(k, 0);
    std::vector<std::vector<int>> members(k);
    for (std::size_t i = 0; i < r.sampled.size(); ++i) {
      const int c = r.gmm.labels[i];
      hsum[c] += height[cand[sample_idx[i]]];
      ++count[c];
      members[c].push_back(int(i));
    }
    std::vector<double> mean_h(k, -1);
    int seed = -1;
    for (int c = 0; c < k; ++c) {
      if (count[c] == 0) continue;
      mean_h[c] = hsum[c] / count[c];
      if (count[c] >= cfg.min_component_points && (seed < 0 || mean_h[c] > mean_h[seed])) seed = c;
    }
    if (seed < 0) return r;
    std::vector<bool> in(k, false);
    in[seed] = true;
    r.chosen_components.push_back(seed);
    const double j2 = cfg.join_distance * cfg.join_distance;
    for (bool grew = true; grew;) {
      grew = false;
      for (int c = 0; c < k; ++c) {
        if (in[c] || count[c] == 0 || mean_h[c] < cfg.height_ratio * mean_h[seed]) continue;
        bool touch = false;
        for (int a : members[c]) {
          for (int s2 : r.chosen_components) {
            for (int b : members[s2])
              if ((r.sampled[a] - r.sampled[b]).squaredNorm() < j2) {
                touch = true;
                break;
              }
            if (touch) break;
          }
          if (touch) break;
        }
        if (touch) {
          in[c] = true;
          r.chosen_components.push_back(c);
          grew = true;
        }
      }
    }
    for (std::size_t i = 0; i < r.sampled.size(); ++i)
      if (in[r.gmm.labels[i]]) chosen.push_back(r.sampled[i]);
  }
  {
    auto s = r.timer.scope("outlier");
    if (chosen.size() > std::size_t(cfg.outlier.mean_k) + 1) {
      const auto keep = geometry::remove_statistical_outliers(chosen, cfg.outlier);
      std::vector<Eigen::Vector3f> kept;
      kept.reserve(keep.size());
      for (int i : keep) kept.push_back(chosen[i]);
      chosen.swap(kept);
    }
  }
  r.points_seedling_sampled = int(chosen.size());
  if (chosen.empty()) return r;

  {
    auto s = r.timer.scope("output");
    // Top-view grid around the kept samples; dense candidates in (dilated) occupied cells join.
    const Eigen::Vector3d e1 = pl.n.unitOrthogonal(), e2 = pl.n.cross(e1);
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for (const auto& p : chosen) {
      const Eigen::Vector2d q(e1.dot(p.cast<double>()), e2.dot(p.cast<double>()));
      lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    }
    const double cell = cfg.topview_cell;
    const int pad = cfg.topview_dilate + 2;
    const Eigen::Vector2d origin = lo - Eigen::Vector2d::Constant(pad * cell);
    const int gw = int((hi.x() - lo.x()) / cell) + 2 * pad + 1, gh = int((hi.y() - lo.y()) / cell) + 2 * pad + 1;
    std::vector<Eigen::Vector3d> chosen_d;
    for (const auto& p : chosen) chosen_d.push_back(p.cast<double>());
    TopViewMask occ = rasterize_top_view(chosen_d, pl.n, cell, origin, gw, gh);
    cv::Mat om = detail::view(occ.mask);
    if (cfg.topview_dilate > 0)
      cv::dilate(om, om,
                 cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                           cv::Size(2 * cfg.topview_dilate + 1, 2 * cfg.topview_dilate + 1)));
    // One plant is one connected region seen from above: keep the largest connected region of
    // the occupancy, so that stray samples (a touching weed leaf, mismatched edge points) cannot
    // stretch the envelope box.
    cv::Mat labels, stats, centroids;
    const int nl = cv::connectedComponentsWithStats(om, labels, stats, centroids, 8, CV_32S);
    if (nl > 2) {
      int best = 1;
      for (int l = 2; l < nl; ++l)
        if (stats.at<int>(l, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = l;
      for (int y = 0; y < om.rows; ++y)
        for (int x = 0; x < om.cols; ++x)
          if (labels.at<int>(y, x) != best) om.at<std::uint8_t>(y, x) = 0;
    }
    std::vector<Eigen::Vector3d> dense;
    for (int i : cand) {
      const Eigen::Vector3d p = sp.points[i].cast<double>();
      const int a = int(std::floor((e1.dot(p) - origin.x()) / cell)),
                b = int(std::floor((e2.dot(p) - origin.y()) / cell));
      if (a < 0 || b < 0 || a >= gw || b >= gh || !occ.mask.at(a, b)) continue;
      r.points.push_back(sp.points[i]);
      r.pixels.push_back(sp.pixels[i]);
      r.image_mask.data[std::size_t(sp.pixels[i])] = 255;
      dense.push_back(p);
    }
    r.top_view = rasterize_top_view(dense, pl.n, cell, origin, gw, gh);
    r.envelope = envelope_box(dense, pl.n, pl.d);
    r.found = !dense.empty();
  }
  return r;
}

}  // namespace cropsight::stereo
