#pragma once
// Conversions between cropsight clouds and PCL point clouds. PCL types are only forward
// declared here so that including this header does not pull PCL in; callers that use these
// functions include the PCL headers themselves (<pcl/point_cloud.h>, <pcl/point_types.h>).
#include "cropsight/core/cloud.hpp"
#include "cropsight/core/organized_cloud.hpp"

namespace pcl {
struct PointXYZ;
struct PointXYZRGB;
struct Normal;
template <typename PointT>
class PointCloud;
}  // namespace pcl

namespace cropsight {

/// Organised clouds keep width×height; invalid points stay NaN and is_dense is false.
void to_pcl(const OrganizedCloud& in, pcl::PointCloud<pcl::PointXYZ>& out);
void to_pcl(const OrganizedCloud& in, pcl::PointCloud<pcl::PointXYZRGB>& out);  ///< black when no colour
void to_pcl(const Cloud& in, pcl::PointCloud<pcl::PointXYZ>& out);
void to_pcl(const Cloud& in, pcl::PointCloud<pcl::PointXYZRGB>& out);
/// Normals of an organised cloud (NaN where undefined); requires in.has_normals().
void normals_to_pcl(const OrganizedCloud& in, pcl::PointCloud<pcl::Normal>& out);

/// From PCL: an organised PCL cloud (height > 1) gives an OrganizedCloud of the same layout.
/// Throws Error("pcl cloud", ...) for an unorganised input.
OrganizedCloud organized_from_pcl(const pcl::PointCloud<pcl::PointXYZ>& in);
OrganizedCloud organized_from_pcl(const pcl::PointCloud<pcl::PointXYZRGB>& in);
Cloud cloud_from_pcl(const pcl::PointCloud<pcl::PointXYZ>& in);     ///< drops non-finite points
Cloud cloud_from_pcl(const pcl::PointCloud<pcl::PointXYZRGB>& in);  ///< drops non-finite points

}  // namespace cropsight
