#include "grape_node.hpp"

#include <cropsight_msgs/GrapeBunchArray.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/MarkerArray.h>

#include <climits>
#include <cmath>

#include "cloud_conversions.hpp"
#include "cropsight/core/error.hpp"
#include "ros_conversions.hpp"

namespace cropsight::ros_io {

namespace {
constexpr std::uint8_t kBunchColour[3] = {200, 40, 220};
constexpr std::uint8_t kPeduncleColour[3] = {240, 170, 40};
constexpr std::uint8_t kRoiColour[3] = {40, 220, 40};
}  // namespace

std::vector<bridge::GrapeInputBox> grape_boxes(const vision_msgs::Detection2DArray& msg, const std::string& topic) {
  std::vector<bridge::GrapeInputBox> out;
  for (std::size_t k = 0; k < msg.detections.size(); ++k) {
    const vision_msgs::Detection2D& d = msg.detections[k];
    const std::string which = "detection " + std::to_string(k);
    if (d.results.empty()) throw Error(topic, which + " has no result (its class)");
    const auto& b = d.bbox;
    for (double v : {b.center.x, b.center.y, b.size_x, b.size_y, d.results[0].score})
      if (!std::isfinite(v)) throw Error(topic, which + " holds a non-finite value");
    if (b.size_x < 0 || b.size_y < 0) throw Error(topic, which + " has a negative box size");
    if (std::abs(b.center.x) > 1e6 || std::abs(b.center.y) > 1e6 || b.size_x > 1e6 || b.size_y > 1e6)
      throw Error(topic, which + " has a box beyond any image");
    if (d.results[0].id < INT_MIN || d.results[0].id > INT_MAX)
      throw Error(topic, which + " has a class id beyond int");
    bridge::GrapeInputBox g;
    g.x1 = b.center.x - 0.5 * b.size_x;
    g.y1 = b.center.y - 0.5 * b.size_y;
    g.x2 = g.x1 + b.size_x;
    g.y2 = g.y1 + b.size_y;
    g.category = int(d.results[0].id);
    g.score = float(d.results[0].score);
    out.push_back(g);
  }
  return out;
}

GrapeNode::GrapeNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
  bridge::GrapeRunnerOptions o;
  // "" or "none": the boxes come on `detections` (a roslaunch arg cannot always be left empty).
  const std::string detector = pnh_.param<std::string>("detector", "detector-grape");
  if (!detector.empty() && detector != "none") o.detector = resolve_project_path(detector);
  o.segmenter = pnh_.param<std::string>("segmenter", "grape-best");
  // A segmenter model file is a path (resolved like the others); a preset is a name or a YAML.
  if (o.segmenter.find('/') != std::string::npos || o.segmenter.find('.') != std::string::npos)
    o.segmenter = resolve_project_path(o.segmenter);
  o.config = resolve_project_path(pnh_.param<std::string>("preset", ""));
  o.sets = read_set_param(pnh_);
  o.threads = pnh_.param("threads", 2);
  depth_scale_ = pnh_.param("depth_scale", 0.001);
  queue_ = std::max(1, pnh_.param("queue_size", 5));
  hints_ = input_transport(pnh_);
  slop_s_ = pnh_.param("slop_s", 0.02);
  exact_sync_ = pnh_.param("exact_sync", false);
  if (!(depth_scale_ > 0)) throw Error("~depth_scale", "must be > 0 (metres per 16UC1 unit)");
  if (o.threads < 1 || o.threads > 64) throw Error("~threads", "must be 1..64");
  runner_ = std::make_unique<bridge::GrapeRunner>(o);
  health_ = std::make_unique<InputHealth>(nh_, ros::this_node::getName());
  lazy_ = std::make_unique<LazyInputs>(
      pnh_.param("lazy", true), [this] { connect(); }, [this] { disconnect(); });
  bunches_pub_ = nh_.advertise<cropsight_msgs::GrapeBunchArray>("bunches", 10, lazy_->callback(), lazy_->callback());
  points_pub_ = nh_.advertise<sensor_msgs::PointCloud2>("bunch_points", 2, lazy_->callback(), lazy_->callback());
  cut_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("cut_points", 2, lazy_->callback(), lazy_->callback());
  debug_pub_ = nh_.advertise<sensor_msgs::Image>("debug_image", 1, lazy_->callback(), lazy_->callback());
  for (const ros::Publisher* p : {&bunches_pub_, &points_pub_, &cut_pub_, &debug_pub_}) lazy_->add_output(p);
  lazy_->update();
  ROS_INFO("cropsight grape node: boxes from %s, segmenter %s",
           runner_->has_detector() ? o.detector.c_str() : "the detections topic", runner_->segmenter_model().c_str());
}

