#include "node_support.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/core/install_paths.hpp"
#include "cropsight/core/statistics.hpp"
#include "ros_conversions.hpp"

namespace fs = std::filesystem;

namespace cropsight::ros_io {

std::vector<std::string> read_set_param(const ros::NodeHandle& pnh) {
  std::vector<std::string> sets;
  if (pnh.getParam("set", sets)) return sets;
  std::string text;
  if (pnh.getParam("set", text)) {
    std::stringstream ss(text);
    for (std::string part; std::getline(ss, part, ';');)
      if (!part.empty()) sets.push_back(part);
  }
  return sets;
}

ros::TransportHints input_transport(const ros::NodeHandle& pnh) {
  ros::TransportHints hints;
  return pnh.param("tcp_nodelay", true) ? hints.tcpNoDelay() : hints;
}

std::string resolve_project_path(const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute() || fs::exists(path)) return path;
  // "models/x.json" and "configs/x.yaml" as shipped: in the data folder of the install or build
  // tree the node runs from (core/install_paths.hpp), never the source tree.
  const fs::path data = cropsight::data_dir();
  const fs::path shipped = data.empty() ? fs::path(path) : data / path;
  return fs::exists(shipped) ? shipped.string() : path;
}

InputHealth::InputHealth(ros::NodeHandle& nh, std::string node_name) : name_(std::move(node_name)) {
  pub_ = nh.advertise<diagnostic_msgs::DiagnosticArray>("diagnostics", 1);
  timer_ = nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { publish(); });
}

void InputHealth::skipped(const std::string& topic, const std::string& problem) {
  ++counts_[topic + ": " + problem];
  const ros::Time now = ros::Time::now();
  auto it = last_log_.find(topic);
  if (it == last_log_.end() || (now - it->second).toSec() >= 5.0 || now < it->second) {
    ROS_ERROR("%s: %s (message skipped)", topic.c_str(), problem.c_str());
    last_log_[topic] = now;
  }
}

void InputHealth::processed(double pipeline_ms) {
  ++processed_;
  if (pipeline_ms_.size() < kWindow) {
    pipeline_ms_.push_back(pipeline_ms);
  } else {
    pipeline_ms_[next_] = pipeline_ms;
    next_ = (next_ + 1) % kWindow;
  }
}

namespace {
// 0 before the first frame: a diagnostics value a monitor can plot.
double percentile(const std::vector<double>& v, double q) { return v.empty() ? 0.0 : quantile(v, q); }
}  // namespace

long InputHealth::skipped_total() const {
  long n = 0;
  for (const auto& [k, v] : counts_) n += v;
  return n;
}

void InputHealth::publish() {
  diagnostic_msgs::DiagnosticArray arr;
  arr.header.stamp = ros::Time::now();
  diagnostic_msgs::DiagnosticStatus st;
  st.name = name_ + ": input";
  st.hardware_id = name_;
  const long bad = skipped_total();
  st.level = bad == 0 ? diagnostic_msgs::DiagnosticStatus::OK : diagnostic_msgs::DiagnosticStatus::WARN;
  st.message = bad == 0 ? "all input processed" : std::to_string(bad) + " messages skipped";
  diagnostic_msgs::KeyValue kv;
  kv.key = "processed";
  kv.value = std::to_string(processed_);
  st.values.push_back(kv);
  kv.key = "skipped";
  kv.value = std::to_string(bad);
  st.values.push_back(kv);
  kv.key = "pipeline_ms_p50";
  kv.value = std::to_string(percentile(pipeline_ms_, 0.5));
  st.values.push_back(kv);
  kv.key = "pipeline_ms_p99";
  kv.value = std::to_string(percentile(pipeline_ms_, 0.99));
  st.values.push_back(kv);
  for (const auto& [problem, n] : counts_) {
    kv.key = problem;
    kv.value = std::to_string(n);
    st.values.push_back(kv);
  }
  arr.status.push_back(st);
  pub_.publish(arr);
}

bool assemble_frame(const sensor_msgs::CameraInfo& info, const sensor_msgs::Image* depth,
                    const sensor_msgs::Image* color, double depth_scale, const InputTopics& topics, InputHealth& health,
                    bridge::FrameBuffers& frame) {
  const std::string* topic = &topics.info;
  try {
    frame.camera = camera_from_info(info, depth_scale, topics.info);
    if (depth) {
      topic = &topics.depth;
      frame.depth = depth_from_image(*depth, frame.camera, topics.depth);
    }
    if (color) {
      topic = &topics.color;
      frame.rgb = rgb_from_image(*color, frame.camera, topics.color);
    }
  } catch (const Error& e) {
    health.skipped(*topic, e.problem());
    return false;
  }
  return true;
}

LazyInputs::LazyInputs(bool lazy, std::function<void()> connect, std::function<void()> disconnect)
    : lazy_(lazy), connect_(std::move(connect)), disconnect_(std::move(disconnect)) {}

ros::SubscriberStatusCallback LazyInputs::callback() {
  return [this](const ros::SingleSubscriberPublisher&) { update(); };
}

void LazyInputs::update() {
  bool wanted = !lazy_;
  for (const ros::Publisher* p : outputs_) wanted = wanted || (*p && p->getNumSubscribers() > 0);
  if (wanted && !connected_) {
    connect_();
    connected_ = true;
  } else if (!wanted && connected_) {
    disconnect_();
    connected_ = false;
  }
}

void draw_box(sensor_msgs::Image& im, float x1, float y1, float x2, float y2, const std::uint8_t colour[3]) {
  const int w = int(im.width), h = int(im.height);
  auto put = [&](int u, int v) {
    if (u < 0 || v < 0 || u >= w || v >= h) return;
    std::uint8_t* p = im.data.data() + std::size_t(v) * im.step + 3 * std::size_t(u);
    p[0] = colour[0];
    p[1] = colour[1];
    p[2] = colour[2];
  };
  const int u1 = int(x1), v1 = int(y1), u2 = int(x2), v2 = int(y2);
  for (int t = 0; t < 2; ++t) {
    for (int u = u1; u <= u2; ++u) put(u, v1 + t), put(u, v2 - t);
    for (int v = v1; v <= v2; ++v) put(u1 + t, v), put(u2 - t, v);
  }
}

sensor_msgs::Image depth_preview(const std::vector<std::uint16_t>& depth, int width, int height) {
  sensor_msgs::Image im;
  im.width = std::uint32_t(width);
  im.height = std::uint32_t(height);
  im.encoding = "rgb8";
  im.step = std::uint32_t(width) * 3;
  im.data.assign(std::size_t(width) * std::size_t(height) * 3, 0);
  std::uint16_t lo = 0xffff, hi = 0;
  for (std::uint16_t d : depth)
    if (d) lo = std::min(lo, d), hi = std::max(hi, d);
  const double span = hi > lo ? double(hi - lo) : 1.0;
  for (std::size_t i = 0; i < depth.size(); ++i)
    if (depth[i]) {
      const auto g = std::uint8_t(255.0 - 200.0 * (depth[i] - lo) / span);
      im.data[3 * i] = im.data[3 * i + 1] = im.data[3 * i + 2] = g;
    }
  return im;
}

}  // namespace cropsight::ros_io
