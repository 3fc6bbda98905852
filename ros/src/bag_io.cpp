#include "cropsight_ros/bag_io.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include "bag_check.hpp"
#include "bridge/frame_conversion.hpp"
#include "cropsight/bridge/sequence_io.hpp"
#include "cropsight/core/error.hpp"
#include "cropsight/io/color_registration.hpp"
#include "cropsight/io/output.hpp"
#include "cropsight/io/pose_track.hpp"
#include "cropsight/io/sequence.hpp"
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

namespace {

// What the first pass over a bag learns: the camera, every depth stamp, the colour stamp matched
// to each depth stamp, and the poses. No image is kept, so memory does not grow with the images.
struct BagIndex {
  std::optional<sensor_msgs::CameraInfo> info;
  std::map<ros::Time, ros::Time> color_of_depth;  // depth stamp -> the colour stamp matched to it
  std::vector<ros::Time> depth_stamps;            // sorted, unique
  std::map<ros::Time, geometry_msgs::Vector3> poses;
  int unmatched_color = 0;
};

void index_message(const rosbag::MessageInstance& m, const BagImportOptions& o, BagIndex& x,
                   std::vector<ros::Time>& color_stamps) {
  if (m.getTopic() == o.topics.tf) {
    auto tf = instantiate_checked<tf2_msgs::TFMessage>(m, o.bag);
    if (!tf) throw Error(o.bag, o.topics.tf + " is not tf2_msgs/TFMessage");
    for (const auto& t : tf->transforms)
      if (t.header.frame_id == o.topics.field_frame) x.poses[t.header.stamp] = t.transform.translation;
  } else if (m.getTopic() == o.topics.camera_info) {
    auto ci = instantiate_checked<sensor_msgs::CameraInfo>(m, o.bag);
    if (!ci) throw Error(o.bag, o.topics.camera_info + " is not sensor_msgs/CameraInfo");
    const auto& info = x.info;
    if (info && (info->width != ci->width || info->height != ci->height || info->K != ci->K || info->D != ci->D))
      throw Error(o.bag, o.topics.camera_info + " changes within the bag (a sequence has one camera)");
    if (!info) x.info = *ci;
  } else {
    // The image is decoded for its header stamp and dropped at once.
    auto im = instantiate_checked<sensor_msgs::Image>(m, o.bag);
    if (!im) throw Error(o.bag, m.getTopic() + " is not sensor_msgs/Image");
    (m.getTopic() == o.topics.depth ? x.depth_stamps : color_stamps).push_back(im->header.stamp);
  }
}

BagIndex index_bag(rosbag::View& view, const BagImportOptions& o) {
  BagIndex x;
  std::vector<ros::Time> color;
  for (const rosbag::MessageInstance& m : view) index_message(m, o, x, color);
  std::sort(x.depth_stamps.begin(), x.depth_stamps.end());
  x.depth_stamps.erase(std::unique(x.depth_stamps.begin(), x.depth_stamps.end()), x.depth_stamps.end());
  if (x.depth_stamps.empty()) throw Error(o.bag, "has no message on the depth topic " + o.topics.depth);
  if (!x.info) throw Error(o.bag, "has no message on the camera info topic " + o.topics.camera_info);
  for (const ros::Time& t : color) {
    const auto& d = x.depth_stamps;
    auto it = std::lower_bound(d.begin(), d.end(), t - ros::Duration(o.max_skew_s));
    if (it != d.end() && std::abs((*it - t).toSec()) <= o.max_skew_s)
      x.color_of_depth[*it] = t;
    else
      ++x.unmatched_color;
  }
  return x;
}

// The second pass: frames complete (depth, and colour when the sequence has it) are written in
// stamp order as soon as they are; what waits is only what a bag's interleaving holds back.
// A colour camera of another size than depth and where it sits (BagImportOptions::color_camera,
// ::extrinsics): each colour image is resampled onto the depth pixels (io::register_color).
struct ColourRegistration {
  CameraIntrinsics color_camera;
  io::DepthToColor extrinsics;
};

std::optional<ColourRegistration> colour_registration(const BagImportOptions& o) {
  if (o.color_camera.empty() != o.extrinsics.empty())
    throw Error(o.color_camera.empty() ? "--extrinsics" : "--color-camera",
                "registering colour needs both --color-camera and --extrinsics");
  if (o.color_camera.empty()) return std::nullopt;
  return ColourRegistration{io::read_camera_yaml(o.color_camera), io::read_extrinsics_yaml(o.extrinsics)};
}

class FrameStream {
 public:
  FrameStream(const BagImportOptions& o, const BagIndex& x, const bridge::CameraModel& cam,
              std::vector<ros::Time> frames, std::vector<Eigen::Vector3d> positions)
      : o_(o),
        x_(x),
        cam_(cam),
        registration_(colour_registration(o)),
        frames_(std::move(frames)),
        positions_(std::move(positions)),
        sink_(o.out, cam, o.overwrite) {
    for (std::size_t i = 0; i < frames_.size(); ++i) index_of_[frames_[i]] = int(i);
  }

