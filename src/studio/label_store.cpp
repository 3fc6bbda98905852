// Label images, labelled.csv and groundtruth.json of a sequence labelled in the studio
// (studio/label_store.hpp).
#include "cropsight/studio/label_store.hpp"

#include <algorithm>
#include <limits>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"
#include "io/sequence_text.hpp"  // the format's groundtruth.json reader and writer
#include "studio/head_geometry.hpp"

namespace cropsight::studio {

namespace fs = std::filesystem;

namespace {

// Frames with a NNNNNN.png in labels/ (other names are left to the sequence reader to report).
std::vector<int> frames_in_labels(const fs::path& labels, int frames) {
  std::vector<int> out;
  std::error_code ec;
  if (!fs::is_directory(labels, ec)) return out;
  for (const auto& entry : fs::directory_iterator(labels)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != 10 || name.compare(6, 4, ".png") != 0) continue;
    if (!std::all_of(name.begin(), name.begin() + 6, [](char c) { return c >= '0' && c <= '9'; })) continue;
    const int f = std::stoi(name.substr(0, 6));
    if (f < frames) out.push_back(f);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string labelled_csv(const std::vector<int>& frames) {
  std::string text = "frame\n";
  for (int f : frames) text += std::to_string(f) + "\n";
  return text;
}

// A head's truth from its pixels (head_geometry.hpp); the position is in the camera frame of
// its frame, which the extra keys say.
io::InstanceTruth head_truth(int id, int frame, const HeadPixels& pixels, const DepthImage& depth,
                             const CameraIntrinsics& cam) {
  const HeadGeometry g = head_geometry(pixels, depth, cam);
  io::InstanceTruth t;
  t.id = id;
  t.position = g.centroid;
  t.diameter_mm = g.diameter_mm;
  t.extra["studio_frame"] = frame;
  t.extra["camera_frame_position"] = 1.0;
  return t;
}

}  // namespace

LabelStore::LabelStore(fs::path sequence, const CameraIntrinsics& camera, int frames, bool read_only)
    : dir_(std::move(sequence)), camera_(camera), frames_(frames), read_only_(read_only) {}

bool LabelStore::reconcile(const fs::path& sequence) {
  if (!fs::exists(sequence / "labelled.csv")) return false;
  const std::vector<int> have = frames_in_labels(sequence / "labels", std::numeric_limits<int>::max());
  fs::create_directories(sequence / "labels");
  io::write_file_atomic(sequence / "labelled.csv", labelled_csv(have));
  return true;
}

std::vector<int> LabelStore::labelled() const {
  std::lock_guard lock(mutex_);
  return frames_in_labels(dir_ / "labels", frames_);
}

LabelImage LabelStore::labels(int frame) const {
  std::lock_guard lock(mutex_);
  const fs::path file = dir_ / "labels" / io::frame_file_name(frame);
  if (!fs::exists(file)) return {};
  return io::read_u16(file);
}

void LabelStore::save(int frame, const std::vector<HeadPixels>& heads, const DepthImage& depth) {
  if (read_only_) throw Error(dir_.string(), "opened read-only: labels are not written");
  if (frame < 0 || frame >= frames_) throw Error(dir_.string(), "frame " + std::to_string(frame) + " out of range");
  std::lock_guard lock(mutex_);
  // The list first when the sequence has none yet: a kill after the image's rename then leaves a
  // list that reconcile() repairs, never label images without a list (an invalid sequence).
  if (!fs::exists(dir_ / "labelled.csv"))
    io::write_file_atomic(dir_ / "labelled.csv", labelled_csv(frames_in_labels(dir_ / "labels", frames_)));
  LabelImage image(depth.width, depth.height, 0);
  for (std::size_t k = 0; k < heads.size(); ++k)
    for (int p : heads[k])
      if (p >= 0 && std::size_t(p) < image.size()) image.data[std::size_t(p)] = std::uint16_t(k + 1);
  write_index_files(frame, heads, image, depth);
}

void LabelStore::write_index_files(int frame, const std::vector<HeadPixels>& heads, const LabelImage& local,
                                   const DepthImage& depth) {
  io::GroundTruth truth;
  const fs::path gt = dir_ / "groundtruth.json";
  if (fs::exists(gt)) truth = io::detail::read_groundtruth_json(gt);
  std::erase_if(truth.instances, [&](const io::InstanceTruth& t) {
    const auto it = t.extra.find("studio_frame");
    return it != t.extra.end() && int(it->second) == frame;
  });
  int next_id = 1;
  for (const auto& t : truth.instances) next_id = std::max(next_id, t.id + 1);
  // Local head k+1 becomes sequence-wide id next_id + k; heads drawn over completely are dropped.
  std::vector<int> id_of(heads.size() + 1, 0);
  std::vector<HeadPixels> kept(heads.size() + 1);
  for (std::size_t p = 0; p < local.size(); ++p)
    if (local.data[p] != 0) kept[local.data[p]].push_back(int(p));
  for (std::size_t k = 1; k < kept.size(); ++k) {
    if (kept[k].empty()) continue;
    if (next_id > 65535) throw Error(gt.string(), "more than 65535 labelled heads (label image values)");
    id_of[k] = next_id;
    truth.instances.push_back(head_truth(next_id++, frame, kept[k], depth, camera_));
  }
  LabelImage image = local;
  for (auto& v : image.data) v = std::uint16_t(id_of[v]);
  io::write_u16(dir_ / "labels" / io::frame_file_name(frame), image);
  std::vector<int> frames = frames_in_labels(dir_ / "labels", frames_);
  io::write_file_atomic(dir_ / "labelled.csv", labelled_csv(frames));
  io::write_file_atomic(gt, io::detail::format_groundtruth_json(truth, gt.string()));
}

}  // namespace cropsight::studio
