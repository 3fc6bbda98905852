#pragma once
// The grape node: colour + aligned depth + camera_info → per frame the grape bunches
// (cropsight_msgs/GrapeBunchArray: each bunch's ROI, its labelled PointCloud2 and its cut point),
// all bunches' points as one labelled PointCloud2 (for rviz), the cut points as arrow markers, a
// debug image and input diagnostics. The pipeline is the library's pipeline::grape::Pipeline (through
// bridge::GrapeRunner), as `cropsight detect grape` runs it. One callback thread (ros::spin).
//
// Boxes: the project's detector (~detector, a .onnx or .pt file), or — with ~detector none — the
// user's own detector's vision_msgs/Detection2DArray on `detections`, synchronised with the
// images (results[0].id is the COCO category: 1 bunch, 2 peduncle; the box is bbox centre ± size/2,
// pixels of the colour image).
//
// Topics (relative, remap them): in  color/image_raw, depth/image_raw, depth/camera_info,
//                                    [detections]
//                                out bunches, bunch_points, cut_points, debug_image, diagnostics
// Parameters (~): detector (detector-grape: its runtime is the preset's detector.backend, libtorch
// where the plugin is installed; a .onnx / .pt file; "" or none = boxes on `detections`), segmenter
// (grape-best: a preset or a model file), preset (grape-camera), set, threads (2), depth_scale
// (0.001 m per 16UC1 unit), lazy (true), queue_size (5), exact_sync (false), slop_s (0.02).
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/sync_policies/exact_time.h>
#include <message_filters/synchronizer.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <vision_msgs/Detection2DArray.h>

#include <memory>

#include "cropsight/bridge/grape_runner.hpp"
#include "node_support.hpp"

namespace cropsight::ros_io {

/// The boxes of a Detection2DArray as the grape pipeline's (category = results[0].id). Throws
/// Error(topic, problem) for a detection without a result, a non-finite or negative box, or a
/// category id outside int.
std::vector<bridge::GrapeInputBox> grape_boxes(const vision_msgs::Detection2DArray& msg, const std::string& topic);

class GrapeNode {
 public:
  /// Reads the parameters and loads the models; throws cropsight::Error on a bad model/preset.
  GrapeNode(ros::NodeHandle nh, ros::NodeHandle pnh);

 private:
  using Image = sensor_msgs::Image;
  using Info = sensor_msgs::CameraInfo;
  using Boxes = vision_msgs::Detection2DArray;
  using RgbdPolicy = message_filters::sync_policies::ApproximateTime<Image, Image, Info>;
  using BoxesPolicy = message_filters::sync_policies::ApproximateTime<Image, Image, Info, Boxes>;
  using RgbdExact = message_filters::sync_policies::ExactTime<Image, Image, Info>;
  using BoxesExact = message_filters::sync_policies::ExactTime<Image, Image, Info, Boxes>;

  void connect();
  void disconnect();
  // message_filters' registerCallback takes member functions (boost::bind), not lambdas.
  void on_frame(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::ImageConstPtr& depth,
                const sensor_msgs::CameraInfoConstPtr& info);
  void on_frame_boxes(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::ImageConstPtr& depth,
                      const sensor_msgs::CameraInfoConstPtr& info, const vision_msgs::Detection2DArrayConstPtr& boxes);
  void publish(const std_msgs::Header& header, const bridge::FrameBuffers& frame,
               const pipeline::grape::FrameResult& out);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<bridge::GrapeRunner> runner_;
  double depth_scale_ = 0.001, slop_s_ = 0.02;
  int queue_ = 5;
  ros::TransportHints hints_;
  int frame_ = 0;
  bool exact_sync_ = false;
  message_filters::Subscriber<Image> color_sub_, depth_sub_;
  message_filters::Subscriber<Info> info_sub_;
  message_filters::Subscriber<Boxes> boxes_sub_;
  std::unique_ptr<message_filters::Synchronizer<RgbdPolicy>> rgbd_sync_;
  std::unique_ptr<message_filters::Synchronizer<BoxesPolicy>> boxes_sync_;
  std::unique_ptr<message_filters::Synchronizer<RgbdExact>> rgbd_exact_;
  std::unique_ptr<message_filters::Synchronizer<BoxesExact>> boxes_exact_;
  ros::Publisher bunches_pub_, points_pub_, cut_pub_, debug_pub_;
  std::unique_ptr<InputHealth> health_;
  std::unique_ptr<LazyInputs> lazy_;
};

}  // namespace cropsight::ros_io
