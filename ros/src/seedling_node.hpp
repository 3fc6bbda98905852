#pragma once
// The seedling node: a rectified stereo pair (left and right images + their camera_info, as
// stereo_image_proc publishes them) → the seedling's envelope box (vision_msgs/Detection3DArray,
// empty when none is found), its points (sensor_msgs/PointCloud2, x y z float32, rectified
// left camera frame) and input diagnostics. The pipeline is the library's pipeline::seedling::Pipeline
// (through bridge::SeedlingRunner). One callback thread (ros::spin).
//
// Topics (relative, remap them): in  left/image_rect_color, right/image_rect_color,
//                                    left/camera_info, right/camera_info
//                                out seedlings, seedling_points, diagnostics
// Parameters (~): preset (seedling), set, lazy (true), queue_size (5), slop_s (0.02).
// The geometry comes from the two P matrices: f = P[0], cx = P[2], cy = P[6] (left),
// cx_right = P[2] and baseline = -P[3] / P[0] (right).
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/synchronizer.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <memory>

#include "cropsight/bridge/seedling_runner.hpp"
#include "node_support.hpp"

namespace cropsight::ros_io {

/// The rectified geometry of a stereo pair's camera_infos; throws Error(topic, ...) when they
/// disagree in size or the right P matrix holds no baseline.
bridge::StereoGeometry stereo_geometry(const sensor_msgs::CameraInfo& left, const sensor_msgs::CameraInfo& right,
                                       const std::string& left_topic, const std::string& right_topic);

class SeedlingNode {
 public:
  SeedlingNode(ros::NodeHandle nh, ros::NodeHandle pnh);

 private:
  using Image = sensor_msgs::Image;
  using Info = sensor_msgs::CameraInfo;
  using Policy = message_filters::sync_policies::ApproximateTime<Image, Image, Info, Info>;

  void connect();
  void disconnect();
  // message_filters' registerCallback takes member functions (boost::bind), not lambdas.
  void on_pair(const sensor_msgs::ImageConstPtr& left, const sensor_msgs::ImageConstPtr& right,
               const sensor_msgs::CameraInfoConstPtr& left_info, const sensor_msgs::CameraInfoConstPtr& right_info);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<bridge::SeedlingRunner> runner_;
  double slop_s_ = 0.02;
  int queue_ = 5;
  ros::TransportHints hints_;
  message_filters::Subscriber<Image> left_sub_, right_sub_;
  message_filters::Subscriber<Info> left_info_sub_, right_info_sub_;
  std::unique_ptr<message_filters::Synchronizer<Policy>> sync_;
  ros::Publisher det_pub_, points_pub_;
  std::unique_ptr<InputHealth> health_;
  std::unique_ptr<LazyInputs> lazy_;
};

}  // namespace cropsight::ros_io
