// Head sizing: bounding-box and convex-hull estimators (Kusumam et al. §4.4), bias correction and
// market window. The hull is our Quickhull (quickhull.hpp) or qhull through pcl::ConvexHull, the
// library implementation the paper used; PCL stays inside this file.
#include "cropsight/measure/head_size.hpp"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/surface/convex_hull.h>

#include <algorithm>
#include <cmath>

#include "cropsight/core/error.hpp"
#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/statistics.hpp"
#include "cropsight/geometry/pca.hpp"
#include "measure/hull_candidates.hpp"
#include "measure/quickhull.hpp"

namespace cropsight::measure {

SizeEstimator parse_size_estimator(const std::string& text, const std::string& where) {
  if (text == "bbox" || text == "bounding_box") return SizeEstimator::bounding_box;
  if (text == "hull" || text == "convex_hull") return SizeEstimator::convex_hull;
  throw Error(where, "unknown size estimator '" + text + "' (expected bbox or hull)");
}

HullEngine parse_hull_engine(const std::string& text, const std::string& where) {
  if (text == "quickhull") return HullEngine::quickhull;
  if (text == "qhull") return HullEngine::qhull;
  throw Error(where, "unknown hull engine '" + text + "' (expected quickhull or qhull)");
}

const char* to_string(SizeEstimator e) { return e == SizeEstimator::bounding_box ? "bbox" : "hull"; }

double bounding_box_width(const std::vector<Eigen::Vector3f>& points) {
  if (points.empty()) return 0.0;
  float lo = points[0].x(), hi = points[0].x();
  for (const auto& p : points) {
    lo = std::min(lo, p.x());
    hi = std::max(hi, p.x());
  }
  return double(hi) - double(lo);
}

namespace {

double mean_distance(const std::vector<Eigen::Vector3f>& pts, const Eigen::Vector3d& c) {
  double s = 0.0;
  for (const auto& p : pts) s += (p.cast<double>() - c).norm();
  return s / double(pts.size());
}

// True when the points span a volume qhull can triangulate: the smallest covariance eigenvalue is
// not negligible against the largest. qhull reports flat input as an error (and PCL prints it), so
// flat sets are caught here and measured by the fallback instead.
bool spans_volume(const std::vector<Eigen::Vector3f>& pts) {
  // Of the scatter (the ratio needs no division by the count); ascending.
  const Eigen::Vector3d ev = geometry::principal_values(geometry::point_moments(pts).scatter);
  return ev(2) > 0.0 && ev(0) > 1e-10 * ev(2);
}

}  // namespace

namespace {

// The hull estimator on `all` (the head's points), the hull built (Quickhull, or qhull when asked
// for or when Quickhull declines) from `hull_input`, a subset that holds every hull vertex of
// `all` (all itself, or the row/column filter's candidates).
double hull_diameter(const std::vector<Eigen::Vector3f>& all, const std::vector<Eigen::Vector3f>& hull_input,
                     int* vertices, HullEngine engine) {
  if (vertices) *vertices = 0;
  if (all.empty()) return 0.0;
  // The flatness check runs on hull_input: it holds every hull vertex of `all`, so it is flat exactly
  // when `all` is, and it is the smaller set (a fifth of a head's points after the filter).
  if (all.size() >= 4 && hull_input.size() >= 4 && spans_volume(hull_input)) {
    if (QuickHull q; engine == HullEngine::quickhull && quickhull(hull_input, q)) {
      std::vector<Eigen::Vector3f> v;
      v.reserve(q.vertices.size());
      for (int i : q.vertices) v.push_back(hull_input[std::size_t(i)]);
      if (vertices) *vertices = int(v.size());
      return 2.0 * mean_distance(v, geometry::point_mean(v));
    }
    // qhull: asked for, or our Quickhull could not build a consistent hull
    pcl::PointCloud<pcl::PointXYZ>::Ptr in(new pcl::PointCloud<pcl::PointXYZ>);
    in->points.reserve(hull_input.size());
    for (const auto& p : hull_input) in->points.emplace_back(p.x(), p.y(), p.z());
    in->width = std::uint32_t(in->points.size());
    in->height = 1;
    in->is_dense = true;
    pcl::ConvexHull<pcl::PointXYZ> hull;
    hull.setDimension(3);
    hull.setInputCloud(in);
    pcl::PointCloud<pcl::PointXYZ> out;
    hull.reconstruct(out);
    if (out.size() >= 4) {
      std::vector<Eigen::Vector3f> v;
      v.reserve(out.size());
      for (const auto& p : out.points) v.emplace_back(p.x, p.y, p.z);
      if (vertices) *vertices = int(v.size());
      return 2.0 * mean_distance(v, geometry::point_mean(v));
    }
  }
  // Fallback for degenerate sets: all points stand in for the hull vertices.
  return 2.0 * mean_distance(all, geometry::point_mean(all));
}

}  // namespace

double convex_hull_diameter(const std::vector<Eigen::Vector3f>& points, int* vertices, HullEngine engine) {
  return hull_diameter(points, points, vertices, engine);
}

std::vector<Eigen::Vector3f> stride_subsample(const std::vector<Eigen::Vector3f>& points, int max_points) {
  if (max_points <= 0 || points.size() <= std::size_t(max_points)) return points;
  const std::size_t k = (points.size() + std::size_t(max_points) - 1) / std::size_t(max_points);
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size() / k + 1);
  for (std::size_t i = 0; i < points.size(); i += k) out.push_back(points[i]);
  return out;
}

