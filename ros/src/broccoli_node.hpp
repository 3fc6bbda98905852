#pragma once
// The broccoli node: depth (+ colour) + camera_info → heads (vision_msgs/Detection3DArray), the
// online field map (visualization_msgs/MarkerArray), a debug image and input diagnostics. The
// pipeline is the library's pipeline::broccoli::Pipeline (through bridge::BroccoliRunner); the map CSV is
// written on shutdown when ~map_file is set. One callback thread (ros::spin).
//
// Topics (relative, remap them): in  depth/image_raw, depth/camera_info, [color/image_raw]
//                                    or, with ~input = cloud, points (an organised PointCloud2)
//                                out heads, field_map, debug_image, diagnostics
// Parameters (~): model, preset, set, track (true), input (depth | cloud), use_color (false),
// depth_scale (0.001 m per 16UC1 unit), map_file (""), lazy (true), queue_size (5), exact_sync
// (false), slop_s (0.02).
// Organised clouds (~input = cloud; depth_image_proc's point_cloud_xyz / xyzrgb, a driver's
// depth/points): one point per pixel in the camera optical frame. The node turns the cloud back
// into a depth image (z / depth_scale) with the intrinsics fitted to the points, so that the
// pipeline runs exactly as on the depth image (cloud_conversions.hpp); colour, with use_color,
// comes from the cloud's rgb field.
// Synchronisation: message_filters ApproximateTime within slop_s (default), or with
// exact_sync = true ExactTime (equal stamps only, as drivers stamp an image and its camera_info);
// the two measured the same latency (docs/ros.md).
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/sync_policies/exact_time.h>
#include <message_filters/synchronizer.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <memory>
#include <optional>

#include "cropsight/bridge/broccoli_runner.hpp"
#include "node_support.hpp"

namespace cropsight::ros_io {

class BroccoliNode {
 public:
  /// Reads the parameters and loads the model; throws cropsight::Error on a bad model/preset.
  BroccoliNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~BroccoliNode();  ///< writes ~map_file when set

 private:
  using Image = sensor_msgs::Image;
  using Info = sensor_msgs::CameraInfo;
  using DepthPolicy = message_filters::sync_policies::ApproximateTime<Image, Info>;
  using ColorPolicy = message_filters::sync_policies::ApproximateTime<Image, Info, Image>;
  using DepthExact = message_filters::sync_policies::ExactTime<Image, Info>;
  using ColorExact = message_filters::sync_policies::ExactTime<Image, Info, Image>;

  void connect();
  void disconnect();
  // message_filters' registerCallback takes member functions (boost::bind), not lambdas.
  void on_depth_frame(const sensor_msgs::ImageConstPtr& depth, const sensor_msgs::CameraInfoConstPtr& info);
  void on_frame(const sensor_msgs::ImageConstPtr& depth, const sensor_msgs::CameraInfoConstPtr& info,
                const sensor_msgs::ImageConstPtr& color);
  void on_cloud(const sensor_msgs::PointCloud2ConstPtr& cloud);
  // One assembled frame through the pipeline and out on every topic.
  void run_frame(bridge::FrameBuffers& f, const std_msgs::Header& header, const std::string& topic, bool color);
  void publish_map(const std_msgs::Header& header);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<bridge::BroccoliRunner> runner_;
  bool use_color_ = false, cloud_input_ = false;
  double depth_scale_ = 0.001, slop_s_ = 0.02;
  int queue_ = 5;
  ros::TransportHints hints_;
  std::string map_file_, field_frame_;
  int frame_ = 0;
  message_filters::Subscriber<Image> depth_sub_, color_sub_;
  message_filters::Subscriber<Info> info_sub_;
  ros::Subscriber cloud_sub_;
  std::unique_ptr<message_filters::Synchronizer<DepthPolicy>> depth_sync_;
  std::unique_ptr<message_filters::Synchronizer<ColorPolicy>> color_sync_;
  std::unique_ptr<message_filters::Synchronizer<DepthExact>> depth_exact_;
  std::unique_ptr<message_filters::Synchronizer<ColorExact>> color_exact_;
  bool exact_sync_ = false;
  ros::Publisher heads_pub_, map_pub_, debug_pub_;
  std::unique_ptr<InputHealth> health_;
  std::unique_ptr<LazyInputs> lazy_;
};

}  // namespace cropsight::ros_io
