#include "cropsight/pipeline/seedling/steps.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <random>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/pca.hpp"
#include "cropsight/geometry/statistical_outlier.hpp"
#include "stereo/cv_convert.hpp"

namespace cropsight::pipeline::seedling {
namespace {

// Least-squares plane of `pts` (normal = smallest principal axis of the scatter matrix).
SoilPlane fit_plane(const std::vector<Eigen::Vector3d>& pts) {
  const auto m = geometry::point_moments(pts);
  SoilPlane pl;
  pl.n = geometry::principal_axes(m.scatter).normal().normalized();
  pl.d = -pl.n.dot(m.mean);
  return pl;
}

// Excess-green test: soil pixels given a leaf's disparity by the matching window lie outside the
// leaf in 3D but are soil-coloured. Normalised excess green; +1 in the denominator keeps black
// pixels at 0 instead of NaN.
void drop_non_green(std::vector<int>& cand, const stereo::StereoPoints& sp, const ColorImage& left, double min_exg) {
  std::erase_if(cand, [&](int i) {
    const Rgb8& c = left.data[std::size_t(sp.pixels[i])];
    const double exg = (2.0 * c.g - c.r - c.b) / (double(c.r) + c.g + c.b + 1.0);
    return exg < min_exg;
  });
}

// Disparity errors on low-contrast soil raise single pixels or small clumps above the height
// threshold; a plant is a solid region in the image. Opening the candidate mask drops the clumps
// narrower than the kernel and keeps the plant (minus thin tips).
void open_candidate_mask(std::vector<int>& cand, const stereo::StereoPoints& sp, const ColorImage& left, int radius) {
  cv::Mat m(left.height, left.width, CV_8U, cv::Scalar(0));
  for (int i : cand) m.data[sp.pixels[i]] = 255;
  const int k = 2 * radius + 1;
  cv::morphologyEx(m, m, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  std::erase_if(cand, [&](int i) { return m.data[sp.pixels[i]] == 0; });
}

// Per GMM component: member indices into the sampled points and mean height (-1 when empty).
struct Components {
  std::vector<std::vector<int>> members;
  std::vector<double> mean_height;
};

Components component_heights(const std::vector<float>& height, const segmentation::GmmResult& gmm) {
  const int k = gmm.model.size();
  Components c{std::vector<std::vector<int>>(k), std::vector<double>(k, -1)};
  std::vector<double> hsum(k, 0);
  for (std::size_t i = 0; i < gmm.labels.size(); ++i) {
    hsum[gmm.labels[i]] += height[i];
    c.members[gmm.labels[i]].push_back(int(i));
  }
  for (int j = 0; j < k; ++j)
    if (!c.members[j].empty()) c.mean_height[j] = hsum[j] / double(c.members[j].size());
  return c;
}

// True when a member of component `c` lies within sqrt(j2) of a member of a chosen component:
// in 3D, or with `top_view` seen from above (along the soil normal: the squared 3D distance less
// the squared height difference).
bool touches(const std::vector<Eigen::Vector3f>& sampled, const std::vector<float>& height, const Components& comp,
             int c, const std::vector<int>& chosen, double j2, bool top_view) {
  for (int a : comp.members[c])
    for (int s : chosen)
      for (int b : comp.members[s]) {
        double d2 = (sampled[a] - sampled[b]).squaredNorm();
        if (top_view) d2 -= double(height[a] - height[b]) * double(height[a] - height[b]);
        if (d2 < j2) return true;
      }
  return false;
}

// The occupancy grid around the kept samples: origin and size in cells, padded so that the
// dilation and the closing cannot reach the border.
struct Grid {
  Eigen::Vector3d e1, e2;
  Eigen::Vector2d origin;
  int width = 0, height = 0;
  double cell = 0;
  bool cell_of(const Eigen::Vector3d& p, int& a, int& b) const {
    a = int(std::floor((e1.dot(p) - origin.x()) / cell));
    b = int(std::floor((e2.dot(p) - origin.y()) / cell));
    return a >= 0 && b >= 0 && a < width && b < height;
  }
};

// The projections take the float points through a cast expression on purpose: Eigen evaluates
// dot() of an expression and of a stored Vector3d in different orders (scalar vs. packet), and one
// rounding step moves a border cell; this keeps the grid bit-identical to the detector's before
// the steps were split out.
Grid grid_around(const std::vector<Eigen::Vector3f>& kept, const Eigen::Vector3d& n, const Config& cfg) {
  Grid g;
  g.e1 = n.unitOrthogonal(), g.e2 = n.cross(g.e1);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& p : kept) {
    const Eigen::Vector2d q(g.e1.dot(p.cast<double>()), g.e2.dot(p.cast<double>()));
    lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  }
  g.cell = cfg.topview_cell;
  const int pad = cfg.topview_dilate + 2;
  g.origin = lo - Eigen::Vector2d::Constant(pad * g.cell);
  g.width = int((hi.x() - lo.x()) / g.cell) + 2 * pad + 1;
  g.height = int((hi.y() - lo.y()) / g.cell) + 2 * pad + 1;
  return g;
}

// One plant is one connected region seen from above: keep the largest connected region of the
// occupancy, so that stray samples (a touching weed leaf, mismatched edge points) cannot stretch
// the envelope box.
void keep_largest_region(cv::Mat& om) {
  cv::Mat labels, stats, centroids;
  const int nl = cv::connectedComponentsWithStats(om, labels, stats, centroids, 8, CV_32S);
  if (nl <= 2) return;
  int best = 1;
  for (int l = 2; l < nl; ++l)
    if (stats.at<int>(l, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = l;
  for (int y = 0; y < om.rows; ++y)
    for (int x = 0; x < om.cols; ++x)
      if (labels.at<int>(y, x) != best) om.at<std::uint8_t>(y, x) = 0;
}

std::vector<Eigen::Vector3d> to_double(const std::vector<Eigen::Vector3f>& pts) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.push_back(p.cast<double>());
  return out;
}

}  // namespace

// RANSAC on a random subset; the normal is oriented towards the camera (origin on the positive
// side), so heights above the soil are positive. The fixed seed makes detections reproducible.
SoilPlane fit_soil_plane(const std::vector<Eigen::Vector3f>& pts, const Config& cfg, const std::string& where) {
  if (pts.size() < 3) throw Error(where, "too few reconstructed points to fit the soil plane");
  std::mt19937 rng(12345);
  std::vector<Eigen::Vector3d> sub;
  const int m = std::min<int>(cfg.ransac_sample, int(pts.size()));
  for (int i = 0; i < m; ++i)
    sub.push_back(pts[std::uniform_int_distribution<std::size_t>(0, pts.size() - 1)(rng)].cast<double>());
  SoilPlane best;
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
  SoilPlane pl = inl.size() >= 3 ? fit_plane(inl) : best;
  if (pl.d < 0) pl.n = -pl.n, pl.d = -pl.d;
  return pl;
}

std::vector<float> heights_above(const std::vector<Eigen::Vector3f>& points, const SoilPlane& pl) {
  std::vector<float> h(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) h[i] = float(pl.n.dot(points[i].cast<double>()) + pl.d);
  return h;
}

std::vector<int> select_candidates(const stereo::StereoPoints& sp, const std::vector<float>& height,
                                   const ColorImage& left, const Config& cfg) {
  std::vector<int> cand;
  for (std::size_t i = 0; i < sp.points.size(); ++i)
    if (height[i] > cfg.min_height && height[i] < cfg.max_height) cand.push_back(int(i));
  if (cfg.candidate_min_exg > -1.0) drop_non_green(cand, sp, left, cfg.candidate_min_exg);
  if (cfg.candidate_open > 0 && !cand.empty()) open_candidate_mask(cand, sp, left, cfg.candidate_open);
  return cand;
}

std::vector<int> select_components(const std::vector<Eigen::Vector3f>& sampled, const std::vector<float>& height,
                                   const segmentation::GmmResult& gmm, const Config& cfg) {
  const Components comp = component_heights(height, gmm);
  const int k = int(comp.members.size());
  int seed = -1;
  for (int c = 0; c < k; ++c)
    if (int(comp.members[c].size()) >= cfg.min_component_points &&
        (seed < 0 || comp.mean_height[c] > comp.mean_height[seed]))
      seed = c;
  if (seed < 0) return {};
  std::vector<int> chosen{seed};
  std::vector<bool> in(k, false);
  in[seed] = true;
  const double j2 = cfg.join_distance * cfg.join_distance;
  // Grow until no component joins: a lower leaf may touch the plant only through another one.
  for (bool grew = true; grew;) {
    grew = false;
    for (int c = 0; c < k; ++c) {
      if (in[c] || comp.members[c].empty() || comp.mean_height[c] < cfg.height_ratio * comp.mean_height[seed]) continue;
      if (!touches(sampled, height, comp, c, chosen, j2, cfg.join_top_view)) continue;
      in[c] = true;
      chosen.push_back(c);
      grew = true;
    }
  }
  return chosen;
}

std::vector<Eigen::Vector3f> points_of_components(const std::vector<Eigen::Vector3f>& sampled,
                                                  const std::vector<int>& labels, const std::vector<int>& components) {
  std::vector<Eigen::Vector3f> out;
  for (std::size_t i = 0; i < sampled.size(); ++i)
    if (std::find(components.begin(), components.end(), labels[i]) != components.end()) out.push_back(sampled[i]);
  return out;
}

std::vector<Eigen::Vector3f> remove_outliers(const std::vector<Eigen::Vector3f>& points, const Config& cfg) {
  if (points.size() <= std::size_t(cfg.outlier.mean_k) + 1) return points;
  const auto keep = geometry::remove_statistical_outliers(points, cfg.outlier);
  std::vector<Eigen::Vector3f> kept;
  kept.reserve(keep.size());
  for (int i : keep) kept.push_back(points[i]);
  return kept;
}

DensePlant densify_top_view(const std::vector<Eigen::Vector3f>& kept, const stereo::StereoPoints& sp,
                            const std::vector<int>& cand, const SoilPlane& pl, const Config& cfg) {
  const std::vector<Eigen::Vector3d> kept_d = to_double(kept);
  const Grid g = grid_around(kept, pl.n, cfg);
  TopViewMask occ = rasterize_top_view(kept_d, pl.n, g.cell, g.origin, g.width, g.height);
  cv::Mat om = stereo::detail::view(occ.mask);
  if (cfg.topview_dilate > 0) {
    const int k = 2 * cfg.topview_dilate + 1;
    cv::dilate(om, om, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  }
  keep_largest_region(om);
  DensePlant plant;
  std::vector<Eigen::Vector3d> dense;
  for (int i : cand) {
    const Eigen::Vector3d p = sp.points[i].cast<double>();
    int a = 0, b = 0;
    if (!g.cell_of(p, a, b) || !occ.mask.at(a, b)) continue;
    plant.indices.push_back(i);
    dense.push_back(p);
  }
  plant.top_view = rasterize_top_view(dense, pl.n, g.cell, g.origin, g.width, g.height);
  return plant;
}

}  // namespace cropsight::pipeline::seedling