  void add(const rosbag::MessageInstance& m) {
    auto im = instantiate_checked<sensor_msgs::Image>(m, o_.bag);
    const bool depth = m.getTopic() == o_.topics.depth;
    ros::Time key = im->header.stamp;
    if (!depth) {  // a colour image belongs to the depth frame it was matched to, if any
      const ros::Duration skew(o_.max_skew_s);
      auto it = x_.color_of_depth.lower_bound(key - skew);
      while (it != x_.color_of_depth.end() && it->first <= key + skew && it->second != key) ++it;
      if (it == x_.color_of_depth.end() || it->second != key) return;
      key = it->first;
    }
    const auto index = index_of_.find(key);
    if (index == index_of_.end() || index->second < next_) return;  // skipped, or a repeated stamp
    Pending& p = pending_[index->second];
    (depth ? p.depth : p.color) = im;
    flush();
  }

  int finish() {
    if (next_ != int(frames_.size()))
      throw Error(o_.bag, "frame " + std::to_string(next_) + " went missing between two reads of the bag");
    sink_.finish();
    return next_;
  }

 private:
  struct Pending {
    sensor_msgs::ImageConstPtr depth, color;
  };

  void flush() {
    const bool with_color = !x_.color_of_depth.empty();
    for (auto it = pending_.find(next_); it != pending_.end() && it->second.depth && (!with_color || it->second.color);
         it = pending_.find(next_)) {
      write(it->second);
      pending_.erase(it);
      ++next_;
    }
  }

  void write(const Pending& p) {
    const ros::Time t = frames_[std::size_t(next_)];
    bridge::FrameBuffers f;
    f.index = next_;
    // From the first frame, as a folder import counts: a robot's bag stamps are Unix times.
    f.timestamp = (t - frames_.front()).toSec();
    f.camera = cam_;
    f.depth = depth_from_image(*p.depth, cam_, o_.bag + " " + o_.topics.depth);
    if (p.color)
      f.rgb =
          registration_ ? registered_rgb(*p.color, f) : rgb_from_image(*p.color, cam_, o_.bag + " " + o_.topics.color);
    if (!positions_.empty()) {
      f.has_camera_position = true;
      for (int c = 0; c < 3; ++c) f.camera_position[c] = positions_[std::size_t(next_)][c];
    } else if (!x_.poses.empty()) {
      auto pose = x_.poses.find(t);
      if (pose == x_.poses.end())
        throw Error(o_.bag, o_.topics.tf + " has camera poses, but none at the stamp of depth frame " +
                                std::to_string(next_) + " (a sequence has a pose on every frame or none)");
      f.has_camera_position = true;
      f.camera_position[0] = pose->second.x;
      f.camera_position[1] = pose->second.y;
      f.camera_position[2] = pose->second.z;
    }
    sink_.write(f);
  }

