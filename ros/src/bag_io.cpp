#include "cropsight_ros/bag_io.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include "bag_check.hpp"
#include "cropsight/bridge/sequence_io.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/output.hpp"
#include "ros_conversions.hpp"

namespace fs = std::filesystem;

namespace cropsight::ros_io {

namespace {

// rosbag throws its own exceptions (and pluginlib's when the encryptor plugin cannot be loaded);
// the CLI's contract is one line naming the file.
template <class F>
auto with_bag_errors(const std::string& bag, const std::string& failure, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const rosbag::BagException& e) {
    throw Error(bag, failure + ": " + e.what());
  } catch (const std::exception& e) {
    const std::string what = e.what();
    if (what.find("plugin") != std::string::npos || what.find("class_loader") != std::string::npos)
      throw Error(bag, "rosbag could not load its encryptor plugin (" + what +
                           "); is Debian's librosbag-storage4d installed with its plugins?");
    throw Error(bag, what);
  }
}

// m.instantiate<T>() after checking the message's lengths (check_message): roscpp's
// deserialiser allocates the lengths it reads before it checks them.
template <class T>
boost::shared_ptr<T> instantiate_checked(const rosbag::MessageInstance& m, const std::string& bag) {
  if (m.getDataType() != ros::message_traits::datatype<T>()) return nullptr;  // the caller names the topic
  std::vector<std::uint8_t> bytes(m.size());
  ros::serialization::OStream out(bytes.data(), std::uint32_t(bytes.size()));
  m.write(out);
  detail::check_message(m.getDataType(), bytes.data(), bytes.size(), bag);
  return m.instantiate<T>();
}

std_msgs::Header header_at(const ros::Time& t, const std::string& frame_id, std::uint32_t seq) {
  std_msgs::Header h;
  h.stamp = t;
  h.frame_id = frame_id;
  h.seq = seq;
  return h;
}

}  // namespace

BagExportSummary export_sequence_bag(const BagExportOptions& o) {
  // The project's one output rule (plain C++17): never an input, replaced only with --force.
  io::check_output_file(o.bag, io::OutputPolicy{"export --bag", o.overwrite, {o.sequence}});
  bridge::SequenceSource seq(o.sequence);
  const bridge::CameraModel& cam = seq.camera();
  if (std::abs(cam.depth_scale - 0.001) > 1e-12)
    throw Error(o.sequence + "/camera.yaml", "depth_scale " + std::to_string(cam.depth_scale) +
                                                 " m: a ROS 16UC1 depth image is in millimetres (depth_scale 0.001)");
  if (!(o.fps > 0)) throw Error("--fps", "must be > 0");
  BagExportSummary s;
  // Written under a hidden temporary name beside the bag and renamed when complete, like every
  // output (io/files.hpp): an interrupted export leaves no file that looks whole, and no name a
  // user's file could have.
  io::write_atomic_with(o.bag, [&](const fs::path& tmp) {
    with_bag_errors(o.bag, "cannot write the bag", [&] {
      rosbag::Bag bag;
      bag.open(tmp.string(), rosbag::bagmode::Write);
      sensor_msgs::CameraInfo info = info_from_camera(cam);
      for (int i = 0; i < seq.size(); ++i) {
        const bridge::FrameBuffers f = seq.read(i);
        const double t_s = o.start_s + (f.timestamp > 0 ? f.timestamp : i / o.fps);
        const ros::Time t(t_s);
        const std_msgs::Header h = header_at(t, o.topics.frame_id, std::uint32_t(i));
        sensor_msgs::Image depth = image_from_depth(f.depth, cam.width, cam.height);
        depth.header = h;
        info.header = h;
        bag.write(o.topics.depth, t, depth);
        bag.write(o.topics.camera_info, t, info);
        s.messages += 2;
        if (!f.rgb.empty()) {
          sensor_msgs::Image color = image_from_rgb(f.rgb, cam.width, cam.height);
          color.header = h;
          bag.write(o.topics.color, t, color);
          ++s.messages;
          s.color = true;
        }
        if (f.has_camera_position) {
          tf2_msgs::TFMessage tf;
          geometry_msgs::TransformStamped pose;
          pose.header = header_at(t, o.topics.field_frame, std::uint32_t(i));
          pose.child_frame_id = o.topics.frame_id;
          pose.transform.translation.x = f.camera_position[0];
          pose.transform.translation.y = f.camera_position[1];
          pose.transform.translation.z = f.camera_position[2];
          pose.transform.rotation.w = 1;
          tf.transforms.push_back(pose);
          bag.write(o.topics.tf, t, tf);
          ++s.messages;
        }
        ++s.frames;
      }
      bag.close();
      return 0;
    });
  });
  return s;
}

