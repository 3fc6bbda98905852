// SequenceWriter: everything is written into a hidden temporary sibling directory, which
// finish() renames onto the final name, so a sequence directory either is complete or does
// not exist (a crashed or abandoned writer leaves no half sequence behind).
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <random>
#include <vector>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "sequence_text.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

fs::path hidden_sibling(const fs::path& dir, const std::string& tag) {
  std::random_device rd;
  const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  return parent / ("." + dir.filename().string() + "." + tag + "-" + std::to_string(::getpid()) + "-" +
                   std::to_string(rd() % 1000000000u));
}

/// Replacing an existing directory is allowed only when it is empty or looks like a sequence,
/// so that a wrong --out never deletes unrelated data.
bool replaceable(const fs::path& dir) {
  if (!fs::is_directory(dir)) return false;
  return fs::is_empty(dir) || fs::exists(dir / "camera.yaml") || fs::exists(dir / "depth");
}

// A run killed by a signal cannot unwind, so its temporary directory stays behind. The next
// writer of the same sequence removes such leftovers: `.NAME.tmp-PID-RANDOM` (or `.old-`) whose
// process no longer exists. A live writer's directory is left alone.
void remove_stale_siblings(const fs::path& dir) {
  const fs::path parent = dir.parent_path().empty() ? fs::path(".") : dir.parent_path();
  const std::string prefix = "." + dir.filename().string() + ".";
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    if (rest.rfind("tmp-", 0) != 0 && rest.rfind("old-", 0) != 0) continue;
    const std::size_t at = 4;  // after "tmp-" / "old-"
    const std::size_t dash = rest.find('-', at);
    if (dash == std::string::npos || dash == at) continue;
    const std::string pid_text = rest.substr(at, dash - at);
    if (!std::all_of(pid_text.begin(), pid_text.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
    const long pid = std::strtol(pid_text.c_str(), nullptr, 10);
    if (pid <= 0 || pid == long(::getpid())) continue;
    if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
    stale.push_back(e.path());
  }
  for (const auto& p : stale) fs::remove_all(p, ec);
}

}  // namespace

SequenceWriter::SequenceWriter(fs::path dir, CameraIntrinsics camera, bool overwrite)
    : dir_(std::move(dir)), camera_(std::move(camera)), overwrite_(overwrite) {
  if (dir_.filename().empty()) dir_ = dir_.parent_path();  // "out/" -> "out"
  if (dir_.empty()) throw Error("sequence", "empty output directory name");
  camera_.validate(dir_.string() + " (camera)");
  if (fs::exists(dir_)) {
    if (!overwrite_) throw Error(dir_.string(), "already exists (refusing to overwrite)");
    if (!replaceable(dir_))
      throw Error(dir_.string(), "exists and is not a sequence directory; refusing to replace it");
  }
  std::error_code ec;
  if (!dir_.parent_path().empty()) {
    fs::create_directories(dir_.parent_path(), ec);
    if (ec) throw Error(dir_.string(), "cannot create parent directory: " + ec.message());
  }
  remove_stale_siblings(dir_);
  tmp_ = hidden_sibling(dir_, "tmp");
  fs::create_directory(tmp_, ec);
  if (ec) throw Error(dir_.string(), "cannot create temporary directory: " + ec.message());
  try {
    fs::create_directory(tmp_ / "depth");
    write_camera_yaml(tmp_ / "camera.yaml", camera_);
  } catch (...) {
    fs::remove_all(tmp_, ec);
    throw;
  }
}

SequenceWriter::~SequenceWriter() {
  if (!finished_) {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
  }
}

void SequenceWriter::write(const RgbdFrame& frame) {
  const std::string where = dir_.string() + " (frame " + std::to_string(next_) + ")";
  if (finished_) throw Error(where, "writer already finished");
  if (frame.index != next_)
    throw Error(where, "frames must be written in order; got frame index " + std::to_string(frame.index));
  auto check = [&](int w, int h, const char* what) {
    if (w != camera_.width || h != camera_.height)
      throw Error(where, std::string(what) + " image is " + std::to_string(w) + "x" + std::to_string(h) +
                             " but the camera is " + std::to_string(camera_.width) + "x" +
                             std::to_string(camera_.height));
  };
  check(frame.depth.width, frame.depth.height, "depth");
  const bool has_color = !frame.color.empty(), has_labels = !frame.labels.empty();
  const bool has_pose = frame.camera_position.has_value();
  if (next_ == 0) {
    color_ = has_color;
    labels_ = has_labels;
    if (color_) fs::create_directory(tmp_ / "color");
    if (labels_) fs::create_directory(tmp_ / "labels");
  } else {
    if (has_color != color_) throw Error(where, "colour present in some frames but not in others");
    if (has_labels != labels_) throw Error(where, "labels present in some frames but not in others");
    if (has_pose != !poses_.empty()) throw Error(where, "camera position present in some frames but not in others");
  }
  if (has_color) check(frame.color.width, frame.color.height, "colour");
  if (has_labels) check(frame.labels.width, frame.labels.height, "labels");

  const std::string name = frame_file_name(next_);
  write_u16(tmp_ / "depth" / name, frame.depth);
  if (has_color) write_color(tmp_ / "color" / name, frame.color);
  if (has_labels) write_u16(tmp_ / "labels" / name, frame.labels);
  if (has_pose) poses_.push_back(CameraPose{next_, frame.timestamp, *frame.camera_position});
  ++next_;
}

void SequenceWriter::set_groundtruth(GroundTruth truth) { truth_ = std::move(truth); }

void SequenceWriter::finish() {
  if (finished_) return;
  if (next_ == 0) throw Error(dir_.string(), "no frames written (a sequence needs at least one frame)");
  if (!poses_.empty()) write_file_atomic(tmp_ / "poses.csv", detail::format_poses_csv(poses_));
  if (truth_) write_file_atomic(tmp_ / "groundtruth.json", detail::format_groundtruth_json(*truth_, dir_.string()));

  std::error_code ec;
  fs::path old;
  if (fs::exists(dir_)) {
    if (!overwrite_) throw Error(dir_.string(), "already exists (refusing to overwrite)");
    if (!replaceable(dir_))
      throw Error(dir_.string(), "exists and is not a sequence directory; refusing to replace it");
    // Move the old sequence aside first: rename() cannot replace a non-empty directory.
    old = hidden_sibling(dir_, "old");
    fs::rename(dir_, old, ec);
    if (ec) throw Error(dir_.string(), "cannot replace existing directory: " + ec.message());
  }
  fs::rename(tmp_, dir_, ec);
  if (ec) {
    std::error_code ec2;
    if (!old.empty()) fs::rename(old, dir_, ec2);  // put the previous sequence back
    throw Error(dir_.string(), "cannot move the finished sequence into place: " + ec.message());
  }
  finished_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace cropsight::io