  // The colour image at its own size, resampled onto this frame's depth pixels.
  std::vector<std::uint8_t> registered_rgb(const sensor_msgs::Image& color, const bridge::FrameBuffers& f) const {
    const CameraIntrinsics& cc = registration_->color_camera;
    const ColorImage colour = bridge::color_from_rgb(
        rgb_from_image(color, bridge::to_camera_model(cc), o_.bag + " " + o_.topics.color), cc.width, cc.height);
    const RgbdFrame depth = bridge::to_rgbd_frame(f);  // f has no colour yet: depth and its camera
    return bridge::rgb_from_color(io::register_color(depth.depth, depth.camera, colour, cc, registration_->extrinsics));
  }

  const BagImportOptions& o_;
  const BagIndex& x_;
  bridge::CameraModel cam_;
  std::optional<ColourRegistration> registration_;
  std::vector<ros::Time> frames_;
  std::vector<Eigen::Vector3d> positions_;  // from --poses, one per frame; empty: /tf's
  std::map<ros::Time, int> index_of_;
  std::map<int, Pending> pending_;
  int next_ = 0;
  bridge::SequenceSink sink_;
};

}  // namespace

BagImportSummary import_bag_sequence(const BagImportOptions& o) {
  io::check_output_folder(o.out, io::OutputPolicy{"import --bag", o.overwrite, {o.bag, o.poses}});
  if (!fs::exists(o.bag)) throw Error(o.bag, "no such file");
  if (fs::is_directory(o.bag)) throw Error(o.bag, "is a directory, not a bag file");
  detail::check_bag_file(o.bag);  // rosbag trusts the lengths a bag declares
  return with_bag_errors(o.bag, "not a readable ROS bag", [&] {
    rosbag::Bag bag;
    bag.open(o.bag, rosbag::bagmode::Read);
    BagImportSummary s;
    BagIndex x;
    {
      rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{o.topics.depth, o.topics.camera_info,
                                                                         o.topics.color, o.topics.tf}));
      x = index_bag(view, o);
    }
    const bridge::CameraModel cam = camera_from_info(*x.info, 0.001, o.bag + " " + o.topics.camera_info);
    // A sequence has colour on every frame or on none: with colour in the bag, a depth frame whose
    // colour image was dropped is skipped and counted, never the reason the import fails.
    std::vector<ros::Time> frames;
    for (const ros::Time& t : x.depth_stamps)
      if (x.color_of_depth.empty() || x.color_of_depth.count(t)) frames.push_back(t);
    s.skipped_without_color = int(x.depth_stamps.size() - frames.size());
    std::vector<Eigen::Vector3d> positions;
    if (!o.poses.empty()) {  // joined to the header stamps, the clock a robot's odometry shares
      if (!(o.pose_tolerance_s > 0)) throw Error("--pose-tolerance", "must be > 0 seconds");
      const io::PoseTrack track = io::read_pose_track(o.poses);
      // The bag's frames are written as they stream; a geo origin would need the sink to carry it.
      if (track.geo_origin)
        throw Error(o.poses,
                    "GNSS poses are joined to folder imports only (a bag's frames stream into the "
                    "sequence, which would then have no geo origin)");
      std::vector<double> times;
      for (const ros::Time& t : frames) times.push_back(t.toSec());
      positions = io::join_poses(track, times, o.pose_tolerance_s, o.poses);
      s.poses_format = track.format;
    }
    FrameStream stream(o, x, cam, std::move(frames), std::move(positions));
    rosbag::View images(bag, rosbag::TopicQuery(std::vector<std::string>{o.topics.depth, o.topics.color}));
    for (const rosbag::MessageInstance& m : images) stream.add(m);
    s.frames = stream.finish();
    s.color = !x.color_of_depth.empty();
    s.unmatched_color = x.unmatched_color;
    return s;
  });
}

}  // namespace cropsight::ros_io
