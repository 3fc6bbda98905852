// Per-point features for the grape GBDT. Neighbourhood statistics use our nanoflann index
// (geometry::PointIndex); FPFH uses PCL's FPFHEstimationOMP on the same k neighbourhoods.
#include "cropsight/pipeline/grape/features.hpp"
#include "cropsight/core/threads.hpp"

#include <pcl/features/fpfh_omp.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <sstream>

#include "core/parallel_for.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/geometry/knn_normals.hpp"
#include "cropsight/geometry/pca.hpp"
#include "cropsight/learning/gbdt.hpp"
#include "geometry/point_kdtree.hpp"

namespace cropsight::pipeline::grape {

namespace {
constexpr std::size_t kBase = 14;       // xyz, radius, rgb, hsv, excess green, normal
constexpr std::size_t kPerRadius = 17;  // log radius, 5 eigen, |n_local·n|, mean rgb, d rgb, rgb std, offset xyz
constexpr std::size_t kFpfh = 33;

void hsv(const Eigen::Vector3f& c, float& h, float& s, float& v) {
  const float mx = c.maxCoeff(), mn = c.minCoeff(), d = mx - mn;
  v = mx;
  s = mx > 0 ? d / mx : 0.f;
  if (d <= 0) {
    h = 0;
  } else if (mx == c.x()) {
    h = std::fmod((c.y() - c.z()) / d + 6.f, 6.f) / 6.f;
  } else if (mx == c.y()) {
    h = ((c.z() - c.x()) / d + 2.f) / 6.f;
  } else {
    h = ((c.x() - c.y()) / d + 4.f) / 6.f;
  }
}
}  // namespace

void FeatureConfig::validate(const std::string& where, const std::string& prefix) const {
  check_config(*this, where, prefix);
}

std::string FeatureConfig::recipe() const {
  std::ostringstream o;
  o.imbue(std::locale::classic());
  o.precision(9);
  o << "k_small=" << k_small << ";k_large=" << k_large << ";fpfh=" << (fpfh ? 1 : 0);
  // Written only for the fast recipe: the original recipe's text (and so its model files) is
  // unchanged.
  if (sample > 0)
    o << ";sample=" << sample << ";sample_seed=" << sample_seed << ";carry_k=" << carry_k
      << ";carry_colour=" << carry_colour << ";carry_soft=" << (carry_soft ? 1 : 0);
  return o.str();
}

FeatureConfig FeatureConfig::from_recipe(const std::string& text, const std::string& where) {
  // The recipe is "key=value;..." of this struct's own fields: split it, then let visit()'s
  // parsers and ranges judge the values, so that a corrupt model file is named with its key
  // (std::stoi used to escape as an internal error, and "fpfh=true" read as false).
  const std::string what = "feature recipe '" + text + "'";
  ConfigMap values;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ';')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw Error(where, what + ": item '" + item + "' is not key=value");
    const std::string key = item.substr(0, eq);
    // threads is how a model is run, not how it was trained: never part of a recipe.
    if (key == "threads") throw Error(where, what + ": unknown key 'threads'");
    if (!values.emplace(key, item.substr(eq + 1)).second) throw Error(where, what + ": key '" + key + "' repeated");
  }
  for (const char* key : {"k_small", "k_large", "fpfh"})
    if (!values.count(key)) throw Error(where, what + ": key '" + std::string(key) + "' missing");
  FeatureConfig c;
  try {
    apply_config(c, values, where);
    c.validate(where);
  } catch (const Error& e) {
    throw Error(where, "feature recipe: " + e.problem());
  }
  return c;
}

std::size_t grape_feature_count(const FeatureConfig& cfg) { return kBase + 2 * (kPerRadius + (cfg.fpfh ? kFpfh : 0)); }

