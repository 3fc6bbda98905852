// SequenceReader: validates the layout of a sequence directory when opened (camera.yaml, frame
// numbering, equal frame sets across depth/colour/labels, poses.csv, groundtruth.json) and the
// image contents (bit depth, channels, size) when each frame is read.
#include <algorithm>
#include <cstdio>

#include "cropsight/core/error.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "number_text.hpp"
#include "sequence_text.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

std::string frame_file_name(int index) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%06d.png", index);
  return buf;
}

namespace {

/// Frame numbers of the NNNNNN.png files in `sub`, sorted; any other entry is an error.
std::vector<int> list_frames(const fs::path& sub) {
  std::vector<int> frames;
  std::error_code ec;
  fs::directory_iterator it(sub, ec);
  if (ec) throw Error(sub.string(), "cannot list directory: " + ec.message());
  for (const auto& entry : it) {
    const std::string name = entry.path().filename().string();
    const bool pattern = name.size() == 10 && name.compare(6, 4, ".png") == 0 &&
                         std::all_of(name.begin(), name.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
    if (!pattern || !entry.is_regular_file())
      throw Error(entry.path().string(), "unexpected entry (frames are files named NNNNNN.png, numbered from 0)");
    frames.push_back(std::stoi(name.substr(0, 6)));
  }
  std::sort(frames.begin(), frames.end());
  return frames;
}

/// Checks that `sub` holds exactly frames 0..n-1, where n is the depth frame count.
void check_same_frames(const fs::path& dir, const std::string& sub, int n, const std::string& what) {
  const std::vector<int> frames = list_frames(dir / sub);
  for (int f : frames)
    if (f >= n)
      throw Error((dir / sub / frame_file_name(f)).string(),
                  "extra frame: " + what + " without depth (depth/ has frames 0.." + std::to_string(n - 1) + ")");
  for (int i = 0; i < n; ++i)
    if (!std::binary_search(frames.begin(), frames.end(), i))
      throw Error((dir / sub / frame_file_name(i)).string(),
                  "missing frame: depth/" + frame_file_name(i) + " exists but this " + what + " frame does not");
}

void check_size(const fs::path& path, int w, int h, const CameraIntrinsics& cam) {
  if (w != cam.width || h != cam.height)
    throw Error(path.string(), "image is " + std::to_string(w) + "x" + std::to_string(h) + " but camera.yaml says " +
                                   std::to_string(cam.width) + "x" + std::to_string(cam.height));
}

}  // namespace

SequenceReader::SequenceReader(fs::path dir) {
  info_.dir = std::move(dir);
  const fs::path& d = info_.dir;
  if (!fs::exists(d)) throw Error(d.string(), "sequence directory not found");
  if (!fs::is_directory(d)) throw Error(d.string(), "not a directory (a sequence is a directory)");
  info_.camera = read_camera_yaml(d / "camera.yaml");

  const fs::path depth = d / "depth";
  if (!fs::is_directory(depth)) throw Error(depth.string(), "directory not found (every sequence has depth frames)");
  const std::vector<int> frames = list_frames(depth);
  if (frames.empty()) throw Error(depth.string(), "no frames (expected 000000.png, 000001.png, ...)");
  for (int i = 0; i < int(frames.size()); ++i) {
    if (frames[std::size_t(i)] != i)
      throw Error((depth / frame_file_name(i)).string(),
                  "missing frame (frames are numbered from 0 without gaps; found up to " +
                      frame_file_name(frames.back()) + ")");
  }
  info_.frames = int(frames.size());

  info_.has_color = fs::exists(d / "color");
  if (info_.has_color) check_same_frames(d, "color", info_.frames, "colour");
  info_.has_labels = fs::exists(d / "labels");
  if (info_.has_labels) check_same_frames(d, "labels", info_.frames, "labels");

  info_.has_poses = fs::exists(d / "poses.csv");
  if (info_.has_poses) poses_ = detail::read_poses_csv(d / "poses.csv", info_.frames);
  info_.has_groundtruth = fs::exists(d / "groundtruth.json");
  if (info_.has_groundtruth) groundtruth_ = detail::read_groundtruth_json(d / "groundtruth.json");

  // Anything else at the top level is tolerated only when hidden (editor/OS files); a stray
  // visible entry usually means a misspelt file name, which would otherwise be silently ignored.
  static const char* kKnown[] = {"camera.yaml",      "depth",       "color",          "labels", "poses.csv",
                                 "groundtruth.json", "depth_color", "geo_origin.yaml"};
  for (const auto& entry : fs::directory_iterator(d)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    if (std::find(std::begin(kKnown), std::end(kKnown), name) == std::end(kKnown))
      throw Error(entry.path().string(),
                  "unexpected entry in sequence (known: camera.yaml, depth/, color/, labels/, poses.csv, "
                  "groundtruth.json, depth_color/, geo_origin.yaml)");
  }
}

fs::path SequenceReader::depth_path(int index) const { return info_.dir / "depth" / frame_file_name(index); }
fs::path SequenceReader::color_path(int index) const { return info_.dir / "color" / frame_file_name(index); }
fs::path SequenceReader::labels_path(int index) const { return info_.dir / "labels" / frame_file_name(index); }

RgbdFrame SequenceReader::read(int index) const {
  if (index < 0 || index >= info_.frames)
    throw Error(info_.dir.string(), "frame " + std::to_string(index) + " out of range (sequence has " +
                                        std::to_string(info_.frames) + " frames)");
  RgbdFrame f;
  f.index = index;
  f.camera = info_.camera;
  const fs::path dp = depth_path(index);
  f.depth = read_u16(dp);
  check_size(dp, f.depth.width, f.depth.height, info_.camera);
  if (info_.has_color) {
    const fs::path cp = color_path(index);
    f.color = read_color(cp);
    check_size(cp, f.color.width, f.color.height, info_.camera);
  }
  if (info_.has_labels) {
    const fs::path lp = labels_path(index);
    f.labels = read_u16(lp);
    check_size(lp, f.labels.width, f.labels.height, info_.camera);
  }
  if (info_.has_poses) {
    const CameraPose& p = poses_[std::size_t(index)];
    f.timestamp = p.timestamp;
    f.camera_position = p.position;
  }
  return f;
}

}  // namespace cropsight::io
