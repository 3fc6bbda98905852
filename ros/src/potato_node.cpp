#include "potato_node.hpp"

#include <cropsight_msgs/HarvestTarget.h>
#include <vision_msgs/Detection2DArray.h>
#include <visualization_msgs/MarkerArray.h>

#include "cropsight/core/error.hpp"
#include "ros_conversions.hpp"

namespace cropsight::ros_io {

namespace {
constexpr std::uint8_t kRipe[3] = {40, 220, 40}, kUnripe[3] = {240, 200, 40}, kTarget[3] = {255, 40, 40};

cropsight_msgs::HarvestTarget to_message(const pipeline::potato::HarvestTarget& t, const std_msgs::Header& header) {
  cropsight_msgs::HarvestTarget m;
  m.header = header;
  m.detection = t.detection;
  m.depth_ok = t.depth_ok;
  m.x = t.x;
  m.y = t.y;
  m.z = t.z;
  m.height = t.height;
  m.width = t.width;
  m.angle = t.angle;
  m.angle_ok = t.angle_ok;
  m.cut = t.cut;
  m.target_id = std::uint32_t(std::max(0, t.target_id));
  m.state = std::uint8_t(t.state);
  m.score = t.score;
  return m;
}
}  // namespace

PotatoNode::PotatoNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
  bridge::PotatoRunnerOptions o;
  o.preset = resolve_project_path(pnh_.param<std::string>("preset", "potato"));
  o.sets = read_set_param(pnh_);
  rate_hz_ = pnh_.param("rate", 3.0);
  use_depth_ = pnh_.param("use_depth", true);
  depth_scale_ = pnh_.param("depth_scale", 0.001);
  queue_ = std::max(1, pnh_.param("queue_size", 5));
  hints_ = input_transport(pnh_);
  slop_s_ = pnh_.param("slop_s", 0.02);
  exact_sync_ = pnh_.param("exact_sync", false);
  if (!(rate_hz_ >= 0)) throw Error("~rate", "must be >= 0 Hz (0 = every frame)");
  if (!(depth_scale_ > 0)) throw Error("~depth_scale", "must be > 0 (metres per 16UC1 unit)");
  runner_ = std::make_unique<bridge::PotatoRunner>(o);
  class_names_ = runner_->class_names();
  health_ = std::make_unique<InputHealth>(nh_, ros::this_node::getName());
  lazy_ = std::make_unique<LazyInputs>(
      pnh_.param("lazy", true), [this] { connect(); }, [this] { disconnect(); });
  target_pub_ =
      nh_.advertise<cropsight_msgs::HarvestTarget>("harvest_target", 10, lazy_->callback(), lazy_->callback());
  det_pub_ = nh_.advertise<vision_msgs::Detection2DArray>("detections", 10, lazy_->callback(), lazy_->callback());
  marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("markers", 1, lazy_->callback(), lazy_->callback());
  debug_pub_ = nh_.advertise<sensor_msgs::Image>("debug_image", 1, lazy_->callback(), lazy_->callback());
  for (const ros::Publisher* p : {&target_pub_, &det_pub_, &marker_pub_, &debug_pub_}) lazy_->add_output(p);
  lazy_->update();
  ROS_INFO("cropsight potato node: preset %s, harvest target at %s, depth %s", o.preset.c_str(),
           rate_hz_ > 0 ? (std::to_string(rate_hz_) + " Hz").c_str() : "every frame", use_depth_ ? "on" : "off");
}

void PotatoNode::connect() {
  color_sub_.subscribe(nh_, "color/image_raw", queue_, hints_);
  info_sub_.subscribe(nh_, use_depth_ ? "depth/camera_info" : "color/camera_info", queue_, hints_);
  if (use_depth_) depth_sub_.subscribe(nh_, "depth/image_raw", queue_, hints_);
  if (exact_sync_ && use_depth_) {
    rgbd_exact_ = std::make_unique<message_filters::Synchronizer<RgbdExact>>(RgbdExact(queue_), color_sub_, depth_sub_,
                                                                             info_sub_);
    rgbd_exact_->registerCallback(&PotatoNode::on_frame, this);
  } else if (exact_sync_) {
    color_exact_ =
        std::make_unique<message_filters::Synchronizer<ColorExact>>(ColorExact(queue_), color_sub_, info_sub_);
    color_exact_->registerCallback(&PotatoNode::on_color_frame, this);
  } else if (use_depth_) {
    rgbd_sync_ = std::make_unique<message_filters::Synchronizer<RgbdPolicy>>(RgbdPolicy(queue_), color_sub_, depth_sub_,
                                                                             info_sub_);
    rgbd_sync_->setMaxIntervalDuration(ros::Duration(slop_s_));
    rgbd_sync_->registerCallback(&PotatoNode::on_frame, this);
  } else {
    color_sync_ =
        std::make_unique<message_filters::Synchronizer<ColorPolicy>>(ColorPolicy(queue_), color_sub_, info_sub_);
    color_sync_->setMaxIntervalDuration(ros::Duration(slop_s_));
    color_sync_->registerCallback(&PotatoNode::on_color_frame, this);
  }
}

