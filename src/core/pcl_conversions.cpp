#include "cropsight/core/pcl_conversions.hpp"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <limits>

#include "cropsight/core/error.hpp"

namespace cropsight {

namespace {
template <typename PointT>
void organized_xyz_to_pcl(const OrganizedCloud& in, pcl::PointCloud<PointT>& out) {
  out.width = std::uint32_t(in.width);
  out.height = std::uint32_t(in.height);
  out.points.resize(in.size());
  bool dense = true;
  for (std::size_t i = 0; i < in.size(); ++i) {
    auto& p = out.points[i];
    p.x = in.x[i];
    p.y = in.y[i];
    p.z = in.z[i];
    dense = dense && in.valid(i);
  }
  out.is_dense = dense;
}

template <typename PointT>
OrganizedCloud organized_from(const pcl::PointCloud<PointT>& in) {
  if (in.height <= 1) throw Error("pcl cloud", "expected an organised cloud (height > 1)");
  OrganizedCloud out(int(in.width), int(in.height));
  for (std::size_t i = 0; i < in.size(); ++i) {
    const auto& p = in.points[i];
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      out.x[i] = p.x;
      out.y[i] = p.y;
      out.z[i] = p.z;
    }
  }
  return out;
}
}  // namespace

void to_pcl(const OrganizedCloud& in, pcl::PointCloud<pcl::PointXYZ>& out) { organized_xyz_to_pcl(in, out); }

void to_pcl(const OrganizedCloud& in, pcl::PointCloud<pcl::PointXYZRGB>& out) {
  organized_xyz_to_pcl(in, out);
  for (std::size_t i = 0; i < in.size(); ++i) {
    auto& p = out.points[i];
    if (in.has_color()) {
      p.r = in.color[i].r;
      p.g = in.color[i].g;
      p.b = in.color[i].b;
    } else {
      p.r = p.g = p.b = 0;
    }
    p.a = 255;
  }
}

void to_pcl(const Cloud& in, pcl::PointCloud<pcl::PointXYZ>& out) {
  out.clear();
  out.points.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out.points[i].getVector3fMap() = in.points[i];
  out.width = std::uint32_t(in.size());
  out.height = 1;
  out.is_dense = true;
}

void to_pcl(const Cloud& in, pcl::PointCloud<pcl::PointXYZRGB>& out) {
  out.clear();
  out.points.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    auto& p = out.points[i];
    p.getVector3fMap() = in.points[i];
    if (in.has_colors()) {
      const Eigen::Vector3f c = (in.colors[i] * 255.0f).cwiseMax(0.0f).cwiseMin(255.0f);
      p.r = std::uint8_t(c.x() + 0.5f);
      p.g = std::uint8_t(c.y() + 0.5f);
      p.b = std::uint8_t(c.z() + 0.5f);
    }
    p.a = 255;
  }
  out.width = std::uint32_t(in.size());
  out.height = 1;
  out.is_dense = true;
}

void normals_to_pcl(const OrganizedCloud& in, pcl::PointCloud<pcl::Normal>& out) {
  if (!in.has_normals()) throw Error("normals_to_pcl", "cloud has no normals");
  out.width = std::uint32_t(in.width);
  out.height = std::uint32_t(in.height);
  out.points.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    auto& n = out.points[i];
    n.normal_x = in.nx[i];
    n.normal_y = in.ny[i];
    n.normal_z = in.nz[i];
    n.curvature = in.curvature.empty() ? std::numeric_limits<float>::quiet_NaN() : in.curvature[i];
  }
  out.is_dense = false;
}

OrganizedCloud organized_from_pcl(const pcl::PointCloud<pcl::PointXYZ>& in) { return organized_from(in); }

OrganizedCloud organized_from_pcl(const pcl::PointCloud<pcl::PointXYZRGB>& in) {
  OrganizedCloud out = organized_from(in);
  out.color.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out.color[i] = {in.points[i].r, in.points[i].g, in.points[i].b};
  return out;
}

Cloud cloud_from_pcl(const pcl::PointCloud<pcl::PointXYZ>& in) {
  Cloud out;
  out.points.reserve(in.size());
  for (const auto& p : in.points)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) out.points.emplace_back(p.x, p.y, p.z);
  return out;
}

Cloud cloud_from_pcl(const pcl::PointCloud<pcl::PointXYZRGB>& in) {
  Cloud out;
  for (const auto& p : in.points) {
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) continue;
    out.points.emplace_back(p.x, p.y, p.z);
    out.colors.emplace_back(p.r / 255.0f, p.g / 255.0f, p.b / 255.0f);
  }
  return out;
}

}  // namespace cropsight
