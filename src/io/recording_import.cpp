#include "cropsight/io/recording_import.hpp"
#include "cropsight/io/file_names.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "cropsight/core/error.hpp"
#include "cropsight/io/cloud_io.hpp"
#include "cropsight/io/image_io.hpp"
#include "cropsight/io/sequence.hpp"

namespace cropsight::io {

namespace fs = std::filesystem;

namespace {

// The last number of a file stem: digits with an optional fractional part ("123", "1596.25").
// The stem of "frame-000123.depth.png" is "frame-000123.depth": its last number is 000123.
bool last_number(const std::string& stem, std::string& key) {
  int end = int(stem.size()) - 1;
  while (end >= 0 && !std::isdigit(static_cast<unsigned char>(stem[std::size_t(end)]))) --end;
  if (end < 0) return false;
  int begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[std::size_t(begin - 1)]))) --begin;
  // A fraction "1596203844123.456": take the integer part before the dot too.
  if (begin >= 2 && stem[std::size_t(begin - 1)] == '.' &&
      std::isdigit(static_cast<unsigned char>(stem[std::size_t(begin - 2)]))) {
    int b2 = begin - 2;
    while (b2 > 0 && std::isdigit(static_cast<unsigned char>(stem[std::size_t(b2 - 1)]))) --b2;
    begin = b2;
  }
  key = stem.substr(std::size_t(begin), std::size_t(end - begin + 1));
  return true;
}

bool is_timestamp(const std::string& key) { return key.find('.') != std::string::npos || key.size() >= 10; }

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
}  // namespace

std::vector<RecordingFile> list_recording(const fs::path& dir, const std::string& ext) {
  if (!fs::is_directory(dir)) throw Error(dir.string(), "not a directory");
  std::vector<RecordingFile> files;
  std::map<std::string, fs::path> seen;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file() || lower_extension(e.path()) != ext) continue;
    RecordingFile f;
    f.path = e.path();
    if (!last_number(e.path().stem().string(), f.key))
      throw Error(f.path.string(), "file name has no frame number (accepted: docs/formats.md, Importing recordings)");
    f.value = std::stod(f.key);
    files.push_back(std::move(f));
  }
  if (files.empty()) throw Error(dir.string(), "no " + ext + " files");
  std::sort(files.begin(), files.end(), [](const RecordingFile& a, const RecordingFile& b) {
    return a.value != b.value ? a.value < b.value : a.path < b.path;
  });
  for (std::size_t i = 1; i < files.size(); ++i)
    if (files[i].value == files[i - 1].value)
      throw Error(files[i].path.string(), "same frame number as " + files[i - 1].path.filename().string());
  return files;
}

ImportSummary import_recording(const ImportOptions& o) {
  // The output first: a bad --out reads no frame.
  const OutputPolicy policy{"import", o.overwrite, {o.depth_dir, o.color_dir, o.pcd_dir, o.camera_yaml}};
  check_output_folder(o.out, policy);
  if (o.depth_dir.empty() == o.pcd_dir.empty()) throw Error("import", "give exactly one of --depth and --pcd");
  if (!(o.fps >= 0)) throw Error("--fps", "must be >= 0");
  const CameraIntrinsics camera = read_camera_yaml(o.camera_yaml);
  const bool pcd = !o.pcd_dir.empty();
  const auto frames = list_recording(pcd ? o.pcd_dir : o.depth_dir, pcd ? ".pcd" : ".png");
  std::vector<RecordingFile> colors;
  if (!o.color_dir.empty()) {
    colors = list_recording(o.color_dir, ".png");
    bool same_keys = colors.size() == frames.size();
    for (std::size_t i = 0; same_keys && i < frames.size(); ++i) same_keys = colors[i].value == frames[i].value;
    if (!same_keys && colors.size() != frames.size())
      throw Error(o.color_dir.string(), std::to_string(colors.size()) + " colour images for " +
                                            std::to_string(frames.size()) + " depth frames (and their numbers differ)");
  }
  const bool stamps =
      std::all_of(frames.begin(), frames.end(), [](const RecordingFile& f) { return is_timestamp(f.key); });
  SequenceWriter writer(o.out, camera, policy);  // temporary folder, renamed by finish()
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const fs::path& file = frames[i].path;
    RgbdFrame f;
    f.index = int(i);
    f.camera = camera;
    f.timestamp = stamps ? (frames[i].value - frames[0].value) / 1000.0 : (o.fps > 0 ? double(i) / o.fps : 0.0);
    if (pcd) {
      const OrganizedCloud c = read_organized_cloud(file);
      if (c.width != camera.width || c.height != camera.height)
        throw Error(file.string(), std::to_string(c.width) + "x" + std::to_string(c.height) +
                                       " cloud, camera.yaml says " + std::to_string(camera.width) + "x" +
                                       std::to_string(camera.height));
      f.depth = depth_from_cloud(c, camera.depth_scale, file);
      if (!c.color.empty() && o.color_dir.empty()) {
        f.color = ColorImage(c.width, c.height);
        f.color.data = c.color;
      }
    } else {
      f.depth = read_u16(file);  // throws Error(file, ...) unless a 16-bit one-channel PNG
      if (f.depth.width != camera.width || f.depth.height != camera.height)
        throw Error(file.string(), std::to_string(f.depth.width) + "x" + std::to_string(f.depth.height) +
                                       " depth image, camera.yaml says " + std::to_string(camera.width) + "x" +
                                       std::to_string(camera.height));
    }
    if (!colors.empty()) {
      f.color = read_color(colors[i].path);
      if (f.color.width != camera.width || f.color.height != camera.height)
        throw Error(colors[i].path.string(),
                    "colour image size differs from the depth's (import needs colour registered to depth)");
    }
    writer.write(f);
  }
  writer.finish();
  ImportSummary s;
  s.frames = int(frames.size());
  s.color = !colors.empty() || (pcd && fs::exists(o.out / "color"));
  s.timestamps_from_names = stamps;
  return s;
}

}  // namespace cropsight::io
