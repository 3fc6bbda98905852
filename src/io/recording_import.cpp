// import_recording: a recorder's folders (+ camera files, extrinsics, poses) -> a sequence.
#include "cropsight/io/recording_import.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "cropsight/core/error.hpp"
#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/color_registration.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/pose_track.hpp"
#include "cropsight/io/sequence.hpp"
#include "frame_times_csv.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

bool is_timestamp(const std::string& key) { return key.find('.') != std::string::npos || key.size() >= 10; }

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

DepthImage depth_from_cloud(const OrganizedCloud& c, double scale, const fs::path& file) {
  DepthImage d(c.width, c.height, 0);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const float z = c.z[i];
    if (!std::isfinite(z) || z <= 0) continue;
    const long raw = std::lround(z / scale);
    if (raw > 65535)
      throw Error(file.string(), "depth " + std::to_string(z) + " m does not fit 16 bits at depth_scale");
    d.data[i] = std::uint16_t(raw);
  }
  return d;
}

// Depth, and the colour and labels it carries, of one organised PCD.
void read_pcd_frame(const fs::path& file, const CameraIntrinsics& camera, bool own_color, RgbdFrame& f) {
  const OrganizedCloud c = read_organized_cloud(file);
  if (c.width != camera.width || c.height != camera.height)
    throw Error(file.string(),
                size_text(c.width, c.height) + " cloud, the camera says " + size_text(camera.width, camera.height));
  f.depth = depth_from_cloud(c, camera.depth_scale, file);
  if (c.has_color() && !own_color) {
    f.color = ColorImage(c.width, c.height);
    f.color.data = c.color;
  }
  if (c.has_labels()) {
    f.labels = LabelImage(c.width, c.height);
    f.labels.data = c.labels;
  }
}

// The colour side of an import: where the images are, and how they reach the depth's pixels.
struct ColorSource {
  std::vector<RecordingFile> files;
  std::optional<CameraIntrinsics> camera;  // set when colour is registered
  DepthToColor extrinsics;

  ColorImage frame(std::size_t i, const RgbdFrame& f) const {
    const fs::path& file = files[i].path;
    ColorImage c = read_color(file);
    if (camera) {
      if (c.width != camera->width || c.height != camera->height)
        throw Error(file.string(), "colour image is " + size_text(c.width, c.height) + " but the colour camera says " +
                                       size_text(camera->width, camera->height));
      return register_color(f.depth, f.camera, c, *camera, extrinsics);
    }
    if (c.width != f.camera.width || c.height != f.camera.height)
      throw Error(file.string(), "colour image is " + size_text(c.width, c.height) + ", depth " +
                                     size_text(f.camera.width, f.camera.height) +
                                     ": colour of another size is registered to depth with --color-camera and "
                                     "--extrinsics");
    return c;
  }
};

ColorSource color_source(const ImportOptions& o, const std::vector<RecordingFile>& frames) {
  ColorSource s;
  if (o.color_camera.empty() != o.extrinsics.empty())
    throw Error(o.color_camera.empty() ? "--extrinsics" : "--color-camera",
                "registering colour needs both --color-camera and --extrinsics");
  if (o.color_dir.empty()) {
    if (!o.color_camera.empty()) throw Error("--color-camera", "given without --color");
    return s;
  }
  s.files = list_recording(o.color_dir, {".png", ".jpg", ".jpeg"});
  bool same_keys = s.files.size() == frames.size();
  for (std::size_t i = 0; same_keys && i < frames.size(); ++i) same_keys = s.files[i].value == frames[i].value;
  if (!same_keys && s.files.size() != frames.size())
    throw Error(o.color_dir.string(), std::to_string(s.files.size()) + " colour images for " +
                                          std::to_string(frames.size()) + " depth frames (and their numbers differ)");
  if (!o.color_camera.empty()) {
    s.camera = read_camera_yaml(o.color_camera);
    s.extrinsics = read_extrinsics_yaml(o.extrinsics);
  }
  return s;
}

// Each frame's time on the recording's own clock (what --poses are joined to): a --timestamps
// CSV's, else file-name timestamps in seconds, else index / fps, else nothing.
std::vector<double> clock_times(const ImportOptions& o, const std::vector<RecordingFile>& frames, bool stamps) {
  if (!o.timestamps.empty()) return detail::frame_times_from_csv(o.timestamps, frames);
  std::vector<double> t;
  for (std::size_t i = 0; i < frames.size(); ++i)
    t.push_back(stamps ? frames[i].value / 1000.0 : (o.fps > 0 ? double(i) / o.fps : 0.0));
  return t;
}

