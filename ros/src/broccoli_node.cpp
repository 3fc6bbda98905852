#include "broccoli_node.hpp"

#include <vision_msgs/Detection3DArray.h>
#include <visualization_msgs/MarkerArray.h>

#include "cloud_conversions.hpp"
#include "cropsight/core/error.hpp"
#include "ros_conversions.hpp"

namespace cropsight::ros_io {

namespace {
constexpr std::uint8_t kHeadColour[3] = {255, 40, 40};
}

BroccoliNode::BroccoliNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
  bridge::BroccoliRunnerOptions o;
  o.model = resolve_project_path(pnh_.param<std::string>("model", "models/broccoli-oes-general.json"));
  o.preset = resolve_project_path(pnh_.param<std::string>("preset", ""));
  o.sets = read_set_param(pnh_);
  o.track = pnh_.param("track", true);
  use_color_ = pnh_.param("use_color", false);
  const std::string input = pnh_.param<std::string>("input", "depth");
  if (input != "depth" && input != "cloud") throw Error("~input", "must be depth or cloud, got '" + input + "'");
  cloud_input_ = input == "cloud";
  depth_scale_ = pnh_.param("depth_scale", 0.001);
  map_file_ = pnh_.param<std::string>("map_file", "");
  field_frame_ = pnh_.param<std::string>("field_frame", "field");
  queue_ = std::max(1, pnh_.param("queue_size", 5));
  hints_ = input_transport(pnh_);
  slop_s_ = pnh_.param("slop_s", 0.02);
  exact_sync_ = pnh_.param("exact_sync", false);
  if (!(depth_scale_ > 0)) throw Error("~depth_scale", "must be > 0 (metres per 16UC1 unit)");
  runner_ = std::make_unique<bridge::BroccoliRunner>(o);
  health_ = std::make_unique<InputHealth>(nh_, ros::this_node::getName());
  lazy_ = std::make_unique<LazyInputs>(
      pnh_.param("lazy", true), [this] { connect(); }, [this] { disconnect(); });
  heads_pub_ = nh_.advertise<vision_msgs::Detection3DArray>("heads", 10, lazy_->callback(), lazy_->callback());
  map_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("field_map", 1, lazy_->callback(), lazy_->callback());
  debug_pub_ = nh_.advertise<sensor_msgs::Image>("debug_image", 1, lazy_->callback(), lazy_->callback());
  lazy_->add_output(&heads_pub_);
  lazy_->add_output(&map_pub_);
  lazy_->add_output(&debug_pub_);
  lazy_->update();
  ROS_INFO("cropsight broccoli node: model %s (%s), input %s, tracking %s, colour %s", o.model.c_str(),
           runner_->pipeline_name().c_str(), input.c_str(), o.track ? "on" : "off", use_color_ ? "on" : "off");
}

BroccoliNode::~BroccoliNode() {
  if (map_file_.empty() || !runner_->tracking()) return;
  try {
    runner_->finish_and_write_map(map_file_);
    ROS_INFO("cropsight broccoli node: field map written to %s", map_file_.c_str());
  } catch (const std::exception& e) {
    ROS_ERROR("cropsight broccoli node: %s", e.what());
  }
}

void BroccoliNode::connect() {
  if (cloud_input_) {
    cloud_sub_ = nh_.subscribe("points", std::uint32_t(queue_), &BroccoliNode::on_cloud, this, hints_);
    return;
  }
  depth_sub_.subscribe(nh_, "depth/image_raw", queue_, hints_);
  info_sub_.subscribe(nh_, "depth/camera_info", queue_, hints_);
  if (exact_sync_) {
    if (use_color_) {
      color_sub_.subscribe(nh_, "color/image_raw", queue_, hints_);
      color_exact_ = std::make_unique<message_filters::Synchronizer<ColorExact>>(ColorExact(queue_), depth_sub_,
                                                                                 info_sub_, color_sub_);
      color_exact_->registerCallback(&BroccoliNode::on_frame, this);
    } else {
      depth_exact_ =
          std::make_unique<message_filters::Synchronizer<DepthExact>>(DepthExact(queue_), depth_sub_, info_sub_);
      depth_exact_->registerCallback(&BroccoliNode::on_depth_frame, this);
    }
  } else if (use_color_) {
    color_sub_.subscribe(nh_, "color/image_raw", queue_, hints_);
    color_sync_ = std::make_unique<message_filters::Synchronizer<ColorPolicy>>(ColorPolicy(queue_), depth_sub_,
                                                                               info_sub_, color_sub_);
    color_sync_->setMaxIntervalDuration(ros::Duration(slop_s_));
    color_sync_->registerCallback(&BroccoliNode::on_frame, this);
  } else {
    depth_sync_ =
        std::make_unique<message_filters::Synchronizer<DepthPolicy>>(DepthPolicy(queue_), depth_sub_, info_sub_);
    depth_sync_->setMaxIntervalDuration(ros::Duration(slop_s_));
    depth_sync_->registerCallback(&BroccoliNode::on_depth_frame, this);
  }
}

