// SequenceWriter: everything is written into a hidden temporary sibling directory (an
// io::OutputFolder), which finish() puts in place of the final name, so a sequence directory
// either is complete or does not exist (a crashed or abandoned writer leaves no half sequence
// behind), and a folder cropsight did not write is never replaced.

#include <algorithm>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "sequence_text.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

SequenceWriter::SequenceWriter(fs::path dir, CameraIntrinsics camera, bool overwrite)
    : SequenceWriter(std::move(dir), std::move(camera), OutputPolicy{"write sequence", overwrite, {}}) {}

SequenceWriter::SequenceWriter(fs::path dir, CameraIntrinsics camera, const OutputPolicy& policy)
    : dir_(std::move(dir)), camera_(std::move(camera)) {
  if (dir_.filename().empty()) dir_ = dir_.parent_path();  // "out/" -> "out"
  if (dir_.empty()) throw Error("sequence", "empty output directory name");
  camera_.validate(dir_.string() + " (camera)");
  out_ = std::make_unique<OutputFolder>(dir_, policy);  // checks dir_ before anything is written
  tmp_ = out_->path();
  fs::create_directory(tmp_ / "depth");
  write_camera_yaml(tmp_ / "camera.yaml", camera_);
}

SequenceWriter::~SequenceWriter() = default;  // an unfinished writer's OutputFolder removes the temporary

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
  timestamps_.push_back(frame.timestamp);
  ++next_;
}

void SequenceWriter::set_groundtruth(GroundTruth truth) { truth_ = std::move(truth); }
void SequenceWriter::set_geo_origin(const GeoOrigin& origin) {
  origin.validate(dir_.string() + "/" + kGeoOriginFile);
  geo_origin_ = origin;
}

void SequenceWriter::finish() {
  if (finished_) return;
  if (next_ == 0) throw Error(dir_.string(), "no frames written (a sequence needs at least one frame)");
  if (!poses_.empty()) write_file_atomic(tmp_ / "poses.csv", detail::format_poses_csv(poses_));
  // Without poses the frames' times would be lost (poses.csv carries them otherwise); a sequence
  // whose frames all say 0 has no time to keep.
  const bool timed = std::any_of(timestamps_.begin(), timestamps_.end(), [](double t) { return t != 0.0; });
  if (poses_.empty() && timed) write_file_atomic(tmp_ / "timestamps.csv", detail::format_timestamps_csv(timestamps_));
  if (truth_) write_file_atomic(tmp_ / "groundtruth.json", detail::format_groundtruth_json(*truth_, dir_.string()));
  if (geo_origin_) write_file_atomic(tmp_ / kGeoOriginFile, geo_origin_yaml(*geo_origin_));

  out_->commit("sequence");  // a previous sequence is swapped out in one step
  finished_ = true;
}

}  // namespace cropsight::io