void PotatoNode::disconnect() {
  color_sub_.unsubscribe();
  depth_sub_.unsubscribe();
  info_sub_.unsubscribe();
}

void PotatoNode::on_color_frame(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::CameraInfoConstPtr& info) {
  on_frame(color, nullptr, info);
}

void PotatoNode::on_frame(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::ImageConstPtr& depth,
                          const sensor_msgs::CameraInfoConstPtr& info) {
  bridge::FrameBuffers f;
  if (!assemble_frame(*info, depth.get(), color.get(), depth_scale_,
                      {info_sub_.getTopic(), depth_sub_.getTopic(), color_sub_.getTopic()}, *health_, f))
    return;
  f.index = frame_;
  f.timestamp = color->header.stamp.toSec();
  pipeline::potato::FrameResult out;
  if (!run_pipeline(*health_, color_sub_.getTopic(), [&] { out = runner_->process(f); })) return;
  ++frame_;

  vision_msgs::Detection2DArray arr;
  arr.header = color->header;
  for (std::size_t k = 0; k < out.detections.size(); ++k) {
    const Detection2D& b = out.detections[k];
    vision_msgs::Detection2D d;
    d.header = color->header;
    vision_msgs::ObjectHypothesisWithPose hyp;
    hyp.id = b.class_id;
    hyp.score = b.score;
    // m, camera frame (0 when the depth was not usable)
    const measure::Position3D p = k < out.positions.size() ? out.positions[k] : measure::Position3D{};
    hyp.pose.pose.position.x = p.xyz.x();
    hyp.pose.pose.position.y = p.xyz.y();
    hyp.pose.pose.position.z = p.xyz.z();
    hyp.pose.pose.orientation.w = 1;
    d.results.push_back(hyp);
    d.bbox.center.x = 0.5 * (b.x1 + b.x2);
    d.bbox.center.y = 0.5 * (b.y1 + b.y2);
    d.bbox.size_x = b.x2 - b.x1;
    d.bbox.size_y = b.y2 - b.y1;
    arr.detections.push_back(d);
  }
  det_pub_.publish(arr);

  const ros::Time stamp = color->header.stamp;
  const bool due = rate_hz_ <= 0 || last_target_.isZero() || stamp < last_target_ ||
                   (stamp - last_target_).toSec() >= 1.0 / rate_hz_ - 1e-6;
  if (due) {
    target_pub_.publish(to_message(out.target, color->header));
    last_target_ = stamp;
  }
  if (marker_pub_.getNumSubscribers() > 0) {
    visualization_msgs::MarkerArray markers;
    visualization_msgs::Marker m;
    m.header = color->header;
    m.ns = "potato_target";
    m.id = 0;
    m.type = visualization_msgs::Marker::SPHERE;
    m.action = out.target.detection && out.target.depth_ok ? visualization_msgs::Marker::ADD
                                                           : visualization_msgs::Marker::DELETE;
    m.pose.position.x = out.target.x;
    m.pose.position.y = out.target.y;
    m.pose.position.z = out.target.z;
    m.pose.orientation.w = 1;
    m.scale.x = m.scale.y = m.scale.z = std::max(0.02f, std::max(out.target.width, out.target.height));
    m.color.r = 1.0f;
    m.color.a = 0.7f;
    markers.markers.push_back(m);
    marker_pub_.publish(markers);
  }
  if (debug_pub_.getNumSubscribers() > 0) {
    sensor_msgs::Image im = image_from_rgb(f.rgb, f.camera.width, f.camera.height);
    im.header = color->header;
    for (std::size_t k = 0; k < out.detections.size(); ++k) {
      const Detection2D& b = out.detections[k];
      draw_box(im, b.x1, b.y1, b.x2, b.y2, k < out.ripe.size() && out.ripe[k] ? kRipe : kUnripe);
    }
    if (out.target.detection)
      draw_box(im, out.target.box.x1 - 3, out.target.box.y1 - 3, out.target.box.x2 + 3, out.target.box.y2 + 3, kTarget);
    debug_pub_.publish(im);
  }
}

}  // namespace cropsight::ros_io
