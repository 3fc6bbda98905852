#include "cropsight/pipeline/broccoli/pcl_reference.hpp"

#include <pcl/features/integral_image_normal.h>
#include <pcl/features/vfh.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight::pipeline::broccoli {

struct PclReferencePipeline::Impl {
  DetectorConfig cfg;
  std::shared_ptr<const learning::Model> model;
  StageTimer timer;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud{new pcl::PointCloud<pcl::PointXYZ>};
  pcl::PointCloud<pcl::Normal>::Ptr normals{new pcl::PointCloud<pcl::Normal>};
  std::vector<std::vector<int>> clusters;
  std::vector<float> scores, feature, scratch;
};

namespace {
using PclCloud = pcl::PointCloud<pcl::PointXYZ>;
using PclNormals = pcl::PointCloud<pcl::Normal>;

// Organised cloud with the depth-range filter applied in place (NaN = filtered / no return);
// returns the indices of the points kept.
pcl::Indices organised_cloud(const RgbdFrame& frame, const geometry::DepthRangeConfig& depth, PclCloud& cloud) {
  const int w = frame.depth.width, h = frame.depth.height;
  pcl::Indices valid;
  cloud.width = std::uint32_t(w);
  cloud.height = std::uint32_t(h);
  cloud.is_dense = false;
  cloud.points.resize(std::size_t(w) * std::size_t(h));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto& cam = frame.camera;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const std::size_t i = std::size_t(v) * std::size_t(w) + std::size_t(u);
      const float z = float(frame.depth.data[i]) * float(cam.depth_scale);
      pcl::PointXYZ& p = cloud[i];
      if (frame.depth.data[i] == 0 || z < depth.min_depth || z > depth.max_depth) {
        p.x = p.y = p.z = nan;
      } else {
        p.x = float((u - cam.cx) / cam.fx) * z;
        p.y = float((v - cam.cy) / cam.fy) * z;
        p.z = z;
        valid.push_back(int(i));
      }
    }
  return valid;
}

void integral_normals(const DetectorConfig& cfg, const PclCloud::Ptr& cloud, PclNormals& normals) {
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
  ne.setNormalEstimationMethod(ne.COVARIANCE_MATRIX);
  ne.setMaxDepthChangeFactor(cfg.normals.max_depth_change_factor);
  ne.setNormalSmoothingSize(cfg.normals.normal_smoothing_size);
  ne.setInputCloud(cloud);
  ne.compute(normals);
}

// The points of `valid` that survive the statistical outlier filter.
pcl::IndicesPtr remove_outliers(const DetectorConfig& cfg, const PclCloud::Ptr& cloud, pcl::Indices valid) {
  pcl::IndicesPtr kept(new pcl::Indices);
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
  sor.setInputCloud(cloud);
  sor.setIndices(pcl::IndicesPtr(new pcl::Indices(std::move(valid))));
  sor.setMeanK(cfg.outliers.sor.mean_k);
  sor.setStddevMulThresh(cfg.outliers.sor.std_mul);
  sor.filter(*kept);
  return kept;
}

std::vector<pcl::PointIndices> euclidean_clusters(const DetectorConfig& cfg, const PclCloud::Ptr& cloud,
                                                  const pcl::IndicesPtr& kept) {
  std::vector<pcl::PointIndices> found;
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(cloud, kept);
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
  ec.setClusterTolerance(cfg.fec.tolerance);
  ec.setMinClusterSize(cfg.fec.min_size);
  ec.setMaxClusterSize(cfg.fec.max_size);
  ec.setSearchMethod(tree);
  ec.setInputCloud(cloud);
  ec.setIndices(kept);
  ec.extract(found);
  return found;
}

// VFH of each cluster (308 zeros for a cluster with fewer than two defined normals); `clusters`
// receives each cluster's sorted indices.
std::vector<std::vector<float>> vfh_histograms(const PclCloud::Ptr& cloud, const PclNormals::Ptr& normals,
                                               const std::vector<pcl::PointIndices>& found,
                                               std::vector<std::vector<int>>& clusters) {
  std::vector<std::vector<float>> hists(found.size());
  pcl::VFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::VFHSignature308> vfh;
  vfh.setInputCloud(cloud);
  vfh.setInputNormals(normals);
  vfh.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  pcl::PointCloud<pcl::VFHSignature308> sig;
  for (std::size_t k = 0; k < found.size(); ++k) {
    // Points whose normal is undefined (next to depth changes) would put NaN into VFH's bins.
    pcl::IndicesPtr idx(new pcl::Indices);
    for (int i : found[k].indices)
      if (std::isfinite((*normals)[std::size_t(i)].normal_x)) idx->push_back(i);
    clusters[k].assign(found[k].indices.begin(), found[k].indices.end());
    std::sort(clusters[k].begin(), clusters[k].end());
    hists[k].assign(308, 0.0f);
    if (idx->size() < 2) continue;
    vfh.setIndices(idx);
    vfh.compute(sig);
    std::copy(sig[0].histogram, sig[0].histogram + 308, hists[k].begin());
  }
  return hists;
}
}  // namespace

PclReferencePipeline::PclReferencePipeline(const DetectorConfig& cfg, std::shared_ptr<const learning::Model> model,
                                           const std::string& where)
    : impl_(std::make_unique<Impl>()) {
  cfg.validate("config");
  if (!model) throw Error(where, "the PCL reference pipeline needs a model");
  if (model->info.features != std::vector<std::string>{"vfh"} || model->info.feature_dim != 308)
    throw Error(where, "the PCL reference pipeline computes VFH only; this model uses other features");
  impl_->cfg = cfg;
  impl_->model = std::move(model);
}

PclReferencePipeline::~PclReferencePipeline() = default;

const std::vector<std::vector<int>>& PclReferencePipeline::clusters() const { return impl_->clusters; }
const std::vector<float>& PclReferencePipeline::scores() const { return impl_->scores; }
StageTimer& PclReferencePipeline::timer() { return impl_->timer; }

std::size_t PclReferencePipeline::process(const RgbdFrame& frame) {
  Impl& m = *impl_;
  const DetectorConfig& cfg = m.cfg;
  pcl::Indices valid;
  {
    auto t = m.timer.scope("cloud");
    valid = organised_cloud(frame, cfg.depth, *m.cloud);
  }
  {
    auto t = m.timer.scope("normals");
    integral_normals(cfg, m.cloud, *m.normals);
  }
  pcl::IndicesPtr kept;
  if (cfg.outliers.enabled) {
    auto t = m.timer.scope("outliers");
    kept = remove_outliers(cfg, m.cloud, std::move(valid));
  } else {
    kept.reset(new pcl::Indices(std::move(valid)));
  }
  std::vector<pcl::PointIndices> found;
  {
    auto t = m.timer.scope("clustering");
    found = euclidean_clusters(cfg, m.cloud, kept);
  }
  m.clusters.resize(found.size());
  m.scores.resize(found.size());
  std::vector<std::vector<float>> hists;
  {
    auto t = m.timer.scope("features");
    hists = vfh_histograms(m.cloud, m.normals, found, m.clusters);
  }
  {
    auto t = m.timer.scope("classify");
    for (std::size_t k = 0; k < found.size(); ++k) m.scores[k] = m.model->score(hists[k], m.scratch);
  }
  return found.size();
}

}  // namespace cropsight::pipeline::broccoli