std::vector<std::string> grape_feature_names(const FeatureConfig& cfg) {
  std::vector<std::string> n = {"x",   "y",   "z",   "r_centroid", "red", "green", "blue",
                                "hue", "sat", "val", "exg",        "nx",  "ny",    "nz"};
  for (const char* s : {"s", "l"}) {
    const std::string p = std::string(s) + "_";
    for (const char* f :
         {"log_radius", "linearity", "planarity", "scattering", "curvature", "omnivariance", "normal_agreement",
          "mean_r", "mean_g", "mean_b", "d_r", "d_g", "d_b", "rgb_std", "off_x", "off_y", "off_z"})
      n.push_back(p + f);
    if (cfg.fpfh)
      for (int i = 0; i < 33; ++i) n.push_back(p + "fpfh" + std::to_string(i));
  }
  return n;
}

namespace {
// Neighbourhood statistics of one neighbourhood (nb[0..k), squared distances d2, nearest first)
// of point i, into g[0..kPerRadius).
void neighbourhood_features(const Cloud& cloud, std::size_t i, const int* nb, const float* d2, std::size_t count,
                            float* g) {
  const Eigen::Vector3f& p = cloud.points[i];
  const Eigen::Vector3f& c = cloud.colors[i];
  const Eigen::Vector3f& nrm = cloud.normals[i];
  const double k = double(count);
  g[0] = count == 0 ? 0.f : float(std::log(std::sqrt(double(d2[count - 1])) + 1e-6));  // log radius: density
  if (count < 3) return;  // isolated point: leave neighbourhood features at 0
  // One pass sums the positions and the colours (per point, ~100k times a cloud); the covariance
  // and its closed-form eigenvectors come from geometry/pca.
  const auto point = [&](std::size_t q) { return cloud.points[std::size_t(nb[q])].cast<double>(); };
  Eigen::Vector3d m = Eigen::Vector3d::Zero(), mc = Eigen::Vector3d::Zero(), mc2 = Eigen::Vector3d::Zero();
  for (std::size_t q = 0; q < count; ++q) {
    m += point(q);
    const Eigen::Vector3d cj = cloud.colors[std::size_t(nb[q])].cast<double>();
    mc += cj;
    mc2 += cj.cwiseProduct(cj);
  }
  m /= k, mc /= k, mc2 /= k;
  const Eigen::Matrix3d cov = geometry::scatter_about(count, point, m) / k;
  const auto pc = geometry::principal_axes(cov, geometry::EigenMethod::closed_form);
  const Eigen::Vector3d l = pc.eigenvalues.cwiseMax(1e-12);  // ascending
  const double sum = l.sum();
  g[1] = float((l[2] - l[1]) / l[2]);
  g[2] = float((l[1] - l[0]) / l[2]);
  g[3] = float(l[0] / l[2]);
  g[4] = float(l[0] / sum);
  g[5] = float(std::cbrt(l[0] * l[1] * l[2]) / sum);
  g[6] = float(std::abs(pc.normal().dot(nrm.cast<double>())));
  const Eigen::Vector3d var = (mc2 - mc.cwiseProduct(mc)).cwiseMax(0.0);
  g[7] = float(mc.x()), g[8] = float(mc.y()), g[9] = float(mc.z());
  g[10] = c.x() - g[7], g[11] = c.y() - g[8], g[12] = c.z() - g[9];
  g[13] = float(std::sqrt(var.sum() / 3));
  const Eigen::Vector3d off = p.cast<double>() - m;
  const double scale = std::sqrt(double(d2[count - 1])) + 1e-9;  // neighbourhood radius
  g[14] = float(off.x() / scale), g[15] = float(off.y() / scale), g[16] = float(off.z() / scale);
}

// Features of the points `subset` of `cloud`, neighbourhoods searched in all of `cloud`.
// shared_query: one k-NN query of max(k_small, k_large) per point, its nearest k_small being the
// fine neighbourhood (the fast recipe); otherwise one query per neighbourhood (the original
// recipe: kept bit for bit, so that models trained with it predict as before).
std::vector<float> compute_features(const Cloud& cloud, const FeatureConfig& cfg, const std::vector<int>& subset,
                                    bool shared_query) {
  const std::size_t n = cloud.size();
  const std::size_t rows = subset.size(), F = grape_feature_count(cfg);
  std::vector<float> X(rows * F, 0.f);

  const Eigen::Vector3d cen = geometry::point_mean(cloud.points);  // zero for an empty cloud

  // The original recipe's index (kept as it was, bit for bit), or for the fast recipe a plain
  // nanoflann tree queried without allocations.
  std::optional<geometry::PointIndex> index;
  geometry::detail::PackedPoints packed;
  std::optional<geometry::detail::PointKdTree> tree;
  if (shared_query) {
    packed.xyz.reserve(3 * n);
    for (const auto& p : cloud.points) packed.xyz.insert(packed.xyz.end(), {p.x(), p.y(), p.z()});
    tree.emplace(3, packed, geometry::detail::kdtree_params());
    tree->buildIndex();
  } else {
    index.emplace(cloud.points);
  }
  const std::size_t k_max = std::min<std::size_t>(std::size_t(std::max(cfg.k_small, cfg.k_large)), n);
  const std::size_t stride = kPerRadius + (cfg.fpfh ? kFpfh : 0);
  auto rows_range = [&](std::size_t r0, std::size_t r1) {
    std::vector<int> nb;
    std::vector<float> d2;
    std::vector<std::uint32_t> found_idx(k_max);
    for (std::size_t r = r0; r < r1; ++r) {
      const std::size_t i = std::size_t(subset[r]);
      float* f = X.data() + r * F;
      const Eigen::Vector3f& p = cloud.points[i];
      const Eigen::Vector3f& c = cloud.colors[i];
      const Eigen::Vector3f& nrm = cloud.normals[i];
      f[0] = p.x(), f[1] = p.y(), f[2] = p.z();
      f[3] = float((p.cast<double>() - cen).norm());
      f[4] = c.x(), f[5] = c.y(), f[6] = c.z();
      hsv(c, f[7], f[8], f[9]);
      f[10] = 2 * c.y() - c.x() - c.z();
      f[11] = nrm.x(), f[12] = nrm.y(), f[13] = nrm.z();
      if (shared_query) {
        d2.resize(k_max);
        const std::size_t found = k_max ? tree->knnSearch(p.data(), k_max, found_idx.data(), d2.data()) : 0;
        nb.assign(found_idx.begin(), found_idx.begin() + long(found));
        d2.resize(found);
      }
      for (int s = 0; s < 2; ++s) {
        const int k = s == 0 ? cfg.k_small : cfg.k_large;
        if (!shared_query) index->knn(p, k, nb, &d2);
        const std::size_t count = std::min(nb.size(), std::size_t(k));
        neighbourhood_features(cloud, i, nb.data(), d2.data(), count, f + kBase + std::size_t(s) * stride);
      }
    }
  };
  // Rows are independent (read-only index): the fast recipe splits them over cfg.threads; the
  // original recipe keeps its single thread (FPFH, its main cost, has its own threads).
  cropsight::detail::parallel_for(rows, shared_query ? cfg.threads : 1, 256, rows_range);
  return X;
}

void check_input(const Cloud& cloud, const FeatureConfig& cfg) {
  if (!cloud.has_normals() || !cloud.has_colors()) throw Error("grape features", "cloud needs normals and colours");
  cfg.validate("grape features");
}

void add_fpfh(const Cloud& cloud, const FeatureConfig& cfg, const std::vector<int>& subset, std::vector<float>& X);
}  // namespace

