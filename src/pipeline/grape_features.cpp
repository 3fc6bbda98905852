// Per-point features for the grape GBDT. Neighbourhood statistics use our nanoflann index
// (geometry::PointIndex); FPFH uses PCL's FPFHEstimationOMP on the same k neighbourhoods.
#include "cropsight/pipeline/grape_features.hpp"

#include <pcl/features/fpfh_omp.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/geometry/knn_normals.hpp"

namespace cropsight::pipeline {

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

std::string GrapeFeatureConfig::recipe() const {
  std::ostringstream o;
  o.imbue(std::locale::classic());
  o.precision(9);
  o << "k_small=" << k_small << ";k_large=" << k_large << ";fpfh=" << (fpfh ? 1 : 0);
  return o.str();
}

GrapeFeatureConfig GrapeFeatureConfig::from_recipe(const std::string& text, const std::string& where) {
  GrapeFeatureConfig c;
  std::istringstream in(text);
  std::string item;
  int seen = 0;
  while (std::getline(in, item, ';')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw Error(where, "bad feature recipe '" + text + "'");
    const std::string k = item.substr(0, eq), v = item.substr(eq + 1);
    if (k == "k_small")
      c.k_small = std::stoi(v), ++seen;
    else if (k == "k_large")
      c.k_large = std::stoi(v), ++seen;
    else if (k == "fpfh")
      c.fpfh = v == "1", ++seen;
    else
      throw Error(where, "unknown feature recipe key '" + k + "'");
  }
  if (seen != 3) throw Error(where, "incomplete feature recipe '" + text + "'");
  return c;
}

std::size_t grape_feature_count(const GrapeFeatureConfig& cfg) {
  return kBase + 2 * (kPerRadius + (cfg.fpfh ? kFpfh : 0));
}

std::vector<std::string> grape_feature_names(const GrapeFeatureConfig& cfg) {
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

std::vector<float> grape_point_features(const Cloud& cloud, const GrapeFeatureConfig& cfg,
                                        const std::vector<int>& subset_in) {
  if (!cloud.has_normals() || !cloud.has_colors()) throw Error("grape features", "cloud needs normals and colours");
  if (cfg.k_small < 3 || cfg.k_large < 3) throw Error("grape features", "neighbourhoods need at least 3 points");
  const std::size_t n = cloud.size();
  std::vector<int> subset = subset_in;
  if (subset.empty()) {
    subset.resize(n);
    for (std::size_t i = 0; i < n; ++i) subset[i] = int(i);
  }
  const std::size_t rows = subset.size(), F = grape_feature_count(cfg);
  std::vector<float> X(rows * F, 0.f);

  Eigen::Vector3d cen = Eigen::Vector3d::Zero();
  for (const auto& p : cloud.points) cen += p.cast<double>();
  cen /= double(std::max<std::size_t>(n, 1));

  geometry::PointIndex index(cloud.points);
  std::vector<int> nb;
  for (std::size_t r = 0; r < rows; ++r) {
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
    for (int s = 0; s < 2; ++s) {
      float* g = f + kBase + std::size_t(s) * (kPerRadius + (cfg.fpfh ? kFpfh : 0));
      std::vector<float> d2;
      index.knn(p, s == 0 ? cfg.k_small : cfg.k_large, nb, &d2);
      const double k = double(nb.size());
      g[0] = d2.empty() ? 0.f : float(std::log(std::sqrt(double(d2.back())) + 1e-6));  // log radius: density
      if (nb.size() < 3) continue;  // isolated point: leave neighbourhood features at 0
      Eigen::Vector3d m = Eigen::Vector3d::Zero(), mc = Eigen::Vector3d::Zero(), mc2 = Eigen::Vector3d::Zero();
      for (int j : nb) {
        m += cloud.points[std::size_t(j)].cast<double>();
        const Eigen::Vector3d cj = cloud.colors[std::size_t(j)].cast<double>();
        mc += cj;
        mc2 += cj.cwiseProduct(cj);
      }
      m /= k, mc /= k, mc2 /= k;
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (int j : nb) {
        const Eigen::Vector3d d = cloud.points[std::size_t(j)].cast<double>() - m;
        cov.noalias() += d * d.transpose();
      }
      cov /= k;
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
      es.computeDirect(cov);
      const Eigen::Vector3d l = es.eigenvalues().cwiseMax(1e-12);  // ascending
      const double sum = l.sum();
      g[1] = float((l[2] - l[1]) / l[2]);
      g[2] = float((l[1] - l[0]) / l[2]);
      g[3] = float(l[0] / l[2]);
      g[4] = float(l[0] / sum);
      g[5] = float(std::cbrt(l[0] * l[1] * l[2]) / sum);
      g[6] = float(std::abs(es.eigenvectors().col(0).dot(nrm.cast<double>())));
      const Eigen::Vector3d var = (mc2 - mc.cwiseProduct(mc)).cwiseMax(0.0);
      g[7] = float(mc.x()), g[8] = float(mc.y()), g[9] = float(mc.z());
      g[10] = c.x() - g[7], g[11] = c.y() - g[8], g[12] = c.z() - g[9];
      g[13] = float(std::sqrt(var.sum() / 3));
      const Eigen::Vector3d off = p.cast<double>() - m;
      const double scale = std::sqrt(double(d2.back())) + 1e-9;  // neighbourhood radius
      g[14] = float(off.x() / scale), g[15] = float(off.y() / scale), g[16] = float(off.z() / scale);
    }
  }

  if (cfg.fpfh) {
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
  return X;
}

}  // namespace cropsight::pipeline
