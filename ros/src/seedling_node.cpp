#include "seedling_node.hpp"

#include <sensor_msgs/PointCloud2.h>
#include <vision_msgs/Detection3DArray.h>

#include <cmath>

#include "cloud_conversions.hpp"
#include "cropsight/core/error.hpp"
#include "ros_conversions.hpp"

namespace cropsight::ros_io {

bridge::StereoGeometry stereo_geometry(const sensor_msgs::CameraInfo& left, const sensor_msgs::CameraInfo& right,
                                       const std::string& left_topic, const std::string& right_topic) {
  if (left.width != right.width || left.height != right.height)
    throw Error(right_topic, "right camera_info size differs from the left one");
  if (left.width == 0 || left.height == 0) throw Error(left_topic, "camera_info has no image size");
  bridge::StereoGeometry g;
  g.width = int(left.width);
  g.height = int(left.height);
  g.f = left.P[0];
  g.cx = left.P[2];
  g.cy = left.P[6];
  g.cx_right = right.P[2];
  for (double v : {g.f, g.cx, g.cy, g.cx_right, right.P[0], right.P[3]})
    if (!std::isfinite(v)) throw Error(right_topic, "camera_info P holds a non-finite value");
  if (!(g.f > 0) || !(right.P[0] > 0))
    throw Error(left_topic, "camera_info P has a focal length <= 0 (not rectified?)");
  g.baseline = -right.P[3] / right.P[0];
  if (!(g.baseline > 0))
    throw Error(right_topic, "right camera_info P[3] gives no baseline (P[3] = -f * baseline must be < 0)");
  return g;
}

SeedlingNode::SeedlingNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
  const std::string preset = resolve_project_path(pnh_.param<std::string>("preset", "seedling"));
  queue_ = std::max(1, pnh_.param("queue_size", 5));
  hints_ = input_transport(pnh_);
  slop_s_ = pnh_.param("slop_s", 0.02);
  runner_ = std::make_unique<bridge::SeedlingRunner>(preset, read_set_param(pnh_));
  health_ = std::make_unique<InputHealth>(nh_, ros::this_node::getName());
  lazy_ = std::make_unique<LazyInputs>(
      pnh_.param("lazy", true), [this] { connect(); }, [this] { disconnect(); });
  det_pub_ = nh_.advertise<vision_msgs::Detection3DArray>("seedlings", 10, lazy_->callback(), lazy_->callback());
  points_pub_ = nh_.advertise<sensor_msgs::PointCloud2>("seedling_points", 2, lazy_->callback(), lazy_->callback());
  lazy_->add_output(&det_pub_);
  lazy_->add_output(&points_pub_);
  lazy_->update();
  ROS_INFO("cropsight seedling node: preset %s", preset.c_str());
}

void SeedlingNode::connect() {
  left_sub_.subscribe(nh_, "left/image_rect_color", queue_, hints_);
  right_sub_.subscribe(nh_, "right/image_rect_color", queue_, hints_);
  left_info_sub_.subscribe(nh_, "left/camera_info", queue_, hints_);
  right_info_sub_.subscribe(nh_, "right/camera_info", queue_, hints_);
  sync_ = std::make_unique<message_filters::Synchronizer<Policy>>(Policy(queue_), left_sub_, right_sub_, left_info_sub_,
                                                                  right_info_sub_);
  sync_->setMaxIntervalDuration(ros::Duration(slop_s_));
  sync_->registerCallback(&SeedlingNode::on_pair, this);
}

void SeedlingNode::disconnect() {
  left_sub_.unsubscribe();
  right_sub_.unsubscribe();
  left_info_sub_.unsubscribe();
  right_info_sub_.unsubscribe();
}

void SeedlingNode::on_pair(const sensor_msgs::ImageConstPtr& left, const sensor_msgs::ImageConstPtr& right,
                           const sensor_msgs::CameraInfoConstPtr& left_info,
                           const sensor_msgs::CameraInfoConstPtr& right_info) {
  bridge::RgbImage l, r;
  bridge::StereoGeometry g;
  std::string topic = right_info_sub_.getTopic();
  try {
    g = stereo_geometry(*left_info, *right_info, left_info_sub_.getTopic(), topic);
    bridge::CameraModel cam;
    cam.width = g.width;
    cam.height = g.height;
    topic = left_sub_.getTopic();
    l = {g.width, g.height, rgb_from_image(*left, cam, topic)};
    topic = right_sub_.getTopic();
    r = {g.width, g.height, rgb_from_image(*right, cam, topic)};
  } catch (const Error& e) {
    health_->skipped(topic, e.problem());
    return;
  }
  pipeline::seedling::FrameResult out;
  // The pipeline's own stage timer would leave out the copies; run_pipeline times the whole call.
  if (!run_pipeline(*health_, left_sub_.getTopic(), [&] { out = runner_->process(l, r, g, left_sub_.getTopic()); }))
    return;
  vision_msgs::Detection3DArray arr;
  arr.header = left->header;
  if (out.found) {
    vision_msgs::Detection3D d;
    d.header = left->header;
    vision_msgs::ObjectHypothesisWithPose hyp;
    hyp.id = 1;  // the seedling class
    hyp.score = 1;
    const Eigen::Vector3d c = out.centroid();
    hyp.pose.pose.position.x = c.x();
    hyp.pose.pose.position.y = c.y();
    hyp.pose.pose.position.z = c.z();
    hyp.pose.pose.orientation.w = 1;
    d.results.push_back(hyp);
    d.bbox.center = hyp.pose.pose;
    // The envelope box (length, width along the soil plane; height above it), m. Its axes are
    // those of the soil plane, not of the camera frame, so the orientation is left identity.
    d.bbox.size.x = out.envelope.length;
    d.bbox.size.y = out.envelope.width;
    d.bbox.size.z = out.envelope.height;
    arr.detections.push_back(d);
  }
  det_pub_.publish(arr);
  if (points_pub_.getNumSubscribers() > 0) {
    std::vector<float> xyz;
    xyz.reserve(3 * out.points.size());
    for (const Eigen::Vector3f& p : out.points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    sensor_msgs::PointCloud2 pc = make_cloud(xyz);
    pc.header = left->header;
    points_pub_.publish(pc);
  }
}

}  // namespace cropsight::ros_io