BagImportSummary import_bag_sequence(const BagImportOptions& o) {
  io::check_output_folder(o.out, io::OutputPolicy{"import --bag", o.overwrite, {o.bag}});
  if (!fs::exists(o.bag)) throw Error(o.bag, "no such file");
  if (fs::is_directory(o.bag)) throw Error(o.bag, "is a directory, not a bag file");
  detail::check_bag_file(o.bag);  // rosbag trusts the lengths a bag declares
  return with_bag_errors(o.bag, "not a readable ROS bag", [&] {
    rosbag::Bag bag;
    bag.open(o.bag, rosbag::bagmode::Read);
    // Pass 1: camera info and the depth frames' stamps; colour matched to depth by stamp.
    std::optional<sensor_msgs::CameraInfo> info;
    std::map<ros::Time, sensor_msgs::ImageConstPtr> depth, color;
    std::map<ros::Time, geometry_msgs::Vector3> poses;
    rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{o.topics.depth, o.topics.camera_info,
                                                                       o.topics.color, o.topics.tf}));
    for (const rosbag::MessageInstance& m : view) {
      if (m.getTopic() == o.topics.tf) {
        auto tf = instantiate_checked<tf2_msgs::TFMessage>(m, o.bag);
        if (!tf) throw Error(o.bag, o.topics.tf + " is not tf2_msgs/TFMessage");
        for (const auto& x : tf->transforms)
          if (x.header.frame_id == o.topics.field_frame) poses[x.header.stamp] = x.transform.translation;
      } else if (m.getTopic() == o.topics.camera_info) {
        auto ci = instantiate_checked<sensor_msgs::CameraInfo>(m, o.bag);
        if (!ci) throw Error(o.bag, o.topics.camera_info + " is not sensor_msgs/CameraInfo");
        if (info && (info->width != ci->width || info->height != ci->height || info->K != ci->K || info->D != ci->D))
          throw Error(o.bag, o.topics.camera_info + " changes within the bag (a sequence has one camera)");
        if (!info) info = *ci;
      } else {
        auto im = instantiate_checked<sensor_msgs::Image>(m, o.bag);
        if (!im) throw Error(o.bag, m.getTopic() + " is not sensor_msgs/Image");
        (m.getTopic() == o.topics.depth ? depth : color)[im->header.stamp] = im;
      }
    }
    if (depth.empty()) throw Error(o.bag, "has no message on the depth topic " + o.topics.depth);
    if (!info) throw Error(o.bag, "has no message on the camera info topic " + o.topics.camera_info);
    const bridge::CameraModel cam = camera_from_info(*info, 0.001, o.bag + " " + o.topics.camera_info);
    BagImportSummary s;
    bridge::SequenceSink sink(o.out, cam, o.overwrite);
    std::map<ros::Time, sensor_msgs::ImageConstPtr> matched;
    for (const auto& [t, c] : color) {
      auto it = depth.lower_bound(t - ros::Duration(o.max_skew_s));
      if (it != depth.end() && std::abs((it->first - t).toSec()) <= o.max_skew_s)
        matched[it->first] = c;
      else
        ++s.unmatched_color;
    }
    if (!matched.empty() && matched.size() != depth.size())
      throw Error(o.bag, std::to_string(depth.size() - matched.size()) + " of " + std::to_string(depth.size()) +
                             " depth frames have no colour image within " + std::to_string(o.max_skew_s) +
                             " s (a sequence has colour on every frame or none)");
    int index = 0;
    for (const auto& [t, d] : depth) {
      bridge::FrameBuffers f;
      f.index = index;
      f.timestamp = t.toSec() - o.start_s;
      f.camera = cam;
      f.depth = depth_from_image(*d, cam, o.bag + " " + o.topics.depth);
      if (auto c = matched.find(t); c != matched.end())
        f.rgb = rgb_from_image(*c->second, cam, o.bag + " " + o.topics.color);
      if (!poses.empty()) {
        auto p = poses.find(t);
        if (p == poses.end())
          throw Error(o.bag, o.topics.tf + " has camera poses, but none at the stamp of depth frame " +
                                 std::to_string(index) + " (a sequence has a pose on every frame or none)");
        f.has_camera_position = true;
        f.camera_position[0] = p->second.x;
        f.camera_position[1] = p->second.y;
        f.camera_position[2] = p->second.z;
      }
      sink.write(f);
      ++index;
    }
    sink.finish();
    s.frames = index;
    s.color = !matched.empty();
    return s;
  });
}

}  // namespace cropsight::ros_io