void BroccoliNode::disconnect() {
  cloud_sub_.shutdown();
  depth_sub_.unsubscribe();
  info_sub_.unsubscribe();
  color_sub_.unsubscribe();
}

void BroccoliNode::on_depth_frame(const sensor_msgs::ImageConstPtr& depth,
                                  const sensor_msgs::CameraInfoConstPtr& info) {
  on_frame(depth, info, nullptr);
}

void BroccoliNode::on_frame(const sensor_msgs::ImageConstPtr& depth, const sensor_msgs::CameraInfoConstPtr& info,
                            const sensor_msgs::ImageConstPtr& color) {
  bridge::FrameBuffers f;
  if (!assemble_frame(*info, depth.get(), color.get(), depth_scale_,
                      {info_sub_.getTopic(), depth_sub_.getTopic(), color_sub_.getTopic()}, *health_, f))
    return;
  run_frame(f, depth->header, depth_sub_.getTopic(), color != nullptr);
}

void BroccoliNode::on_cloud(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  const std::string topic = cloud_sub_.getTopic();
  bridge::FrameBuffers f;
  try {
    f = frame_from_organised_cloud(*cloud, depth_scale_, use_color_, topic);
  } catch (const Error& e) {
    health_->skipped(topic, e.problem());
    return;
  }
  run_frame(f, cloud->header, topic, use_color_);
}

void BroccoliNode::run_frame(bridge::FrameBuffers& f, const std_msgs::Header& header, const std::string& topic,
                             bool color) {
  f.index = frame_;
  f.timestamp = header.stamp.toSec();
  pipeline::broccoli::FrameResult out;
  if (!run_pipeline(*health_, topic, [&] { out = runner_->process(f); })) return;
  ++frame_;

  vision_msgs::Detection3DArray arr;
  arr.header = header;
  for (const Detection& h : out.detections) {
    vision_msgs::Detection3D d;
    d.header = header;
    vision_msgs::ObjectHypothesisWithPose hyp;
    hyp.id = 1;  // the broccoli head class
    hyp.score = h.score;
    hyp.pose.pose.position.x = h.centroid.x();
    hyp.pose.pose.position.y = h.centroid.y();
    hyp.pose.pose.position.z = h.centroid.z();
    hyp.pose.pose.orientation.w = 1;
    d.results.push_back(hyp);
    d.bbox.center = hyp.pose.pose;
    d.bbox.size.x = d.bbox.size.y = h.size_m;  // diameter; 0 = not measured (cut by the border)
    d.bbox.size.z = 0;
    arr.detections.push_back(d);
  }
  heads_pub_.publish(arr);
  if (map_pub_.getNumSubscribers() > 0) publish_map(header);
  if (debug_pub_.getNumSubscribers() > 0) {
    sensor_msgs::Image im = color ? image_from_rgb(f.rgb, f.camera.width, f.camera.height)
                                  : depth_preview(f.depth, f.camera.width, f.camera.height);
    im.header = header;
    for (const Detection& h : out.detections)
      draw_box(im, h.box.x, h.box.y, h.box.x + h.box.width - 1, h.box.y + h.box.height - 1, kHeadColour);
    debug_pub_.publish(im);
  }
}

void BroccoliNode::publish_map(const std_msgs::Header& header) {
  // The field map in the field frame of the temporal filter (its origin: the first camera
  // position); markers are spheres of the head diameter, ids the map's head ids.
  visualization_msgs::MarkerArray arr;
  visualization_msgs::Marker clear;
  clear.action = visualization_msgs::Marker::DELETEALL;
  arr.markers.push_back(clear);
  for (const tracking::TrackedHead& h : runner_->current_map()) {
    visualization_msgs::Marker m;
    m.header.stamp = header.stamp;
    m.header.frame_id = field_frame_;
    m.ns = "broccoli_heads";
    m.id = h.id;
    m.type = visualization_msgs::Marker::SPHERE;
    m.action = visualization_msgs::Marker::ADD;
    m.pose.position.x = h.position.x();
    m.pose.position.y = h.position.y();
    m.pose.position.z = h.position.z();
    m.pose.orientation.w = 1;
    const double d = h.diameter_mm > 0 ? h.diameter_mm / 1000.0 : 0.05;
    m.scale.x = m.scale.y = m.scale.z = d;
    m.color.r = h.harvestable ? 0.1f : 0.9f;
    m.color.g = h.harvestable ? 0.9f : 0.6f;
    m.color.b = 0.1f;
    m.color.a = 0.8f;
    arr.markers.push_back(m);
  }
  map_pub_.publish(arr);
}

}  // namespace cropsight::ros_io