HeadSizer::HeadSizer(const HeadSizeConfig& cfg)
    : cfg_(cfg), estimator_(parse_size_estimator(cfg.estimator)), engine_(parse_hull_engine(cfg.hull_engine)) {
  check_config(cfg_, "sizing", "sizing.");  // the ranges declared in HeadSizeConfig::visit
  if (!(cfg_.market_min_mm <= cfg_.market_max_mm))
    throw Error("sizing.market_min_mm", "market window is empty (min > max)");
  if (estimator_ == SizeEstimator::convex_hull && !cfg_.compute_hull)
    throw Error("sizing.compute_hull", "the hull estimator is chosen but compute_hull is false");
}

double HeadSizer::correct(SizeEstimator e, double raw_mm) const {
  return e == SizeEstimator::bounding_box ? cfg_.bbox_scale * raw_mm + cfg_.bbox_offset_mm
                                          : cfg_.hull_scale * raw_mm + cfg_.hull_offset_mm;
}

double HeadSizer::corrected(double bbox_mm, double hull_mm) const {
  return estimator_ == SizeEstimator::bounding_box ? correct(estimator_, bbox_mm) : correct(estimator_, hull_mm);
}

bool HeadSizer::harvestable(double d) const { return d >= cfg_.market_min_mm && d <= cfg_.market_max_mm; }

HeadSize HeadSizer::measure(const std::vector<Eigen::Vector3f>& points) const { return measure_with(points, nullptr); }

HeadSize HeadSizer::measure_with(const std::vector<Eigen::Vector3f>& points,
                                 const std::vector<Eigen::Vector3f>* hull_candidates) const {
  HeadSize s;
  s.points = int(points.size());
  if (s.points < cfg_.min_points) return s;
  s.valid = true;
  s.bbox_mm = 1000.0 * bounding_box_width(points);
  if (cfg_.compute_hull) {
    if (cfg_.hull_max_points > 0 && points.size() > std::size_t(cfg_.hull_max_points))
      s.hull_mm =
          1000.0 * convex_hull_diameter(stride_subsample(points, cfg_.hull_max_points), &s.hull_vertices, engine_);
    else
      s.hull_mm =
          1000.0 * hull_diameter(points, hull_candidates ? *hull_candidates : points, &s.hull_vertices, engine_);
  }
  s.diameter_mm = corrected(s.bbox_mm, s.hull_mm);
  s.harvestable = harvestable(s.diameter_mm);
  return s;
}

HeadSize HeadSizer::measure(const OrganizedCloud& cloud, const std::vector<int>& indices) const {
  std::vector<Eigen::Vector3f> pts;
  std::vector<int> valid;
  pts.reserve(indices.size());
  valid.reserve(indices.size());
  for (int i : indices) {
    if (i < 0 || std::size_t(i) >= cloud.size()) throw Error("head sizing", "point index out of range");
    if (cloud.valid(std::size_t(i))) {
      pts.push_back(cloud.point(std::size_t(i)));
      valid.push_back(i);
    }
  }
  const bool filter =
      cfg_.compute_hull && cfg_.hull_prefilter && cfg_.hull_max_points == 0 && int(pts.size()) >= cfg_.min_points;
  if (filter)
    if (const auto cand = hull_vertex_candidates(cloud, valid)) {
      std::vector<Eigen::Vector3f> cpts;
      cpts.reserve(cand->size());
      for (int i : *cand) cpts.push_back(cloud.point(std::size_t(i)));
      return measure_with(pts, &cpts);
    }
  return measure_with(pts, nullptr);
}

BiasFit fit_size_bias(const std::vector<double>& est, const std::vector<double>& truth, const std::string& where) {
  if (est.size() != truth.size()) throw Error(where, "estimates and truths differ in count");
  if (est.size() < 2) throw Error(where, "need at least 2 heads with measured diameters to fit a bias");
  // The noise is in the estimate (view to view), not in the measured diameter, so the robust line
  // is fitted in the direction estimate = a · truth + b and then inverted: truth = (estimate − b) / a.
  // Regressing truth on the noisy estimate instead attenuates the slope (errors in the regressor),
  // and the pairs of one head seen in several frames (same truth, different estimates) give
  // slope 0 there and pull the median further down; here they have no slope and are skipped.
  // Theil–Sen (median of the pairwise slopes, then the median intercept) is robust to the few
  // gross errors real detections carry (a head merged with a leaf reads 100 mm too wide), which pull
  // a least-squares line far off. Above 2000 pairs' worth of points an even subsample keeps it
  // O(2000²).
  const std::size_t n = est.size(), step = n > 2000 ? (n + 1999) / 2000 : 1;
  std::vector<double> slopes;
  for (std::size_t i = 0; i < n; i += step)
    for (std::size_t j = i + step; j < n; j += step)
      if (std::abs(truth[j] - truth[i]) > 1e-9) slopes.push_back((est[j] - est[i]) / (truth[j] - truth[i]));
  if (slopes.empty()) throw Error(where, "measured diameters have no spread (one head?); cannot fit a scale");
  const double a = median(slopes);
  if (!(a > 1e-6)) throw Error(where, "estimated diameters do not grow with the measured ones; cannot fit a scale");
  std::vector<double> icpt(n);
  for (std::size_t i = 0; i < n; ++i) icpt[i] = est[i] - a * truth[i];
  const double b = median(icpt);
  BiasFit f;
  f.n = int(n);
  f.scale = 1.0 / a;
  f.offset_mm = -b / a;
  double sb = 0, sa = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sb += (est[i] - truth[i]) * (est[i] - truth[i]);
    const double c = f.scale * est[i] + f.offset_mm;
    sa += (c - truth[i]) * (c - truth[i]);
  }
  f.rms_before_mm = std::sqrt(sb / double(n));
  f.rms_after_mm = std::sqrt(sa / double(n));
  return f;
}

}  // namespace cropsight::measure
