#pragma once
// What every cropsight node shares: parameters under ~, the input-health counters published on
// `diagnostics` and logged with a throttled ROS_ERROR, lazy subscription, and the debug image.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cropsight/bridge/frame_buffers.hpp"

namespace cropsight::ros_io {

/// ~set as a list of "key=value" strings, or one string of them separated by ';'.
std::vector<std::string> read_set_param(const ros::NodeHandle& pnh);
/// The transport of a node's inputs: TCP with TCP_NODELAY unless ~tcp_nodelay is false. Without
/// it, Nagle's algorithm may hold a small message (a camera_info sent right after its image) until
/// the image's data is acknowledged, which showed as a latency tail (docs/ros.md, "Latency").
ros::TransportHints input_transport(const ros::NodeHandle& pnh);
/// A model or preset path: absolute, relative to the working directory, or as shipped
/// ("models/x.json") in the data folder of the install or build tree (core/install_paths.hpp).
std::string resolve_project_path(const std::string& path);

/// Counts the messages a node skipped, by problem, and the ones it processed. Not thread-safe:
/// call from the node's callback thread (nodes spin single-threaded).
class InputHealth {
 public:
  InputHealth(ros::NodeHandle& nh, std::string node_name);
  /// Logs "TOPIC: PROBLEM (message skipped)" at most every 5 s per topic and counts it.
  void skipped(const std::string& topic, const std::string& problem);
  /// One message processed, the pipeline taking `pipeline_ms` (wall clock) on it.
  void processed(double pipeline_ms);
  long skipped_total() const;
  long processed_total() const { return processed_; }
  /// Publishes a diagnostic_msgs/DiagnosticArray (also called by a 1 Hz timer): processed and
  /// skipped counts, each problem's count, and pipeline_ms_p50 / pipeline_ms_p99 over the last
  /// 1000 messages (the pipeline alone, without ROS transport and conversion).
  void publish();

 private:
  std::string name_;
  ros::Publisher pub_;
  ros::Timer timer_;
  std::map<std::string, long> counts_;  // "topic: problem" -> messages
  std::map<std::string, ros::Time> last_log_;
  long processed_ = 0;
  std::vector<double> pipeline_ms_;  // last kWindow messages, for the p50 / p99 on diagnostics
  std::size_t next_ = 0;
  static constexpr std::size_t kWindow = 1000;
};

/// The frame of one synchronised set: camera from `info` (depth_scale: metres per 16UC1 unit),
/// depth and colour when given (null: absent). On a malformed message: health.skipped(its topic,
/// the problem) and false.
struct InputTopics {
  std::string info, depth, color;
};
bool assemble_frame(const sensor_msgs::CameraInfo& info, const sensor_msgs::Image* depth,
                    const sensor_msgs::Image* color, double depth_scale, const InputTopics& topics, InputHealth& health,
                    bridge::FrameBuffers& frame);

/// Runs one pipeline call `run()`, records its wall time with health.processed(); an exception
/// (a frame the pipeline rejects) is health.skipped(topic, what) and false.
template <class F>
bool run_pipeline(InputHealth& health, const std::string& topic, F&& run) {
  try {
    const ros::WallTime start = ros::WallTime::now();
    run();
    health.processed((ros::WallTime::now() - start).toSec() * 1e3);
    return true;
  } catch (const std::exception& e) {
    health.skipped(topic, e.what());
    return false;
  }
}

/// Calls `connect` when the first subscriber of any of the node's outputs appears and `disconnect`
/// when the last one leaves (lazy subscription, as image_proc's nodelets do). With lazy = false
/// connect() is called at once.
class LazyInputs {
 public:
  LazyInputs(bool lazy, std::function<void()> connect, std::function<void()> disconnect);
  ros::SubscriberStatusCallback callback();  ///< give to every advertise()
  void add_output(const ros::Publisher* pub) { outputs_.push_back(pub); }
  void update();

 private:
  bool lazy_, connected_ = false;
  std::function<void()> connect_, disconnect_;
  std::vector<const ros::Publisher*> outputs_;
};

/// Draws box outlines (pixels, 2 px wide) in `colour` on an rgb8 image.
void draw_box(sensor_msgs::Image& rgb8, float x1, float y1, float x2, float y2, const std::uint8_t colour[3]);
/// A grey rgb8 image of the depth (near bright) for the debug image of depth-only input.
sensor_msgs::Image depth_preview(const std::vector<std::uint16_t>& depth, int width, int height);

}  // namespace cropsight::ros_io