std::vector<float> grape_point_features(const Cloud& cloud, const FeatureConfig& cfg,
                                        const std::vector<int>& subset_in) {
  check_input(cloud, cfg);
  std::vector<int> subset = subset_in;
  if (subset.empty()) {
    subset.resize(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) subset[i] = int(i);
  }
  std::vector<float> X = compute_features(cloud, cfg, subset, false);
  if (cfg.fpfh) add_fpfh(cloud, cfg, subset, X);
  return X;
}

std::vector<int> grape_sample(std::size_t size, const FeatureConfig& cfg, std::uint64_t seed) {
  std::vector<int> idx(size);
  for (std::size_t i = 0; i < size; ++i) idx[i] = int(i);
  if (cfg.sample <= 0 || std::size_t(cfg.sample) >= size) return idx;
  // Partial Fisher-Yates with our own index draw (std::uniform_int_distribution and
  // std::shuffle are implementation-defined; this is the same on every standard library).
  std::mt19937_64 rng(seed);
  const std::size_t m = std::size_t(cfg.sample);
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t j = i + std::size_t(rng() % std::uint64_t(size - i));
    std::swap(idx[i], idx[j]);
  }
  idx.resize(m);
  std::sort(idx.begin(), idx.end());
  return idx;
}

std::vector<float> grape_sample_features(const Cloud& cloud, const FeatureConfig& cfg, const std::vector<int>& sample) {
  check_input(cloud, cfg);
  Cloud sub;
  sub.points.reserve(sample.size());
  sub.colors.reserve(sample.size());
  sub.normals.reserve(sample.size());
  for (int i : sample) {
    if (i < 0 || std::size_t(i) >= cloud.size()) throw Error("grape features", "sample index out of range");
    sub.points.push_back(cloud.points[std::size_t(i)]);
    sub.colors.push_back(cloud.colors[std::size_t(i)]);
    sub.normals.push_back(cloud.normals[std::size_t(i)]);
  }
  std::vector<int> all(sample.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  std::vector<float> X = compute_features(sub, cfg, all, true);
  if (cfg.fpfh) add_fpfh(sub, cfg, all, X);
  return X;
}

namespace {
void add_fpfh(const Cloud& cloud, const FeatureConfig& cfg, const std::vector<int>& subset, std::vector<float>& X) {
  const std::size_t n = cloud.size(), rows = subset.size(), F = grape_feature_count(cfg);
  {
    pcl::PointCloud<pcl::PointXYZ>::Ptr pc(new pcl::PointCloud<pcl::PointXYZ>);
    pcl::PointCloud<pcl::Normal>::Ptr pn(new pcl::PointCloud<pcl::Normal>);
    pc->resize(n);
    pn->resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      (*pc)[i].getVector3fMap() = cloud.points[i];
      (*pn)[i].getNormalVector3fMap() = cloud.normals[i];
    }
    pcl::IndicesPtr idx(new pcl::Indices(subset.begin(), subset.end()));
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
    for (int s = 0; s < 2; ++s) {
      pcl::FPFHEstimationOMP<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> est(
          static_cast<unsigned>(std::max(1, cfg.threads)));
      est.setInputCloud(pc);
      est.setInputNormals(pn);
      est.setIndices(idx);
      est.setSearchMethod(tree);
      est.setKSearch(s == 0 ? cfg.k_small : cfg.k_large);
      pcl::PointCloud<pcl::FPFHSignature33> out;
      est.compute(out);
      if (out.size() != rows) throw Error("grape features", "FPFH returned an unexpected number of rows");
      const std::size_t off = kBase + std::size_t(s) * (kPerRadius + kFpfh) + kPerRadius;
      for (std::size_t r = 0; r < rows; ++r) {
        float* g = X.data() + r * F + off;
        for (std::size_t b = 0; b < kFpfh; ++b) {
          const float v = out[r].histogram[b];
          g[b] = std::isfinite(v) ? v : 0.f;  // PCL writes NaN for points without neighbours
        }
      }
    }
  }
}
}  // namespace

}  // namespace cropsight::pipeline::grape
