// SequenceReader: validates the layout of a sequence directory when opened (camera.yaml, frame
// numbering, equal frame sets across depth/colour/labels, poses.csv, groundtruth.json) and the
// image contents (bit depth, channels, size) when each frame is read.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cropsight/core/error.hpp"
#include "cropsight/io/files.hpp"
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

// The entries a sequence may hold at its top level (docs/formats.md); detections.json: 2D boxes
// per frame (COCO, image_id = frame), which a grape batch reads when it runs no detector;
// labelled.csv: the labelled frames of a partly labelled sequence.
const char* const kKnownEntries[] = {"camera.yaml",      "depth",           "color",       "labels",
                                     "poses.csv",        "timestamps.csv",  "depth_color", "geo_origin.yaml",
                                     "groundtruth.json", "detections.json", "labelled.csv"};

// Levenshtein distance: the fewest insertions, deletions and substitutions from a to b.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// Visible top-level entries that are no part of the format. A recorder's README or a user's notes
// beside the frames are harmless; a name one or two edits from a known one (groundtruth.jsn,
// pose.csv) is almost surely a misspelling whose content would otherwise be silently unused.
std::vector<fs::path> unknown_entries(const fs::path& dir) {
  std::vector<fs::path> unknown;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    if (std::find(std::begin(kKnownEntries), std::end(kKnownEntries), name) != std::end(kKnownEntries)) continue;
    for (const char* known : kKnownEntries)
      if (edit_distance(name, known) <= 2)
        throw Error(entry.path().string(), std::string("unexpected entry in sequence: did you mean ") + known +
                                               "? (known: camera.yaml, depth/, color/, labels/, poses.csv, "
                                               "timestamps.csv, groundtruth.json, labelled.csv, depth_color/, "
                                               "geo_origin.yaml)");
    unknown.push_back(entry.path());
  }
  std::sort(unknown.begin(), unknown.end());
  return unknown;
}

std::string ignored_notice(const std::vector<fs::path>& ignored) {
  std::string names;
  for (const auto& p : ignored) names += (names.empty() ? "" : ", ") + p.filename().string();
  return "cropsight: notice: " + ignored.front().parent_path().string() + ": ignored " +
         std::to_string(ignored.size()) + " entr" + (ignored.size() == 1 ? "y" : "ies") +
         " that are no part of a sequence (" + names + ")";
}

// labelled.csv: the header "frame", then the labelled frames in increasing order, one a line (a
// partly labelled sequence, as the studio writes it while a user labels frame by frame).
std::vector<int> read_labelled_csv(const fs::path& path, int frames) {
  std::istringstream in(read_file(path));
  std::string line;
  std::vector<int> out;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::string at = "line " + std::to_string(line_no) + ": ";
    if (line_no == 1) {
      if (line != "frame") throw Error(path.string(), at + "expected the header 'frame'");
      continue;
    }
    const bool digits =
        line.size() <= 9 && std::all_of(line.begin(), line.end(), [](char c) { return c >= '0' && c <= '9'; });
    const int f = digits ? std::stoi(line) : -1;
    if (f < 0 || f >= frames)
      throw Error(path.string(),
                  at + "expected a frame number in 0.." + std::to_string(frames - 1) + ", got '" + line + "'");
    if (!out.empty() && f <= out.back()) throw Error(path.string(), at + "frames must be listed in increasing order");
    out.push_back(f);
  }
  if (line_no == 0) throw Error(path.string(), "empty (expected the header 'frame')");
  return out;
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
  if (fs::exists(d / "labelled.csv")) {
    if (!info_.has_labels) throw Error((d / "labelled.csv").string(), "lists labelled frames but there is no labels/");
    info_.labelled_frames = read_labelled_csv(d / "labelled.csv", info_.frames);
    if (list_frames(d / "labels") != info_.labelled_frames)
      throw Error((d / "labels").string(), "holds other frames than labelled.csv lists");
  } else if (info_.has_labels) {
    check_same_frames(d, "labels", info_.frames, "labels");
    for (int i = 0; i < info_.frames; ++i) info_.labelled_frames.push_back(i);
  }

  info_.has_poses = fs::exists(d / "poses.csv");
  if (info_.has_poses) poses_ = detail::read_poses_csv(d / "poses.csv", info_.frames);
  for (const auto& p : poses_) timestamps_.push_back(p.timestamp);
  info_.has_timestamps = fs::exists(d / "timestamps.csv");
  if (info_.has_timestamps) check_timestamps(d / "timestamps.csv");
  info_.has_groundtruth = fs::exists(d / "groundtruth.json");
  if (info_.has_groundtruth) groundtruth_ = detail::read_groundtruth_json(d / "groundtruth.json");
  info_.ignored = unknown_entries(d);
  if (!info_.ignored.empty()) std::cerr << ignored_notice(info_.ignored) << "\n";
}

void SequenceReader::check_timestamps(const fs::path& file) {
  const std::vector<double> t = detail::read_timestamps_csv(file, info_.frames);
  // Two files with one quantity must agree, or a reader would have to guess which one is right.
  for (std::size_t i = 0; i < timestamps_.size(); ++i)
    if (timestamps_[i] != t[i])
      throw Error(file.string(), "frame " + std::to_string(i) + " has timestamp " + std::to_string(t[i]) +
                                     " but poses.csv says " + std::to_string(timestamps_[i]));
  timestamps_ = t;
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
  if (info_.labelled(index)) {
    const fs::path lp = labels_path(index);
    f.labels = read_u16(lp);
    check_size(lp, f.labels.width, f.labels.height, info_.camera);
  }
  if (!timestamps_.empty()) f.timestamp = timestamps_[std::size_t(index)];
  if (info_.has_poses) f.camera_position = poses_[std::size_t(index)].position;
  return f;
}

}  // namespace cropsight::io