void GrapeNode::connect() {
  color_sub_.subscribe(nh_, "color/image_raw", queue_, hints_);
  depth_sub_.subscribe(nh_, "depth/image_raw", queue_, hints_);
  info_sub_.subscribe(nh_, "depth/camera_info", queue_, hints_);
  const bool boxes = !runner_->has_detector();
  if (boxes) boxes_sub_.subscribe(nh_, "detections", queue_, hints_);
  if (exact_sync_ && boxes) {
    boxes_exact_ = std::make_unique<message_filters::Synchronizer<BoxesExact>>(BoxesExact(queue_), color_sub_,
                                                                               depth_sub_, info_sub_, boxes_sub_);
    boxes_exact_->registerCallback(&GrapeNode::on_frame_boxes, this);
  } else if (exact_sync_) {
    rgbd_exact_ = std::make_unique<message_filters::Synchronizer<RgbdExact>>(RgbdExact(queue_), color_sub_, depth_sub_,
                                                                             info_sub_);
    rgbd_exact_->registerCallback(&GrapeNode::on_frame, this);
  } else if (boxes) {
    boxes_sync_ = std::make_unique<message_filters::Synchronizer<BoxesPolicy>>(BoxesPolicy(queue_), color_sub_,
                                                                               depth_sub_, info_sub_, boxes_sub_);
    boxes_sync_->setMaxIntervalDuration(ros::Duration(slop_s_));
    boxes_sync_->registerCallback(&GrapeNode::on_frame_boxes, this);
  } else {
    rgbd_sync_ = std::make_unique<message_filters::Synchronizer<RgbdPolicy>>(RgbdPolicy(queue_), color_sub_, depth_sub_,
                                                                             info_sub_);
    rgbd_sync_->setMaxIntervalDuration(ros::Duration(slop_s_));
    rgbd_sync_->registerCallback(&GrapeNode::on_frame, this);
  }
}

void GrapeNode::disconnect() {
  color_sub_.unsubscribe();
  depth_sub_.unsubscribe();
  info_sub_.unsubscribe();
  boxes_sub_.unsubscribe();
}

void GrapeNode::on_frame(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::ImageConstPtr& depth,
                         const sensor_msgs::CameraInfoConstPtr& info) {
  on_frame_boxes(color, depth, info, nullptr);
}

void GrapeNode::on_frame_boxes(const sensor_msgs::ImageConstPtr& color, const sensor_msgs::ImageConstPtr& depth,
                               const sensor_msgs::CameraInfoConstPtr& info,
                               const vision_msgs::Detection2DArrayConstPtr& boxes) {
  bridge::FrameBuffers f;
  if (!assemble_frame(*info, depth.get(), color.get(), depth_scale_,
                      {info_sub_.getTopic(), depth_sub_.getTopic(), color_sub_.getTopic()}, *health_, f))
    return;
  std::vector<bridge::GrapeInputBox> given;
  if (boxes) {
    try {
      given = grape_boxes(*boxes, boxes_sub_.getTopic());
    } catch (const Error& e) {
      health_->skipped(boxes_sub_.getTopic(), e.problem());
      return;
    }
  }
  f.index = frame_;
  f.timestamp = color->header.stamp.toSec();
  pipeline::grape::FrameResult out;
  if (!run_pipeline(*health_, color_sub_.getTopic(),
                    [&] { out = boxes ? runner_->process(f, given) : runner_->process(f); }))
    return;
  ++frame_;
  publish(color->header, f, out);
}

