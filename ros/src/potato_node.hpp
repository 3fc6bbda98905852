#pragma once
// The potato node: colour + aligned depth + camera_info → the harvest target
// (cropsight_msgs/HarvestTarget, the paper's Table 3.2 with a header) at ~rate Hz (default 3, the
// paper's; 0 = every frame), every frame's boxes (vision_msgs/Detection2DArray), a target marker,
// a debug image and input diagnostics. The pipeline is the library's pipeline::potato::Pipeline (through
// bridge::PotatoRunner): every frame is processed, since the target tracker needs them all; only
// the harvest message is throttled. One callback thread (ros::spin).
//
// Topics (relative, remap them): in  color/image_raw, depth/image_raw, depth/camera_info
//                                out harvest_target, detections, markers, debug_image, diagnostics
// Parameters (~): preset (potato), set, rate (3.0), use_depth (true), depth_scale (0.001),
// lazy (true), queue_size (5), exact_sync (false), slop_s (0.02); exact_sync as in broccoli_node.hpp.
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/sync_policies/exact_time.h>
#include <message_filters/synchronizer.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <memory>

#include "cropsight/bridge/potato_runner.hpp"
#include "node_support.hpp"

namespace cropsight::ros_io {

class PotatoNode {
 public:
  PotatoNode(ros::NodeHandle nh, ros::NodeHandle pnh);

 private:
  using Image = sensor_msgs::Image;
  using Info = sensor_msgs::CameraInfo;
  using RgbdPolicy = message_filters::sync_policies::ApproximateTime<Image, Image, Info>;
  using ColorPolicy = message_filters::sync_policies::ApproximateTime<Image, Info>;
  using RgbdExact = message_filters::sync_policies::ExactTime<Image, Image, Info>;
  using ColorExact = message_filters::sync_policies::ExactTime<Image, Info>;

  void connect();
  void disconnect();
  // message_filters' registerCallback takes member functions (boost::bind), not lambdas.
  void on_color_frame(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::CameraInfoConstPtr& info);
  void on_frame(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::ImageConstPtr& depth,
                const sensor_msgs::CameraInfoConstPtr& info);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<bridge::PotatoRunner> runner_;
  std::vector<std::string> class_names_;
  bool use_depth_ = true;
  double rate_hz_ = 3.0, depth_scale_ = 0.001, slop_s_ = 0.02;
  int queue_ = 5;
  ros::TransportHints hints_;
  int frame_ = 0;
  ros::Time last_target_;
  message_filters::Subscriber<Image> color_sub_, depth_sub_;
  message_filters::Subscriber<Info> info_sub_;
  std::unique_ptr<message_filters::Synchronizer<RgbdPolicy>> rgbd_sync_;
  std::unique_ptr<message_filters::Synchronizer<ColorPolicy>> color_sync_;
  std::unique_ptr<message_filters::Synchronizer<RgbdExact>> rgbd_exact_;
  std::unique_ptr<message_filters::Synchronizer<ColorExact>> color_exact_;
  bool exact_sync_ = false;
  ros::Publisher target_pub_, det_pub_, marker_pub_, debug_pub_;
  std::unique_ptr<InputHealth> health_;
  std::unique_ptr<LazyInputs> lazy_;
};

}  // namespace cropsight::ros_io