std::vector<Eigen::Vector3d> joined_poses(const ImportOptions& o, const std::vector<double>& times, bool timed,
                                          std::string& format, std::optional<GeoOrigin>& geo_origin) {
  if (o.poses.empty()) return {};
  if (!(o.pose_tolerance_s > 0)) throw Error("--pose-tolerance", "must be > 0 seconds");
  if (!timed && times.size() > 1)
    throw Error(o.poses.string(),
                "the frames have no times to join the poses to (give --fps, or files named "
                "by timestamp)");
  const PoseTrack track = read_pose_track(o.poses);
  format = track.format;
  geo_origin = track.geo_origin;
  return join_poses(track, times, o.pose_tolerance_s, o.poses.string());
}

void check_options(const ImportOptions& o) {
  if (o.depth_dir.empty() == o.pcd_dir.empty()) throw Error("import", "give exactly one of --depth and --pcd");
  if (!(o.fps >= 0)) throw Error("--fps", "must be >= 0");
  if (o.fps > 0 && !o.timestamps.empty()) throw Error("--fps", "give --fps or --timestamps, not both");
  if (!(o.depth_scale >= 0) || !std::isfinite(o.depth_scale)) throw Error("--depth-scale", "must be > 0 metres");
}

}  // namespace

// One pass over the frames, each read, checked, registered and written before the next.
ImportSummary import_recording(const ImportOptions& o) {
  // The output first: a bad --out reads no frame.
  const OutputPolicy policy{
      "import",
      o.overwrite,
      {o.depth_dir, o.color_dir, o.pcd_dir, o.camera_yaml, o.color_camera, o.extrinsics, o.poses}};
  check_output_folder(o.out, policy);
  check_options(o);
  CameraIntrinsics camera = read_camera_yaml(o.camera_yaml);
  if (o.depth_scale > 0) camera.depth_scale = o.depth_scale;
  const bool pcd = !o.pcd_dir.empty();
  const auto frames = list_recording(pcd ? o.pcd_dir : o.depth_dir, {pcd ? ".pcd" : ".png"});
  const ColorSource colors = color_source(o, frames);
  const bool csv = !o.timestamps.empty();
  const bool stamps =
      !csv && std::all_of(frames.begin(), frames.end(), [](const RecordingFile& f) { return is_timestamp(f.key); });
  const std::vector<double> clock = clock_times(o, frames, stamps);
  ImportSummary s;
  s.time_source = csv ? "csv" : stamps ? "names" : o.fps > 0 ? "fps" : "none";
  std::optional<GeoOrigin> geo_origin;  // GNSS poses: the sequence is geo-referenced
  const std::vector<Eigen::Vector3d> positions =
      joined_poses(o, clock, csv || stamps || o.fps > 0, s.poses_format, geo_origin);
  SequenceWriter writer(o.out, camera, policy);  // temporary folder, renamed by finish()
  if (geo_origin) writer.set_geo_origin(*geo_origin);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    RgbdFrame f;
    f.index = int(i);
    f.camera = camera;
    // From the first frame in the names' own milliseconds: 1596203844400.5 - 1596203844000.5 is
    // exact, their quotients by 1000 are not.
    f.timestamp = stamps ? (frames[i].value - frames[0].value) / 1000.0 : clock[i] - (csv ? clock[0] : 0.0);
    if (pcd) {
      read_pcd_frame(frames[i].path, camera, !colors.files.empty(), f);
    } else {
      f.depth = read_u16(frames[i].path);  // throws Error(file, ...) unless a 16-bit one-channel PNG
      if (f.depth.width != camera.width || f.depth.height != camera.height)
        throw Error(frames[i].path.string(), size_text(f.depth.width, f.depth.height) +
                                                 " depth image, the camera says " +
                                                 size_text(camera.width, camera.height));
    }
    if (!colors.files.empty()) f.color = colors.frame(i, f);
    if (!positions.empty()) f.camera_position = positions[i];
    s.color = s.color || !f.color.empty();
    s.labels = s.labels || !f.labels.empty();
    writer.write(f);
  }
  writer.finish();
  s.frames = int(frames.size());
  s.color_registered = colors.camera.has_value();
  s.timestamps_from_names = stamps;
  return s;
}

}  // namespace cropsight::io