// Long on purpose: the node's four outputs (bunches, labelled cloud, cut-point markers, debug image) from one result.
void GrapeNode::publish(const std_msgs::Header& header, const bridge::FrameBuffers& f,
                        const pipeline::grape::FrameResult& out) {
  cropsight_msgs::GrapeBunchArray arr;
  arr.header = header;
  for (const pipeline::grape::Bunch& b : out.bunches) {
    cropsight_msgs::GrapeBunch m;
    m.roi_x = b.roi.x;
    m.roi_y = b.roi.y;
    m.roi_width = b.roi.width;
    m.roi_height = b.roi.height;
    FlatCloud flat;
    append_cloud(b.cloud, flat);
    m.cloud = make_cloud(flat.xyz, b.cloud.has_colors() ? &flat.rgb : nullptr, &flat.labels);
    m.cloud.header = header;
    m.has_cut_point = b.cut_point.has_value();
    const pipeline::grape::CutPoint cut = b.cut_point.value_or(pipeline::grape::CutPoint{});
    m.cut_position.x = cut.position.x();
    m.cut_position.y = cut.position.y();
    m.cut_position.z = cut.position.z();
    m.cut_direction.x = cut.direction.x();
    m.cut_direction.y = cut.direction.y();
    m.cut_direction.z = cut.direction.z();
    m.cut_confidence = cut.confidence;
    arr.bunches.push_back(std::move(m));
  }
  bunches_pub_.publish(arr);

  if (points_pub_.getNumSubscribers() > 0) {
    // Every bunch in one cloud; the label field is the segmenter's label (bunches: see `bunches`).
    FlatCloud all;
    for (const pipeline::grape::Bunch& b : out.bunches) append_cloud(b.cloud, all);
    sensor_msgs::PointCloud2 pc = make_cloud(all.xyz, &all.rgb, &all.labels);
    pc.header = header;
    points_pub_.publish(pc);
  }
  if (cut_pub_.getNumSubscribers() > 0) {
    // An arrow per cut point, 5 cm along the peduncle's axis; DELETEALL first so that the markers
    // of bunches no longer seen disappear.
    visualization_msgs::MarkerArray markers;
    visualization_msgs::Marker clear;
    clear.header = header;
    clear.action = visualization_msgs::Marker::DELETEALL;
    markers.markers.push_back(clear);
    for (std::size_t k = 0; k < out.bunches.size(); ++k) {
      if (!out.bunches[k].cut_point) continue;
      const pipeline::grape::CutPoint& cut = *out.bunches[k].cut_point;
      visualization_msgs::Marker m;
      m.header = header;
      m.ns = "grape_cut_points";
      m.id = int(k);
      m.type = visualization_msgs::Marker::ARROW;
      m.action = visualization_msgs::Marker::ADD;
      geometry_msgs::Point p0, p1;
      p0.x = cut.position.x(), p0.y = cut.position.y(), p0.z = cut.position.z();
      p1.x = p0.x + 0.05 * cut.direction.x(), p1.y = p0.y + 0.05 * cut.direction.y();
      p1.z = p0.z + 0.05 * cut.direction.z();
      m.points = {p0, p1};
      m.pose.orientation.w = 1;
      m.scale.x = 0.005, m.scale.y = 0.01, m.scale.z = 0.01;
      m.color.r = 1.0f, m.color.g = 0.6f, m.color.a = 0.9f;
      markers.markers.push_back(m);
    }
    cut_pub_.publish(markers);
  }
  if (debug_pub_.getNumSubscribers() > 0) {
    sensor_msgs::Image im = image_from_rgb(f.rgb, f.camera.width, f.camera.height);
    im.header = header;
    for (const pipeline::grape::Detection& d : out.detections)
      draw_box(im, float(d.box.x), float(d.box.y), float(d.box.x + d.box.width - 1), float(d.box.y + d.box.height - 1),
               d.category == 2 ? kPeduncleColour : kBunchColour);
    for (const pipeline::grape::Bunch& b : out.bunches)
      draw_box(im, float(b.roi.x - 2), float(b.roi.y - 2), float(b.roi.x + b.roi.width + 1),
               float(b.roi.y + b.roi.height + 1), kRoiColour);
    debug_pub_.publish(im);
  }
}

}  // namespace cropsight::ros_io
